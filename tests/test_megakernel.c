// SPDX-License-Identifier: MIT
/* The CPU's path-per-work-item kernel (PATH_KERNEL_MEGAKERNEL, cl/stages/megakernel.cl), the
 * wavefront's tail and the wavefront whose shading leaves its shadow rays to intersect_shadow
 * (split_shadow) against the wavefront, whose shading traces them, on the same device: the same stage functions in the same order per path, so the same rays and the film's
 * very bits, on scenes that exercise every material family, textures, normal maps, media, the
 * environment map, the indirect clamp and adaptive sampling (whose windows cycle over the pixels
 * still sampled). And which of them a render gets. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "render/wavefront_internal.h"
#include "support.h"

/* Render b (by `name`) against the wavefront's a: the same rays, the same bits. */
static void expect_same_bits(const char *scene, const char *name, RenderFixture *f,
                             const float *wave_image, const float *b, const RenderStats *wave,
                             const RenderStats *stats)
{
    cr_expect_eq(stats->extension_rays, wave->extension_rays, "%s: %s: %llu extension rays, wavefront %llu",
                 scene, name, (unsigned long long)stats->extension_rays,
                 (unsigned long long)wave->extension_rays);
    cr_expect_eq(stats->shadow_rays, wave->shadow_rays, "%s: %s: %llu shadow rays, wavefront %llu", scene,
                 name, (unsigned long long)stats->shadow_rays, (unsigned long long)wave->shadow_rays);
    size_t n = (size_t)f->scene.desc.width * (size_t)f->scene.desc.height * 3, differ = 0;
    for (size_t i = 0; i < n; i++)
        differ += memcmp(&wave_image[i], &b[i], sizeof b[i]) != 0;
    cr_expect_eq(differ, 0, "%s: %s: %zu of %zu values differ from the wavefront's", scene, name,
                 differ, n);
}

/* Kernel k's render against the wavefront's: the same rays, the same bits. */
static void expect_same_as_wavefront(const char *scene, RenderFixture *f, RenderSettings s, int k,
                                     const float *wave_image, const RenderStats *wave,
                                     RenderStats *stats)
{
    s.path_kernel = k;
    s.tail_paths = 0;
    float *b = render_fixture_render(f, s, stats);
    const char *name = k == PATH_KERNEL_MEGAKERNEL ? "megakernel" : "megakernel-single";
    cr_expect(stats->config.megakernel, "%s: %s: the megakernel was not used", scene, name);
    expect_same_bits(scene, name, f, wave_image, b, wave, stats);
    free(b);
}

/* The wavefront, the megakernel and the one-path megakernel render the same bits with the same
 * rays, on the tests' program (every feature: two BVH levels, cut-outs, so one path per work item)
 * and on the program pt builds for such a scene (one level, no cut-outs), where the megakernel has
 * eight paths per work item and traces their rays as packets on the 8-wide layout (CPUs). */
static void expect_same_render_on(const char *scene, RenderSettings s, int width, int height,
                                  bool one_level)
{
    RenderFixture f;
    if (one_level)
        render_fixture_open_one_level(&f, scene, width, height);
    else
        render_fixture_open(&f, scene, width, height);
    bool packets = one_level;
    RenderStats wave, tail, mega, single;
    s.path_kernel = PATH_KERNEL_WAVEFRONT;
    s.tail_paths = -1; /* every bounce a step of its own */
    float *a = render_fixture_render(&f, s, &wave);
    cr_expect(!wave.config.megakernel, "%s: the wavefront was not used", scene);
    cr_expect_gt(wave.extension_rays, (uint64_t)width * (uint64_t)height, "%s: no bounces traced", scene);
    cr_expect_eq(wave.stage_launches[STAGE_FINISH_PATHS], 0, "%s: finish_paths ran with the tail off",
                 scene);
    /* The tail kernel takes each window's paths once its samples have all started: with a small
     * pool, after steps that refilled slots, and over more than one window. */
    RenderSettings t = s;
    t.tail_paths = 1 << 30;
    if (!t.pool_size)
        t.pool_size = 512;
    float *b = render_fixture_render(&f, t, &tail);
    cr_expect_gt(tail.stage_launches[STAGE_FINISH_PATHS], 0, "%s: finish_paths never ran", scene);
    expect_same_bits(scene, "the wavefront's tail", &f, a, b, &wave, &tail);
    free(b);
    /* Shadow rays traced by intersect_shadow (split) or by the shading that queued them (the
     * wavefront's default): the same bits. */
    cr_expect_eq(wave.stage_launches[STAGE_INTERSECT_SHADOW], 0,
                 "%s: intersect_shadow ran while shading connects", scene);
    RenderSettings c = s;
    c.split_shadow = true;
    RenderStats split;
    b = render_fixture_render(&f, c, &split);
    cr_expect_gt(split.stage_launches[STAGE_INTERSECT_SHADOW], 0,
                 "%s: split shadow rays but no intersect_shadow", scene);
    expect_same_bits(scene, "the split shadow stage", &f, a, b, &wave, &split);
    free(b);
    expect_same_as_wavefront(scene, &f, s, PATH_KERNEL_MEGAKERNEL, a, &wave, &mega);
    expect_same_as_wavefront(scene, &f, s, PATH_KERNEL_MEGAKERNEL_SINGLE, a, &wave, &single);
    bool wide = f.dev->bvh_width == 8;
    cr_expect_eq(mega.config.packets, packets && wide, "%s: packets %s (8-wide layout: %s)", scene,
                 mega.config.packets ? "used" : "not used", wide ? "yes" : "no");
    cr_expect(!single.config.packets, "%s: megakernel-single used packets", scene);
    free(a);
    render_fixture_close(&f);
}

static void expect_same_render(const char *scene, RenderSettings s)
{
    expect_same_render_on(scene, s, 24, 24, false);
    expect_same_render_on(scene, s, 24, 24, true);
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

/* Media and `interface` surfaces (the medium state and since_vertex ride along with the path):
 * the tail, the megakernel and the split shadow stage render the wavefront's bits (tests' program
 * only: the one-level program has no media). The smoke's grid medium draws its shadow rays'
 * ratio tracking from the queuing bounce's stream. */
Test(megakernel, same_bits_with_media, .timeout = 600)
{
    const char *scenes[] = {"tests/scenes/fog-room/scene.json", "tests/scenes/liquid/scene.json",
                            "tests/scenes/smoke/scene.json"};
    for (size_t i = 0; i < sizeof scenes / sizeof scenes[0]; i++)
        expect_same_render_on(scenes[i], (RenderSettings){.spp = 4, .max_depth = 16, .seed = 7},
                              24, 24, false);
}

/* The tail's part built on a thread of its own beside the renders, as pt builds it: a render
 * before it is there steps every bounce, one after takes it (here from its start, once the build
 * is taken in); both have the bits of a render with the tail off. */
Test(megakernel, tail_built_beside_the_renders, .timeout = 600)
{
    RenderFixture f;
    render_fixture_open_in_parts(&f, "scenes/cornell-box/scene.json", 24, 24);
    RenderSettings s = {.spp = 4, .max_depth = 8, .seed = 5, .path_kernel = PATH_KERNEL_WAVEFRONT,
                        .pool_size = 512, .tail_paths = -1};
    RenderStats off, early, late;
    float *a = render_fixture_render(&f, s, &off);
    s.tail_paths = 0; /* the default: the part builds beside the render */
    float *b = render_fixture_render(&f, s, &early);
    cr_expect(f.dev->background || f.dev->programs[PROGRAM_PART_TAIL],
              "the tail's part is neither building nor built");
    expect_same_bits("scenes/cornell-box/scene.json", "a render beside the tail's build", &f, a, b,
                     &off, &early);
    device_finish_background_build(f.dev);
    cr_assert_not_null(f.dev->programs[PROGRAM_PART_TAIL]);
    float *c = render_fixture_render(&f, s, &late);
    cr_expect_gt(late.stage_launches[STAGE_FINISH_PATHS], 0, "the built tail was not taken");
    expect_same_bits("scenes/cornell-box/scene.json", "a render after the tail's build", &f, a, c,
                     &off, &late);
    free(a);
    free(b);
    free(c);
    render_fixture_close(&f);
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
    return stats.config.device_bytes;
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
    return stats.config.megakernel;
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
    unsetenv("PT_MEGAKERNEL");
    /* Sorting only orders the wavefront's launches: a CPU still gets the megakernel (auto). */
    cr_expect_eq(auto_choice(&f, (RenderSettings){.sort_materials = true}), cpu);
    render_fixture_close(&f);
}

/* A slot's shadow_contribution is stored only where a shadow ray is queued (render.h
 * shadow_contribution_pack), so no slot may still wait for one once its path has been shaded and
 * connected: a later path in that slot would add the stale contribution to its own sample. After a
 * window in each flow (the wavefront with its shadow queue or its flags, its tail, without
 * compaction, the megakernel with packets and one path per work item, and through media), every
 * slot's waits lane reads 0. */
static void expect_no_slot_waits(const char *scene, bool one_level, RenderSettings s, const char *name)
{
    RenderFixture f;
    if (one_level)
        render_fixture_open_one_level(&f, scene, 16, 16);
    else
        render_fixture_open(&f, scene, 16, 16);
    Error err = {0};
    Wavefront *w = wavefront_create(f.dev, &f.scene, &f.buffers, &s, &err);
    cr_assert(w, "%s: %s: %s", scene, name, err.message);
    wavefront_advance(w, 1, s.spp);
    uint32_t pool = w->stats->config.pool_size, waiting = 0;
    cl_float4 *c = malloc(pool * sizeof *c);
    cr_assert(c);
    device_read(w->dev, w->shadow_contribution, 0, pool * sizeof *c, c);
    for (uint32_t i = 0; i < pool; i++)
        waiting += c[i].s[3] != 0.0f;
    cr_expect_eq(waiting, 0, "%s: %s: %u of %u slots still wait for a shadow ray after a window",
                 scene, name, waiting, pool);
    free(c);
    wavefront_destroy(w);
    render_fixture_close(&f);
}

Test(megakernel, no_slot_waits_for_a_shadow_ray_after_a_window, .timeout = 300)
{
    const char *scenes[] = {"scenes/cornell-box/scene.json", "tests/scenes/fog-room/scene.json"};
    for (size_t i = 0; i < sizeof scenes / sizeof scenes[0]; i++) {
        RenderSettings s = {.spp = 4, .max_depth = 8, .seed = 3, .pool_size = 128,
                            .path_kernel = PATH_KERNEL_WAVEFRONT, .tail_paths = -1};
        expect_no_slot_waits(scenes[i], false, s, "wavefront");
        RenderSettings flags = s;
        flags.shadow_flags = true;
        expect_no_slot_waits(scenes[i], false, flags, "wavefront with shadow flags");
        RenderSettings tail = s;
        tail.tail_paths = 1 << 30;
        expect_no_slot_waits(scenes[i], false, tail, "the wavefront's tail");
        RenderSettings whole = s;
        whole.no_compaction = true;
        whole.pool_size = 0;
        expect_no_slot_waits(scenes[i], false, whole, "no compaction");
        RenderSettings single = s;
        single.path_kernel = PATH_KERNEL_MEGAKERNEL_SINGLE;
        expect_no_slot_waits(scenes[i], false, single, "megakernel, one path per work item");
    }
    RenderSettings packets = {.spp = 4, .max_depth = 8, .seed = 3, .pool_size = 128,
                              .path_kernel = PATH_KERNEL_MEGAKERNEL};
    expect_no_slot_waits("scenes/cornell-box/scene.json", true, packets, "megakernel");
}

/* A lit grid of n x n quads (2 n^2 triangles) facing the camera, its scene's path returned. */
static const char *write_grid_scene(const char *name, int n)
{
    static char scene[512];
    char obj[512];
    const char *dir = test_temp_dir();
    snprintf(obj, sizeof obj, "%s/%s.obj", dir, name);
    snprintf(scene, sizeof scene, "%s/%s.json", dir, name);
    FILE *f = fopen(obj, "w");
    cr_assert_not_null(f);
    for (int j = 0; j <= n; j++)
        for (int i = 0; i <= n; i++)
            fprintf(f, "v %g %g 0\n", (double)i / n - 0.5, (double)j / n - 0.5);
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            int a = j * (n + 1) + i + 1, b = a + 1, c = a + n + 1, d = c + 1;
            fprintf(f, "f %d %d %d\nf %d %d %d\n", a, b, d, a, d, c);
        }
    fclose(f);
    f = fopen(scene, "w");
    cr_assert_not_null(f);
    fprintf(f, "{\"camera\": {\"eye\": [0, 0, 2], \"target\": [0, 0, 0], \"up\": [0, 1, 0], "
               "\"fov_y\": 40}, \"film\": {\"width\": 8, \"height\": 8}, "
               "\"lights\": [{\"type\": \"point\", \"position\": [0, 0, 1], \"intensity\": 1}], "
               "\"objects\": [{\"obj\": \"%s.obj\"}]}\n", name);
    fclose(f);
    return scene;
}

/* The wavefront's shading traces its shadow rays in scenes of up to 2^15 traced triangles and
 * leaves them to intersect_shadow in larger ones (CONNECT_MAX_TRIANGLES); PT_CONNECT_IN_SHADING
 * is not set here. Grids of 2 x 128^2 = 32768 and 2 x 129^2 = 33282 triangles. */
Test(megakernel, shading_connects_up_to_2_15_triangles, .timeout = 240)
{
    const int sizes[] = {128, 129};
    for (int k = 0; k < 2; k++) {
        char name[32];
        snprintf(name, sizeof name, "grid%d", sizes[k]);
        RenderFixture f;
        render_fixture_open(&f, write_grid_scene(name, sizes[k]), 8, 8);
        RenderStats st;
        free(render_fixture_render(&f, (RenderSettings){.spp = 1, .max_depth = 2,
                                                        .path_kernel = PATH_KERNEL_WAVEFRONT},
                                   &st));
        cr_expect_gt(st.shadow_rays, 0u, "%s: no shadow rays", name);
        cr_expect_eq(st.stage_launches[STAGE_INTERSECT_SHADOW] > 0, k == 1,
                     "%s: intersect_shadow launched %u times", name,
                     st.stage_launches[STAGE_INTERSECT_SHADOW]);
        render_fixture_close(&f);
    }
}
