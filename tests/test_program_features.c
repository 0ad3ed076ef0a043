// SPDX-License-Identifier: MIT
/* pt builds its kernels for the scene's light types (render/session.c: -DPT_FEATURE_ENV=0 and
 * -DPT_FEATURE_ANALYTIC=0 for a scene with neither); the tests' program keeps every feature. Both
 * must render a scene without those lights to the same bits: the options only remove branches
 * that such a scene never takes. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/image_io.h"
#include "support.h"

Test(program_features, specialised_kernels_render_the_same_bits, .timeout = 240)
{
    const char *dir = test_temp_dir();
    char cmd[1024], exr[512];
    snprintf(exr, sizeof exr, "%s/pt.exr", dir);
    snprintf(cmd, sizeof cmd, "'%s' render scenes/cornell-box --device cpu --width 48 --height 48 --spp 4 "
             "--seed 3 -q -o '%s' 2>/dev/null", test_pt_bin(), exr);
    cr_assert_eq(system(cmd), 0, "%s", cmd);
    float *specialised;
    int w, h;
    Error err = {0};
    cr_assert(image_read_exr(exr, &specialised, &w, &h, &err), "%s", err.message);
    cr_assert(w == 48 && h == 48);

    RenderFixture f;
    render_fixture_open(&f, "scenes/cornell-box", 48, 48);
    cr_assert(!strstr(f.dev->build_options, "PT_FEATURE"), "the tests' program has every feature");
    float *full = render_fixture_render(&f, (RenderSettings){.spp = 4, .max_depth = f.scene.desc.max_depth, .seed = 3}, NULL);
    size_t n = (size_t)w * h * 3, differ = 0;
    for (size_t i = 0; i < n; i++)
        differ += memcmp(&specialised[i], &full[i], sizeof(float)) != 0;
    cr_expect_eq(differ, 0, "%zu of %zu values differ between the specialised and the full program",
                 differ, n);
    double sum = 0.0;
    for (size_t i = 0; i < n; i++)
        sum += full[i];
    cr_expect(sum > 0.0, "the render is not black");
    free(specialised), free(full);
    render_fixture_close(&f);
}
