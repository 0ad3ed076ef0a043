// SPDX-License-Identifier: MIT
/* The environment map's orientation (shared/DESIGN.md "Environment") on a map generated here: the
 * lat-long mapping and the rotation sense, through the EXR and the HDR readers (and, when ../shared
 * is there, on OpenEXR's OrientationLatLong.exr as well). Sampling:
 * test_environment_sampling.c; unbiasedness: test_environment_unbiased.c; bad input:
 * test_environment_input.c. */
#include <stb_image_write.h>

#include "environment_maps.h"
#include <unistd.h>

#include "io/image_io.h"

/* A speck far below, out of every view: the scene needs an object. */
static const char *write_speck(const char *dir)
{
    return test_write_file(dir, "speck.obj", "v 50 -50 50\nv 50.01 -50 50\nv 50 -50 50.01\nf 1 2 3\n");
}

/* Looking along each axis from the origin, the image centre shows the colour DESIGN's mapping
 * predicts; rotation 90 turns the map like an object rotated 90 degrees counter-clockwise seen
 * from +y: what was at -z is now at -x, +x moves to -z, +z to +x, -x to +z. */
Test(environment, orientation_and_rotation_follow_design, .timeout = 120)
{
    const char *dir = test_temp_dir();
    int w = 64, h = 32;
    float *rgb = axis_map(w, h);
    char exr[512], hdr[512];
    snprintf(exr, sizeof exr, "%s/axes.exr", dir);
    snprintf(hdr, sizeof hdr, "%s/axes.hdr", dir);
    Error err = {0};
    cr_assert(image_write_exr(exr, rgb, w, h, &err), "%s", err.message);
    cr_assert(stbi_write_hdr(hdr, w, h, 3, rgb));
    free(rgb);
    write_speck(dir);
    const char *camera = "{\"eye\": [0, 0, 0], \"target\": [0, 0, -1], \"fov_y\": 4}";
    const char *objects = "[{\"obj\": \"speck.obj\"}]";
    /* view direction, up, expected axis colour at rotation 0 and at rotation 90 */
    static const struct {
        float look[3], up[3];
        int at_0, at_90;
    } views[] = {
        {{0, 0, -1}, {0, 1, 0}, 0, 1}, {{1, 0, 0}, {0, 1, 0}, 1, 3}, {{-1, 0, 0}, {0, 1, 0}, 2, 0},
        {{0, 0, 1}, {0, 1, 0}, 3, 2},  {{0, 1, 0}, {0, 0, -1}, 4, 4}, {{0, -1, 0}, {0, 0, -1}, 5, 5},
    };
    for (int rotated = 0; rotated < 2; rotated++) {
        /* The EXR reader at rotation 0, the HDR reader (stb) at 90. */
        const char *scene = write_scene(dir, rotated ? "rotated.json" : "plain.json", objects,
                                        rotated ? "axes.hdr" : "axes.exr", rotated ? 90.0f : 0.0f,
                                        camera);
        RenderFixture f;
        render_fixture_open(&f, scene, 9, 9);
        for (size_t v = 0; v < sizeof views / sizeof views[0]; v++) {
            CameraDesc *c = &f.scene.desc.camera;
            memset(c->eye, 0, sizeof c->eye);
            memcpy(c->target, views[v].look, sizeof c->target);
            memcpy(c->up, views[v].up, sizeof c->up);
            float *img = render_fixture_render(&f, (RenderSettings){.spp = 4, .max_depth = 1, .seed = 1}, NULL);
            int expected = rotated ? views[v].at_90 : views[v].at_0;
            const float *px = &img[3 * (4 * 9 + 4)];
            for (int ch = 0; ch < 3; ch++)
                cr_expect(fabsf(px[ch] - axis_colours[expected][ch]) < 1e-3f,
                          "rotation %d, looking along (%g, %g, %g): centre channel %d = %g, expected %g",
                          rotated ? 90 : 0, views[v].look[0], views[v].look[1], views[v].look[2], ch,
                          px[ch], axis_colours[expected][ch]);
            free(img);
        }
        render_fixture_close(&f);
    }
}


/* DESIGN's mapping evaluated on the host: the bilinear radiance of map rgb (w x h) seen along d
 * with rotation theta (a fraction of a turn). */
static void expected_radiance(const float *rgb, int w, int h, const double d[3], double theta,
                              double out[3])
{
    double u = 0.5 + atan2(d[0], -d[2]) / (2.0 * ENV_PI) + theta, v = acos(d[1]) / ENV_PI;
    u -= floor(u);
    double x = u * w - 0.5, y = v * h - 0.5, fx = x - floor(x), fy = y - floor(y);
    int i0 = (int)floor(x), j0 = (int)floor(y);
    int i1 = (i0 + 1) % w, j1 = j0 + 1 > h - 1 ? h - 1 : j0 + 1;
    i0 = (i0 + w) % w, j0 = j0 < 0 ? 0 : j0;
    for (int c = 0; c < 3; c++)
        out[c] = (1 - fy) * ((1 - fx) * rgb[3 * (j0 * w + i0) + c] + fx * rgb[3 * (j0 * w + i1) + c]) +
                 fy * ((1 - fx) * rgb[3 * (j1 * w + i0) + c] + fx * rgb[3 * (j1 * w + i1) + c]);
}

/* True when a and b differ by more than 10% of the larger in some channel. */
static bool differs(const double a[3], const double b[3])
{
    for (int c = 0; c < 3; c++)
        if (fabs(a[c] - b[c]) > 0.1 * fmax(fmax(a[c], b[c]), 0.05))
            return true;
    return false;
}

/* The shared OpenEXR orientation map (tiled, mip-mapped, half float; read at level 0), when
 * ../shared is there: a 1 x 1 film with a 0.01 degree field of view looking along 40 directions
 * at rotations 0 and 90 sees what DESIGN's formula predicts from the decoded texels (bilinear).
 * The directions are drawn where the map tells the conventions apart: DESIGN's prediction differs
 * from the mirrored mapping's (u growing toward -x) and from OpenEXR's own (+z at the centre). */
Test(environment, shared_orientation_map_follows_design, .timeout = 120)
{
    REQUIRE_ASSETS();
    const char *map = ASSETS_DIR "/openexr-envmaps/OrientationLatLong.exr";
    float *rgb;
    int w, h;
    Error err = {0};
    cr_assert(image_read_exr(map, &rgb, &w, &h, &err), "%s", err.message);
    const char *dir = test_temp_dir();
    char root[2048], path[4096];
    cr_assert(getcwd(root, sizeof root));
    snprintf(path, sizeof path, "%s/%s", root, map);
    write_speck(dir);
    uint64_t state = 11;
    for (int rotated = 0; rotated < 2; rotated++) {
        double theta = rotated ? 0.25 : 0.0;
        const char *scene = write_scene(dir, rotated ? "rotated.json" : "plain.json", "[{\"obj\": \"speck.obj\"}]",
                                        path, rotated ? 90.0f : 0.0f,
                                        "{\"eye\": [0, 0, 0], \"target\": [0, 0, -1], \"fov_y\": 0.01}");
        RenderFixture f;
        render_fixture_open(&f, scene, 1, 1);
        int agree = 0, n = 40;
        for (int k = 0; k < n; k++) {
            double d[3], want[3], other[3];
            for (;;) { /* uniform on the sphere away from the poles, where the conventions differ */
                double z = 1.8 * mesh_rng_float(&state) - 0.9, ph = 2.0 * ENV_PI * mesh_rng_float(&state);
                d[0] = sqrt(1 - z * z) * cos(ph), d[1] = z, d[2] = sqrt(1 - z * z) * sin(ph);
                expected_radiance(rgb, w, h, d, theta, want);
                double mirrored[3] = {-d[0], d[1], d[2]}, facing_z[3] = {-d[0], d[1], -d[2]};
                expected_radiance(rgb, w, h, mirrored, theta, other);
                if (!differs(want, other))
                    continue;
                expected_radiance(rgb, w, h, facing_z, theta, other);
                if (differs(want, other))
                    break;
            }
            CameraDesc *c = &f.scene.desc.camera;
            memset(c->eye, 0, sizeof c->eye);
            for (int i = 0; i < 3; i++)
                c->target[i] = (float)d[i];
            c->up[0] = 0, c->up[1] = 1, c->up[2] = 0;
            float *px = render_fixture_render(&f, (RenderSettings){.spp = 4, .max_depth = 1, .seed = 1}, NULL);
            bool ok = true;
            for (int ch = 0; ch < 3; ch++)
                ok = ok && fabs(px[ch] - want[ch]) < 0.03 * fmax(want[ch], 1.0);
            if (!ok)
                cr_log_error("rotation %d, direction (%.3f, %.3f, %.3f): rendered (%g, %g, %g), DESIGN says (%g, %g, %g)",
                             rotated ? 90 : 0, d[0], d[1], d[2], px[0], px[1], px[2], want[0], want[1], want[2]);
            agree += ok;
            free(px);
        }
        cr_expect_eq(agree, n, "rotation %d: %d of %d directions see what DESIGN predicts", rotated ? 90 : 0, agree, n);
        render_fixture_close(&f);
    }
    free(rgb);
}
