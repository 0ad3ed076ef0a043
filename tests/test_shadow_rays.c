// SPDX-License-Identifier: MIT
/* Next-event shadow rays reach the light: an occluder that sits just in front of an emitter (a
 * lamp shade, a recessed fixture) blocks it completely, however far the shaded point is. A shadow
 * ray that stops short of the light by a fraction of its length lets light leak past it. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "support.h"

#define LIGHT_HEIGHT 50.0 /* the floor at y = 0 is this far below the light */
#define GAP 1e-3          /* between the emitter and the occluder just below it */
#define FILM 32

/* Writes the quad (x0..x1, y, z0..z1) as two triangles facing down (-y) or up. */
static void write_quad(FILE *out, int *next_vertex, double x0, double x1, double y, double z0,
                       double z1, int facing_down)
{
    fprintf(out, "v %.9g %.9g %.9g\nv %.9g %.9g %.9g\nv %.9g %.9g %.9g\nv %.9g %.9g %.9g\n", x0, y, z0,
            x1, y, z0, x1, y, z1, x0, y, z1);
    int a = *next_vertex, b = a + 1, c = a + 2, d = a + 3;
    *next_vertex += 4;
    /* (b - a) x (c - a) points to -y. */
    if (facing_down)
        fprintf(out, "f %d %d %d\nf %d %d %d\n", a, b, c, a, c, d);
    else
        fprintf(out, "f %d %d %d\nf %d %d %d\n", a, c, b, a, d, c);
}

/* A white floor under a 1 x 1 emitter (facing down) at LIGHT_HEIGHT, seen from below the light;
 * with an occluder, a 2 x 2 grey quad GAP under the emitter. Returns the scene.json path. */
static const char *write_lamp_scene(const char *dir, int with_occluder)
{
    static char path[512];
    char file[512];
    snprintf(file, sizeof file, "%s/lamp.mtl", dir);
    FILE *f = fopen(file, "w");
    cr_assert(f, "cannot write %s", file);
    fprintf(f, "newmtl floor\nKd 0.8 0.8 0.8\n\nnewmtl shade\nKd 0.5 0.5 0.5\n\n"
               "newmtl lamp\nKd 0 0 0\nKe 1000 1000 1000\n");
    fclose(f);
    snprintf(file, sizeof file, "%s/lamp.obj", dir);
    f = fopen(file, "w");
    cr_assert(f, "cannot write %s", file);
    int next = 1;
    fprintf(f, "mtllib lamp.mtl\nusemtl floor\n");
    write_quad(f, &next, -100, 100, 0, -100, 100, 0);
    fprintf(f, "usemtl lamp\n");
    write_quad(f, &next, -0.5, 0.5, LIGHT_HEIGHT, -0.5, 0.5, 1);
    if (with_occluder) {
        fprintf(f, "usemtl shade\n");
        write_quad(f, &next, -1, 1, LIGHT_HEIGHT - GAP, -1, 1, 1);
    }
    fclose(f);
    snprintf(path, sizeof path, "%s/scene.json", dir);
    f = fopen(path, "w");
    cr_assert(f, "cannot write %s", path);
    /* The camera looks straight down from y = 10 (so it never sees the lamp): it sees the floor
     * from x, z = -3.6 to 3.6, where the lamp's light arrives within 5 degrees of vertical. */
    fprintf(f, "{\"camera\": {\"eye\": [0, 10, 0], \"target\": [0, 0, 0], \"up\": [0, 0, -1], "
               "\"fov_y\": 40}, \"objects\": [{\"obj\": \"lamp.obj\"}], \"background\": [0, 0, 0]}\n");
    fclose(f);
    return path;
}

/* The floor's radiance: direct light only (max_depth 2: the camera ray's hit and one more
 * segment), so a bounce off the shade, which emits nothing, adds nothing either. */
static float *render_floor(const char *scene_path)
{
    RenderFixture f;
    render_fixture_open(&f, scene_path, FILM, FILM);
    float *rgb = render_fixture_render(&f, (RenderSettings){.spp = 16, .max_depth = 2, .seed = 5}, NULL);
    render_fixture_close(&f);
    return rgb;
}

Test(shadow_rays, an_occluder_just_below_a_far_light_blocks_it_completely, .timeout = 120)
{
    const char *dir = test_temp_dir();
    float *lit = render_floor(write_lamp_scene(dir, 0));
    /* Without the shade: E = Le * A * cos^2 / d^2 ~ 1000 / 2500 directly below the lamp, radiance
     * 0.8 / pi of that. */
    double lit_mean = 0.0;
    int dark = 0; /* a shadow ray blocked by the lamp's own triangle */
    for (int i = 0; i < FILM * FILM * 3; i++) {
        lit_mean += lit[i];
        dark += !(lit[i] > 0.0f);
    }
    cr_expect_eq(dark, 0, "%d of %d values of the unshaded floor are dark", dark, FILM * FILM * 3);
    lit_mean /= FILM * FILM * 3;
    double expected = 0.8 / 3.14159265358979 * 1000.0 / (LIGHT_HEIGHT * LIGHT_HEIGHT);
    cr_expect(lit_mean > 0.8 * expected && lit_mean < 1.05 * expected,
              "unshaded floor: mean radiance %g, expected about %g", lit_mean, expected);

    dir = test_temp_dir();
    float *shaded = render_floor(write_lamp_scene(dir, 1));
    int leaking = 0;
    double max_leak = 0.0;
    for (int i = 0; i < FILM * FILM * 3; i++)
        if (shaded[i] != 0.0f) {
            leaking++;
            max_leak = fmax(max_leak, shaded[i]);
        }
    cr_expect_eq(leaking, 0,
                 "%d of %d floor values receive light through a shade %g below the lamp (max %g)",
                 leaking, FILM * FILM * 3, GAP, max_leak);
    free(lit);
    free(shaded);
}
