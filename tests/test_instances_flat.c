// SPDX-License-Identifier: MIT
/* Flat BVHs for static instances (host/accel/scene_bvh.h BVH_FLAT) through the whole renderer:
 * the flat walk renders the two levels' image but for rounding and the brute force's bits; pt
 * builds the walk of the levels it chose (flat, two levels with --instancing always or a moving
 * instance); the choice itself and the checkpoints' hash. Hits against the brute force in every
 * layout: tests/test_accel_instances_bvh.c. */
#define _DEFAULT_SOURCE /* realpath */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>

#include "io/image_io.h"
#include "render/scene_upload.h"
#include "scene/scene_hash.h"
#include "support.h"
#include "turned_instances.h"

/* The flat BVH's hits are the two levels' up to rounding (world-space triangles against rays in
 * object space), and its unbaked (instance, triangle) place them where the two levels do: the
 * same random numbers draw the same image but for the few paths whose hits round differently.
 * An instance or triangle mapped wrongly moves, turns or mirrors a tetrahedron's shading. */
Test(instances_flat, a_flat_bvh_renders_the_two_levels_image, .timeout = 300)
{
    const char *scene = turned_instances_scene();
    RenderSettings s = {.spp = 4, .max_depth = 4, .seed = 5};
    RenderFixture two, flat;
    render_fixture_open_with(&two, scene, 48, 48, INSTANCING_AUTO);
    float *a = render_fixture_render(&two, s, NULL);
    render_fixture_close(&two);
    render_fixture_open_flat(&flat, scene, 48, 48);
    cr_assert_eq(flat.bvh.levels, BVH_FLAT);
    const SceneData *d = &flat.scene.data;
    uint32_t baked = 0;
    for (uint32_t i = 0; i < d->num_instances; i++)
        baked += d->meshes[d->instances[i].mesh].num_triangles;
    cr_assert_eq(flat.bvh.num_flat_prims, baked, "one pair per instance's triangle");
    float *b = render_fixture_render(&flat, s, NULL);
    render_fixture_close(&flat);
    int n = 48 * 48 * 3, apart = 0;
    double sum_a = 0.0, sum_b = 0.0;
    for (int i = 0; i < n; i++) {
        sum_a += a[i], sum_b += b[i];
        apart += fabsf(a[i] - b[i]) > 1e-3f * fmaxf(1.0f, fabsf(a[i]));
    }
    cr_expect(apart <= n / 100, "%d of %d values differ between the flat and two-level BVHs", apart,
              n);
    cr_expect(fabs(sum_a - sum_b) <= 2e-3 * sum_a, "image sums %.6g (two levels) vs %.6g (flat)",
              sum_a, sum_b);
    free(a), free(b);
}

/* The flat BVH finds the hits that testing every baked triangle finds: the same bits. */
Test(instances_flat, a_flat_bvh_renders_the_brute_force_bits, .timeout = 300)
{
    RenderFixture f;
    render_fixture_open_flat(&f, turned_instances_scene(), 48, 48);
    expect_brute_force_bits(&f, "the flat BVH");
}

/* pt itself (session.c pairs the program's features with the levels it builds; a mismatch reads
 * past the BVH): exit status, the summary's levels and the image, for the scene as it is (flat),
 * with --instancing always (two levels) and with a moving tetrahedron (two levels); the first two
 * render the same image but for rounding. */
static float *pt_render_instances(const char *scene, const char *flags, const char *summary)
{
    const char *dir = test_temp_dir();
    char cmd[4096], exr[512], log[512];
    snprintf(exr, sizeof exr, "%s/out.exr", dir);
    snprintf(log, sizeof log, "%s/stderr.txt", dir);
    snprintf(cmd, sizeof cmd, "'%s' render '%s' --spp 8 --max-depth 4 --width 24 --height 24 -o '%s' %s 2>'%s'",
             test_pt_bin(), scene, exr, flags, log);
    int status = system(cmd);
    char *text = test_read_file(log, NULL);
    cr_assert(WIFEXITED(status) && WEXITSTATUS(status) == 0, "pt %s: %s", flags, text);
    cr_expect(strstr(text, summary), "pt %s: no \"%s\" in: %s", flags, summary, text);
    free(text);
    float *rgb;
    int w, h;
    Error err = {0};
    cr_assert(image_read_exr(exr, &rgb, &w, &h, &err), "%s", err.message);
    return rgb;
}

Test(instances_flat, pt_builds_the_walk_of_the_levels_it_chose, .timeout = 300)
{
    const char *scene = turned_instances_scene();
    float *flat = pt_render_instances(scene, "", "one flat BVH over them");
    float *two = pt_render_instances(scene, "--instancing always", "two-level BVH");
    int n = 24 * 24 * 3, apart = 0;
    for (int i = 0; i < n; i++)
        apart += fabsf(flat[i] - two[i]) > 1e-3f * fmaxf(1.0f, fabsf(two[i]));
    cr_expect(apart <= n / 50, "%d of %d values differ between pt's flat and two-level renders",
              apart, n);
    free(flat), free(two);
    /* One tetrahedron moving over the shutter: two levels. */
    char *json = test_read_file(scene, NULL);
    const char *from = "{\"translate\": [0.45, 0.6, -0.3]}]}";
    char *at = strstr(json, from);
    cr_assert(at);
    char moving[8192];
    snprintf(moving, sizeof moving,
             "%.*s{\"translate\": [0.45, 0.6, -0.3]}], \"transform_end\": [{\"translate\": [0.45, 0.8, "
             "-0.3]}]}%s",
             (int)(at - json), json, at + strlen(from));
    free(json);
    const char *with_shutter = strstr(moving, "\"fov_y\": 39.3}");
    cr_assert(with_shutter);
    char timed[8192];
    snprintf(timed, sizeof timed, "%.*s\"fov_y\": 39.3, \"shutter\": [0, 1]}%s",
             (int)(with_shutter - moving), moving, with_shutter + strlen("\"fov_y\": 39.3}"));
    char dir[512]; /* beside scene.json, whose objects are relative to it */
    snprintf(dir, sizeof dir, "%.*s", (int)(strrchr(scene, '/') - scene), scene);
    free(pt_render_instances(test_write_file(dir, "moving.json", timed), "", "(1 moving)"));
}

/* --instancing always reaches the levels (SceneData.keep_two_levels), and the checkpoints' scene
 * hash tells the two apart (their hits round differently). */
Test(instances_flat, instancing_always_keeps_two_levels_and_its_own_hash)
{
    const char *scene = turned_instances_scene();
    Scene a, b;
    Error err = {0};
    cr_assert(scene_load_with(scene, INSTANCING_AUTO, &a, &err), "%s", err.message);
    cr_assert(scene_load_with(scene, INSTANCING_ALWAYS, &b, &err), "%s", err.message);
    cr_expect_eq(scene_accel_levels(&a.data), BVH_FLAT);
    cr_expect_eq(scene_accel_levels(&b.data), BVH_TWO_LEVEL);
    cr_expect_neq(scene_hash(&a), scene_hash(&b));
    scene_free(&a);
    scene_free(&b);
}

/* Which levels pt builds: flat for static instances up to the budget of baked triangles; two
 * levels above it, with a moving instance, or when --instancing always asks; one without
 * instances. */
Test(instances_flat, flat_bvh_only_for_few_static_triangles)
{
    SceneMesh meshes[2] = {{.num_triangles = 1}, {.num_triangles = FLAT_BVH_TRIANGLE_BUDGET / 2}};
    SceneInstance instances[3] = {{.mesh = 1}, {.mesh = 1}, {.mesh = 0}};
    SceneData d = {.meshes = meshes, .num_meshes = 2, .instances = instances, .num_instances = 2,
                   .two_level = true};
    cr_expect_eq(scene_accel_levels(&d), BVH_FLAT, "exactly the budget");
    d.num_instances = 3;
    cr_expect_eq(scene_accel_levels(&d), BVH_TWO_LEVEL, "one triangle over the budget");
    d.num_instances = 2;
    d.num_moving = 1;
    cr_expect_eq(scene_accel_levels(&d), BVH_TWO_LEVEL, "a moving instance");
    d.num_moving = 0;
    d.keep_two_levels = true;
    cr_expect_eq(scene_accel_levels(&d), BVH_TWO_LEVEL, "--instancing always");
    d.keep_two_levels = false;
    d.two_level = false;
    cr_expect_eq(scene_accel_levels(&d), BVH_ONE_LEVEL, "one mesh in world space");
    cr_expect_eq(BVH_LEVELS_FEATURES(BVH_FLAT), FEATURE_INSTANCES);
    cr_expect_eq(BVH_LEVELS_FEATURES(BVH_TWO_LEVEL), FEATURE_INSTANCES | FEATURE_TLAS);
    cr_expect_eq(BVH_LEVELS_FEATURES(BVH_ONE_LEVEL), 0u);
}
