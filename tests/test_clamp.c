// SPDX-License-Identifier: MIT
/* --clamp (RenderSettings.clamp_indirect): direct light is never clamped, each contribution of
 * indirect light is (shade_emission.cl, clamp_indirect). */
#include <criterion/criterion.h>
#include <stdlib.h>
#include <string.h>

#include "render/wavefront.h"
#include "support.h"

#define SIDE 24
#define PIXELS (SIDE * SIDE)
#define MAX 0.02f

/* Paths of at most 2 segments carry direct light only: the clamp changes no bit. */
Test(clamp, direct_light_is_never_clamped, .timeout = 300)
{
    RenderFixture f;
    render_fixture_open(&f, "scenes/cornell-box/scene.json", SIDE, SIDE);
    RenderSettings s = {.spp = 8, .max_depth = 2, .seed = 2};
    float *plain = render_fixture_render(&f, s, NULL);
    s.clamp_indirect = MAX;
    float *clamped = render_fixture_render(&f, s, NULL);
    cr_expect(memcmp(plain, clamped, PIXELS * 3 * sizeof(float)) == 0,
              "the clamp changed an image of direct light");
    free(plain), free(clamped);
    render_fixture_close(&f);
}

/* One sample per pixel, so the film holds each sample. With max_depth 3 a sample is its depth-2
 * part (the same paths: the RNG is keyed on pixel, sample and bounce, and roulette starts later)
 * plus at most two indirect contributions: the light connection at the second vertex and the
 * emitter hit by the third segment. Clamped, each is at most MAX in every channel. */
Test(clamp, each_indirect_contribution_is_bounded, .timeout = 300)
{
    RenderFixture f;
    render_fixture_open(&f, "scenes/cornell-box/scene.json", SIDE, SIDE);
    RenderSettings s = {.spp = 1, .max_depth = 2, .seed = 2};
    float *direct = render_fixture_render(&f, s, NULL);
    s.max_depth = 3;
    float *plain = render_fixture_render(&f, s, NULL);
    s.clamp_indirect = MAX;
    float *clamped = render_fixture_render(&f, s, NULL);
    int above = 0, changed = 0;
    for (int i = 0; i < PIXELS * 3; i++) {
        float extra = clamped[i] - direct[i];
        cr_expect(extra >= -1e-4f && extra <= 2 * MAX + 1e-4f, "value %d: %g direct + %g indirect", i,
                  direct[i], extra);
        above += plain[i] - direct[i] > 2 * MAX;
        changed += clamped[i] != plain[i];
        cr_expect(clamped[i] <= plain[i] + 1e-4f, "value %d: the clamp added light", i);
    }
    cr_expect(above > PIXELS / 8, "only %d values had more than %g of indirect light", above, 2 * MAX);
    cr_expect(changed >= above);
    free(direct), free(plain), free(clamped);
    render_fixture_close(&f);
}
