// SPDX-License-Identifier: MIT
/* The CPU's path-per-work-item kernel (PATH_KERNEL_MEGAKERNEL, cl/stages/megakernel.cl) against the
 * wavefront on the same device: the same stage functions in the same order per path, so the same
 * rays and the film's very bits, on scenes that exercise every material family, textures, normal
 * maps, the environment map, the indirect clamp and adaptive sampling (whose windows cycle over the
 * pixels still sampled). And which of the two a render gets. */
#include <criterion/criterion.h>
#include <stdlib.h>
#include <string.h>

#include "support.h"

static void expect_same_render(const char *scene, RenderSettings s)
{
    RenderFixture f;
    render_fixture_open(&f, scene, 24, 24);
    size_t n = 24 * 24 * 3;
    RenderStats wave, mega;
    s.path_kernel = PATH_KERNEL_WAVEFRONT;
    float *a = render_fixture_render(&f, s, &wave);
    s.path_kernel = PATH_KERNEL_MEGAKERNEL;
    float *b = render_fixture_render(&f, s, &mega);
    cr_expect(!wave.megakernel && mega.megakernel, "%s: the path kernel asked for was not used", scene);
    cr_expect_eq(mega.extension_rays, wave.extension_rays, "%s: %llu extension rays, wavefront %llu",
                 scene, (unsigned long long)mega.extension_rays, (unsigned long long)wave.extension_rays);
    cr_expect_eq(mega.shadow_rays, wave.shadow_rays, "%s: %llu shadow rays, wavefront %llu", scene,
                 (unsigned long long)mega.shadow_rays, (unsigned long long)wave.shadow_rays);
    cr_expect_gt(wave.extension_rays, 24u * 24u, "%s: no bounces traced", scene);
    size_t differ = 0;
    for (size_t i = 0; i < n; i++)
        differ += memcmp(&a[i], &b[i], sizeof a[i]) != 0;
    cr_expect_eq(differ, 0, "%s: %zu of %zu values differ from the wavefront's", scene, differ, n);
    free(a), free(b);
    render_fixture_close(&f);
}

Test(megakernel, same_bits_and_rays_as_the_wavefront, .timeout = 600)
{
    const char *scenes[] = {
        "scenes/cornell-box/scene.json",   "scenes/cornell-box/sphere.json",
        "tests/scenes/textured/scene.json", "tests/scenes/glass/scene.json",
        "tests/scenes/mix/scene.json",      "tests/scenes/normalmap/scene.json",
        "tests/scenes/conductors/scene.json", "tests/scenes/envmap/scene.json",
    };
    for (size_t i = 0; i < sizeof scenes / sizeof scenes[0]; i++)
        expect_same_render(scenes[i], (RenderSettings){.spp = 4, .max_depth = 8, .seed = 5});
}

/* Windows smaller than the film and pools smaller than a window: the megakernel launches a pool
 * of samples at a time, the wavefront refills; both cover every sample once. */
Test(megakernel, same_bits_with_small_pools_and_windows, .timeout = 300)
{
    expect_same_render("scenes/cornell-box/scene.json",
                       (RenderSettings){.spp = 6, .max_depth = 8, .seed = 9, .pool_size = 100,
                                        .window_size = 1000});
}

Test(megakernel, same_bits_with_clamp_and_adaptive_sampling, .timeout = 300)
{
    expect_same_render("scenes/cornell-box/scene.json",
                       (RenderSettings){.spp = 32, .max_depth = 8, .seed = 2, .clamp_indirect = 0.5f});
    expect_same_render("scenes/cornell-box/scene.json",
                       (RenderSettings){.spp = 64, .max_depth = 8, .seed = 2, .noise_threshold = 0.05f,
                                        .min_spp = 8, .window_size = 24 * 24 * 8,
                                        .pool_size = 24 * 24 * 2});
}

/* Device bytes of a render with path kernel k (PATH_KERNEL_*), sorting or not. */
static uint64_t device_bytes(RenderFixture *f, int k, bool sort)
{
    RenderStats stats;
    RenderSettings s = {.spp = 1, .max_depth = 2, .path_kernel = k, .sort_materials = sort};
    free(render_fixture_render(f, s, &stats));
    return stats.device_bytes;
}

/* Asked for material sorting, the megakernel renders without a sorter (it has no shading launches
 * to order: no sorted list on the device) and the wavefront sorts its launches (one more list);
 * neither changes a path's arithmetic. */
Test(megakernel, same_bits_when_sorting_is_asked, .timeout = 300)
{
    expect_same_render("scenes/cornell-box/scene.json",
                       (RenderSettings){.spp = 4, .max_depth = 8, .seed = 3, .sort_materials = true});
    RenderFixture f;
    render_fixture_open(&f, "scenes/cornell-box/scene.json", 8, 8);
    cr_expect_eq(device_bytes(&f, PATH_KERNEL_MEGAKERNEL, true),
                 device_bytes(&f, PATH_KERNEL_MEGAKERNEL, false),
                 "the megakernel allocated the sorter's list");
    cr_expect_gt(device_bytes(&f, PATH_KERNEL_WAVEFRONT, true),
                 device_bytes(&f, PATH_KERNEL_WAVEFRONT, false), "the wavefront did not sort");
    render_fixture_close(&f);
}

static bool auto_choice(RenderFixture *f, RenderSettings s)
{
    RenderStats stats;
    s.spp = 1, s.max_depth = 2;
    free(render_fixture_render(f, s, &stats));
    return stats.megakernel;
}

Test(megakernel, chosen_on_cpus_unless_overridden_or_an_ablation)
{
    RenderFixture f;
    render_fixture_open(&f, "scenes/cornell-box/scene.json", 8, 8);
    bool cpu = (f.dev->type & CL_DEVICE_TYPE_CPU) != 0;
    unsetenv("PT_MEGAKERNEL");
    cr_expect_eq(auto_choice(&f, (RenderSettings){0}), cpu, "auto: the megakernel exactly on CPUs");
    setenv("PT_MEGAKERNEL", "0", 1);
    cr_expect(!auto_choice(&f, (RenderSettings){0}), "PT_MEGAKERNEL=0 keeps the wavefront");
    setenv("PT_MEGAKERNEL", "1", 1);
    cr_expect(auto_choice(&f, (RenderSettings){0}), "PT_MEGAKERNEL=1 asks for the megakernel");
    cr_expect(!auto_choice(&f, (RenderSettings){.path_kernel = PATH_KERNEL_WAVEFRONT}),
              "the setting overrides the variable");
    cr_expect(!auto_choice(&f, (RenderSettings){.no_compaction = true}), "an ablation of the wavefront");
    cr_expect(!auto_choice(&f, (RenderSettings){.brute_force = true}), "an ablation of the wavefront");
    /* Sorting only orders the wavefront's launches: a CPU still gets the megakernel. */
    cr_expect_eq(auto_choice(&f, (RenderSettings){.sort_materials = true}), cpu);
    unsetenv("PT_MEGAKERNEL");
    render_fixture_close(&f);
}
