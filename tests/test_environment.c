// SPDX-License-Identifier: MIT
/* The environment map's orientation (shared/DESIGN.md "Environment") on a map generated here: the
 * lat-long mapping and the rotation sense, through the EXR and the HDR readers. Sampling:
 * test_environment_sampling.c; unbiasedness: test_environment_unbiased.c; bad input:
 * test_environment_input.c. */
#include <stb_image_write.h>

#include "environment_maps.h"
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

