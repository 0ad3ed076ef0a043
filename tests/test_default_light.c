// SPDX-License-Identifier: MIT
/* A scene without any light (a bare OBJ without Ke: no emissive triangles, no "lights", no
 * environment, black background) renders under a uniform white sky with one warning naming what
 * is missing; --no-default-light leaves it black without the warning. A lit scene gets neither. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "io/image_io.h"
#include "support.h"

typedef struct {
    int exit_code;
    char err[8192];
    double mean; /* of the written image, -1 when none */
} Rendered;

static Rendered render_cli(const char *dir, const char *scene, const char *flags)
{
    Rendered r = {.mean = -1.0};
    char cmd[4096], exr[1024], err_path[1024];
    snprintf(exr, sizeof exr, "%s/out.exr", dir);
    snprintf(err_path, sizeof err_path, "%s/stderr.txt", dir);
    unlink(exr);
    snprintf(cmd, sizeof cmd, "'%s' render '%s' --spp 2 --width 8 --height 8 --quiet -o '%s' %s 2>'%s' >/dev/null",
             test_pt_bin(), scene, exr, flags, err_path);
    int status = system(cmd);
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    char *text = test_read_file(err_path, NULL);
    snprintf(r.err, sizeof r.err, "%s", text ? text : "");
    free(text);
    float *rgb;
    int w, h;
    Error err = {0};
    if (image_read_exr(exr, &rgb, &w, &h, &err)) {
        double sum = 0.0;
        for (int k = 0; k < w * h * 3; k++)
            sum += rgb[k];
        r.mean = sum / (w * h * 3);
        free(rgb);
    }
    return r;
}

static int count(const char *text, const char *needle)
{
    int n = 0;
    for (const char *s = strstr(text, needle); s; s = strstr(s + 1, needle))
        n++;
    return n;
}

static const char *bare_obj(const char *dir)
{
    return test_write_file(dir, "bare.obj", "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3\nf 1 3 4\n");
}

Test(default_light, unlit_scene_gets_a_white_sky_and_one_warning, .timeout = 120)
{
    const char *dir = test_temp_dir();
    Rendered r = render_cli(dir, bare_obj(dir), "");
    cr_assert_eq(r.exit_code, 0, "exit %d: %s", r.exit_code, r.err);
    cr_expect(r.mean > 0.05, "the image is black (mean %g)", r.mean);
    cr_expect_eq(count(r.err, "pt: warning:"), 1, "stderr: %s", r.err);
    cr_expect(strstr(r.err, "no emissive triangles") && strstr(r.err, "no \"lights\"") &&
                  strstr(r.err, "no environment map") && strstr(r.err, "bare.obj") &&
                  strstr(r.err, "--no-default-light"),
              "the warning does not name what is missing: %s", r.err);
}

Test(default_light, no_default_light_keeps_it_black, .timeout = 120)
{
    const char *dir = test_temp_dir();
    Rendered r = render_cli(dir, bare_obj(dir), "--no-default-light");
    cr_assert_eq(r.exit_code, 0, "exit %d: %s", r.exit_code, r.err);
    cr_expect(r.mean == 0.0, "mean %g, not black", r.mean);
    cr_expect(!strstr(r.err, "warning"), "stderr: %s", r.err);
}

/* A point light is a light: no warning, and no sky behind the plane (most of the image sees past
 * the plane: white under the default sky, a mean near 0.9; black here, the lit plane's mean ~0.02). */
Test(default_light, lit_scene_gets_no_default, .timeout = 120)
{
    const char *dir = test_temp_dir();
    bare_obj(dir);
    const char *scene = test_write_file(dir, "scene.json",
                                        "{\"camera\": {\"eye\": [0, 0, 3], \"target\": [0, 0, 0], \"fov_y\": 90},"
                                        " \"objects\": [{\"obj\": \"bare.obj\"}],"
                                        " \"lights\": [{\"type\": \"point\", \"position\": [0, 0, 1], \"intensity\": 1}]}");
    Rendered r = render_cli(dir, scene, "");
    cr_assert_eq(r.exit_code, 0, "exit %d: %s", r.exit_code, r.err);
    cr_expect(!strstr(r.err, "warning"), "stderr: %s", r.err);
    cr_expect(r.mean > 0.0 && r.mean < 0.2, "mean %g: the plane lit by the point light alone", r.mean);
}
