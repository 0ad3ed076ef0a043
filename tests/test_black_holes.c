// SPDX-License-Identifier: MIT
/* Black holes in whole renders (cl/stages/integrate_geodesic.cl) and in the scene file
 * (host/scene/black_holes.c): the shadow's radius against the capture condition, scenes without
 * holes unchanged to the bit, and bad input as one-line errors naming the key. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "support.h"

#define PI 3.14159265358979323846

/* A scene in a fresh folder: one small triangle far behind the camera (a scene needs a
 * triangle), a white background, and `extra` JSON members. Returns the scene file's path. */
static const char *write_scene(const char *camera, const char *extra)
{
    const char *dir = test_temp_dir();
    test_write_file(dir, "tri.obj", "v -1 -1 900\nv 1 -1 900\nv 0 1 900\nf 1 2 3\n");
    char json[2048];
    snprintf(json, sizeof json,
             "{\"camera\": %s, \"film\": {\"width\": 512, \"height\": 512},"
             " \"render\": {\"spp\": 1, \"max_depth\": 1}, \"background\": [1, 1, 1],"
             " \"objects\": [{\"obj\": \"tri.obj\"}]%s}",
             camera, extra);
    return test_write_file(dir, "scene.json", json);
}

/* The angular radius of the shadow seen from distance D: rays at angle alpha to the hole's
 * direction have impact parameter b = D sin(alpha) / sqrt(1 - 2M/D) and fall in when
 * 1/(D sin alpha)^2 - 2M/D^3 > 1/(27 M^2), i.e. b < 3 sqrt(3) M. */
static double shadow_angle(double M, double D)
{
    return asin(1.0 / (D * sqrt(1.0 / (27.0 * M * M) + 2.0 * M / (D * D * D))));
}

/* The shadow's radius in pixels at 512^2 for a hole of mass M at the origin, camera on +z at D. */
static void check_shadow(double M, double D, double fov_y)
{
    char camera[256], holes[256];
    snprintf(camera, sizeof camera, "{\"eye\": [0, 0, %.9g], \"target\": [0, 0, 0], \"fov_y\": %.9g}", D,
             fov_y);
    snprintf(holes, sizeof holes, ", \"black_holes\": [{\"position\": [0, 0, 0], \"mass\": %.9g}]", M);
    RenderFixture f;
    render_fixture_open(&f, write_scene(camera, holes), 0, 0);
    RenderSettings s = {.spp = 1, .max_depth = 1, .seed = 1};
    float *rgb = render_fixture_render(&f, s, NULL);
    int w = f.scene.desc.width, h = f.scene.desc.height;
    /* Each pixel is 1 (escaped to the white background) or 0 (captured) at 1 spp: the black area
     * in pixels, and the radius of the disc of that area. */
    double black = 0.0;
    for (int i = 0; i < w * h; i++)
        black += 1.0 - fmin(fmax(rgb[3 * i + 1], 0.0f), 1.0f);
    double radius = sqrt(black / PI);
    double expected = tan(shadow_angle(M, D)) / tan(0.5 * fov_y * PI / 180.0) * 0.5 * h;
    cr_log_info("M %g, D %g: shadow radius %.3f px, expected %.3f px", M, D, radius, expected);
    cr_expect(fabs(radius - expected) <= 0.5, "M %g, camera at %g: shadow radius %.3f px, expected %.3f px",
              M, D, radius, expected);
    free(rgb);
    render_fixture_close(&f);
}

/* Two distances: near (the shadow spans 30 degrees) and far (10 degrees); each fills about half
 * the film's height, so a half-pixel error is 0.3% of the radius. */
Test(black_holes, shadow_radius_matches_capture_condition, .timeout = 1800)
{
    check_shadow(1.0, 10.0, 2.0 * shadow_angle(1.0, 10.0) * 180.0 / PI / 0.55);
    check_shadow(2.0, 60.0, 2.0 * shadow_angle(2.0, 60.0) * 180.0 / PI / 0.55);
}

/* No key, an empty array and a hole of mass 0 render the same bits. */
Test(black_holes, massless_hole_changes_nothing, .timeout = 600)
{
    const char *camera = "{\"eye\": [0, 0, -20], \"target\": [0, 0, 900], \"fov_y\": 5}";
    const char *variants[] = {"", ", \"black_holes\": []",
                              ", \"black_holes\": [{\"position\": [0, 0, 400], \"mass\": 0,"
                              " \"disk\": {\"outer_radius\": 30}}]"};
    float *first = NULL;
    for (int v = 0; v < 3; v++) {
        RenderFixture f;
        render_fixture_open(&f, write_scene(camera, variants[v]), 64, 64);
        cr_assert_eq(f.scene.desc.num_black_holes, 0);
        RenderSettings s = {.spp = 4, .max_depth = 3, .seed = 7};
        float *rgb = render_fixture_render(&f, s, NULL);
        if (v == 0)
            first = rgb;
        else {
            cr_expect(memcmp(first, rgb, 64 * 64 * 3 * sizeof *rgb) == 0, "variant %d differs", v);
            free(rgb);
        }
        render_fixture_close(&f);
    }
    free(first);
}

/* A hole of negligible mass (1e-5: it bends the rays through the box by about 1e-5 rad) whose
 * influence sphere holds the whole Cornell box and the camera: every segment goes through
 * integrate_geodesic's chords and write-back, and the lit, shaded picture (NEE, MIS on the
 * lamp, diffuse bounces) must stay the one without it: the same energy to 0.5%, every pixel
 * within a small difference on average. A lost pdf, a wrong hit or a dropped path shows. */
Test(black_holes, weak_hole_leaves_a_lit_scene_unchanged, .timeout = 1800)
{
    char cwd[1024], obj[1100], json[2048];
    cr_assert(getcwd(cwd, sizeof cwd));
    snprintf(obj, sizeof obj, "%s/scenes/cornell-box/CornellBox-Original.obj", cwd);
    const char *dir = test_temp_dir();
    float *rgb[2];
    for (int v = 0; v < 2; v++) {
        snprintf(json, sizeof json,
                 "{\"camera\": {\"eye\": [0, 1, 3.9], \"target\": [0, 1, 0], \"fov_y\": 39.3},"
                 " \"film\": {\"width\": 48, \"height\": 48}, \"render\": {\"spp\": 16, \"max_depth\": 4},"
                 " \"objects\": [{\"obj\": \"%s\"}]%s}",
                 obj, v ? ", \"black_holes\": [{\"position\": [0.1, 1.1, 0.2], \"mass\": 1e-5,"
                          " \"influence_radius\": 10}]" : "");
        RenderFixture f;
        render_fixture_open(&f, test_write_file(dir, v ? "hole.json" : "plain.json", json), 0, 0);
        cr_assert_eq(f.scene.desc.num_black_holes, v);
        RenderSettings s = {.spp = 16, .max_depth = 4, .seed = 3};
        rgb[v] = render_fixture_render(&f, s, NULL);
        render_fixture_close(&f);
    }
    double sum[2] = {0, 0}, diff = 0.0;
    int n = 48 * 48 * 3;
    for (int i = 0; i < n; i++)
        sum[0] += rgb[0][i], sum[1] += rgb[1][i], diff += fabs(rgb[0][i] - rgb[1][i]);
    cr_log_info("energy %.4f vs %.4f, mean |difference| %.5f of the mean", sum[1], sum[0], diff / sum[0]);
    cr_expect(fabs(sum[1] / sum[0] - 1.0) < 5e-3, "energy %.5f with the hole, %.5f without", sum[1], sum[0]);
    cr_expect(diff / sum[0] < 0.02, "pixels differ by %.4f of the mean on average", diff / sum[0]);
    free(rgb[0]), free(rgb[1]);
}

/* ---- Bad input -------------------------------------------------------------------------------- */

/* Loading the scene with `holes` (and camera eye at [0, 0, 50]) fails with one line naming key. */
static void expect_error(const char *holes, const char *key, const char *eye)
{
    char camera[160], extra[1024];
    snprintf(camera, sizeof camera, "{\"eye\": %s, \"target\": [0, 0, 0]}", eye ? eye : "[0, 0, 50]");
    snprintf(extra, sizeof extra, ", \"black_holes\": %s", holes);
    SceneDesc d;
    Error err = {0};
    bool ok = scene_desc_load(write_scene(camera, extra), &d, &err);
    if (ok)
        scene_desc_free(&d);
    cr_expect(!ok, "%s was accepted", holes);
    cr_expect(strstr(err.message, key) != NULL, "the error \"%s\" does not name %s", err.message, key);
    cr_expect(strchr(err.message, '\n') == NULL, "the error is not one line: %s", err.message);
}

Test(black_holes, bad_input_is_one_line_naming_the_key)
{
    expect_error("[{\"position\": [0, 0, 0], \"mass\": -1}]", "black_holes[0].mass", NULL);
    expect_error("[{\"position\": [0, 0, 0], \"mass\": 1e999}]", "black_holes[0].mass", NULL);
    expect_error("[{\"position\": [0, 0, 0]}]", "black_holes[0].mass", NULL);
    expect_error("[{\"position\": [0, 0], \"mass\": 1}]", "black_holes[0].position", NULL);
    expect_error("[{\"position\": [0, 0, 0], \"mass\": 1, \"disk\": {\"inner_radius\": 8, "
                 "\"outer_radius\": 8}}]",
                 "black_holes[0].disk.inner_radius", NULL);
    expect_error("[{\"position\": [0, 0, 0], \"mass\": 1, \"disk\": {\"inner_radius\": 1.5, "
                 "\"outer_radius\": 8}}]",
                 "black_holes[0].disk.inner_radius", NULL);
    expect_error("[{\"position\": [0, 0, 0], \"mass\": 1, \"disk\": {}}]",
                 "black_holes[0].disk.outer_radius", NULL);
    expect_error("[{\"position\": [0, 0, 0], \"mass\": 1, \"disk\": {\"outer_radius\": 9, "
                 "\"noise\": {\"octaves\": 2.5}}}]",
                 "black_holes[0].disk.noise.octaves", NULL);
    expect_error("[{\"position\": [0, 0, 0], \"mass\": 1, \"influence_radius\": 2}]",
                 "black_holes[0].influence_radius", NULL);
    expect_error("[{\"position\": [0, 0, 0], \"mass\": 1, \"spin\": 0.5}]", "spin", NULL);
    expect_error("[{\"position\": [0, 0, 0], \"mass\": 1}]", "camera.eye", "[1.5, 0, 0]");
    expect_error("[{\"position\": [0, 0, 0], \"mass\": 1}, {\"position\": [5, 0, 0], \"mass\": 1}]",
                 "black_holes[1].position", NULL);
    expect_error("[{\"position\": [0, 0, 0], \"mass\": 1, \"disk\": {\"outer_radius\": 20}},"
                 " {\"position\": [22, 0, 0], \"mass\": 1}]",
                 "black_holes[1].position", NULL);
    expect_error("{\"mass\": 1}", "black_holes", NULL);
}

/* The pt binary: exit status 1 and one "pt: ..." line on stderr. */
Test(black_holes, pt_exits_non_zero_on_a_camera_inside_a_horizon)
{
    const char *scene = write_scene("{\"eye\": [0, 0, 1], \"target\": [0, 0, -1]}",
                                    ", \"black_holes\": [{\"position\": [0, 0, 0], \"mass\": 1}]");
    char cmd[2048];
    snprintf(cmd, sizeof cmd, "%s render %s -o /dev/null 2>&1", test_pt_bin(), scene);
    FILE *p = popen(cmd, "r");
    cr_assert(p);
    char out[4096] = {0};
    size_t n = fread(out, 1, sizeof out - 1, p);
    int status = pclose(p);
    out[n] = '\0';
    cr_expect(status != 0, "pt exited 0: %s", out);
    cr_expect(strstr(out, "camera.eye") && strstr(out, "horizon"), "output: %s", out);
    cr_expect(strchr(out, '\n') == out + n - 1, "not one line: %s", out);
}

/* Every value reaching the geodesic integrator is finite and bounded (issue 42): a hole at 3e38, a
 * mass whose influence radius overflows when squared, a huge influence_radius or disk radius are
 * refused naming the key (they used to give inf and NaN in the integrator: a hang, black pixels). */
Test(black_holes, lengths_the_integrator_cannot_square_are_refused)
{
    expect_error("[{\"position\": [3e38, 0, 0], \"mass\": 1}]", "black_holes[0].position", NULL);
    expect_error("[{\"position\": [0, -2e18, 0], \"mass\": 1}]", "black_holes[0].position", NULL);
    expect_error("[{\"position\": [0, 0, 0], \"mass\": 1e30}]", "black_holes[0].mass", NULL);
    expect_error("[{\"position\": [0, 0, 0], \"mass\": 1, \"influence_radius\": 1e30}]",
                 "black_holes[0].influence_radius", NULL);
    expect_error("[{\"position\": [0, 0, 0], \"mass\": 1, \"disk\": {\"outer_radius\": 1e30}}]",
                 "black_holes[0].disk.outer_radius", NULL);
}
