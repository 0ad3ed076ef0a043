// SPDX-License-Identifier: MIT
/* pt builds its kernels for the features the scene uses (cl/shared/features.h; render/session.c:
 * no FEATURE_ENV nor FEATURE_ANALYTIC for a scene with neither); the tests' program keeps every
 * feature. Both must render a scene without those lights to the same bits: the options only remove
 * branches that such a scene never takes. Without media the specialised program also stores no
 * camera ray's origin and throughput (path_state.cl camera_state_implied) where the full one, with
 * media, does: the same bits check that what it implies is what was stored. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <stb_image_write.h>

#include "io/image_io.h"
#include "support.h"

/* Renders `scene` with pt (kernels built for the scene) and with the tests' full program; every
 * value must have the same bits. */
static void expect_same_bits(const char *scene)
{
    const char *dir = test_temp_dir();
    char cmd[1024], exr[512];
    snprintf(exr, sizeof exr, "%s/pt.exr", dir);
    /* The device the fixture renders on (PT_TEST_DEVICE, test_device()): bits are per device. */
    const char *device = getenv("PT_TEST_DEVICE") ? getenv("PT_TEST_DEVICE") : "cpu";
    snprintf(cmd, sizeof cmd, "'%s' render %s --device '%s' --width 48 --height 48 --spp 4 "
             "--seed 3 -q -o '%s' 2>/dev/null", test_pt_bin(), scene, device, exr);
    cr_assert_eq(system(cmd), 0, "%s", cmd);
    float *specialised;
    int w, h;
    Error err = {0};
    cr_assert(image_read_exr(exr, &specialised, &w, &h, &err), "%s", err.message);
    cr_assert(w == 48 && h == 48);

    RenderFixture f;
    render_fixture_open(&f, scene, 48, 48);
    char summary[PROGRAM_FEATURE_SUMMARY_SIZE];
    program_features_summary(f.dev->features, summary);
    cr_assert_str_eq(summary, "all", "the tests' program has every feature");
    float *full = render_fixture_render(&f, (RenderSettings){.spp = 4, .max_depth = f.scene.desc.max_depth, .seed = 3}, NULL);
    size_t n = (size_t)w * h * 3, differ = 0;
    for (size_t i = 0; i < n; i++)
        differ += memcmp(&specialised[i], &full[i], sizeof(float)) != 0;
    cr_expect_eq(differ, 0, "%s: %zu of %zu values differ between the specialised and the full program",
                 scene, differ, n);
    double sum = 0.0;
    for (size_t i = 0; i < n; i++)
        sum += full[i];
    cr_expect(sum > 0.0, "%s: the render is not black", scene);
    free(specialised), free(full);
    render_fixture_close(&f);
}

/* No environment, analytic light or material feature beyond Lambert. */
Test(program_features, specialised_kernels_render_the_same_bits, .timeout = 240)
{
    expect_same_bits("scenes/cornell-box");
}

/* Material features (FEATURE_MIX and the others, host/scene/materials.c material_features): a mix of a
 * diffuse and a rough conductor with eta/k beside a Fresnel-1 mirror; rough glass with absorption;
 * anisotropic copper (surface detail: the uv tangent frame). Under-reporting any of them changes
 * the bits. */
Test(program_features, material_specialised_kernels_render_the_same_bits, .timeout = 480)
{
    expect_same_bits("tests/scenes/mix");
    expect_same_bits("tests/scenes/glass");
    expect_same_bits("tests/scenes/conductors");
}

/* Texture features (material_features: texture, srgb-texture, float-texture, texture-sampler,
 * bump-map): three quads under a point light, their uvs running to 2 so that wrap modes matter,
 * one bump-mapped (8-bit linear heights), one with an sRGB albedo clamped at its edges, one with a
 * float albedo. Under-reporting any feature leaves its lookup out of the specialised program (a
 * flat normal, raw sRGB codes, float bits read as bytes, repeat for clamp): other bits. */
Test(program_features, texture_specialised_kernels_render_the_same_bits, .timeout = 480)
{
    const char *dir = test_temp_dir();
    char path[512];
    unsigned char heights[16], colours[16 * 3];
    float floats[16 * 3];
    for (int i = 0; i < 16; i++) {
        heights[i] = (unsigned char)(i * 37 % 256);
        for (int c = 0; c < 3; c++) {
            colours[3 * i + c] = (unsigned char)((i * 53 + c * 90) % 256);
            floats[3 * i + c] = 0.05f * (float)((i * 7 + c * 3) % 16);
        }
    }
    snprintf(path, sizeof path, "%s/heights.png", dir);
    cr_assert(stbi_write_png(path, 4, 4, 1, heights, 4));
    snprintf(path, sizeof path, "%s/colours.png", dir);
    cr_assert(stbi_write_png(path, 4, 4, 3, colours, 12));
    snprintf(path, sizeof path, "%s/floats.hdr", dir);
    cr_assert(stbi_write_hdr(path, 4, 4, 3, floats));
    /* The MTL names the materials that the scene's JSON then defines (a usemtl the MTL lacks
     * would take the default material). */
    test_write_file(dir, "quads.mtl",
                    "newmtl bumpy\nKd 0.5 0.5 0.5\nnewmtl clamped\nKd 0.5 0.5 0.5\n"
                    "newmtl hdr\nKd 0.5 0.5 0.5\n");
    test_write_file(dir, "quads.obj",
                    "mtllib quads.mtl\nvt 0 0\nvt 2 0\nvt 2 2\nvt 0 2\n"
                    "v 0 0 1\nv 1 0 1\nv 1 0 0\nv 0 0 0\nusemtl bumpy\nf 1/1 2/2 3/3 4/4\n"
                    "v 1 0 1\nv 2 0 1\nv 2 0 0\nv 1 0 0\nusemtl clamped\nf 5/1 6/2 7/3 8/4\n"
                    "v 2 0 1\nv 3 0 1\nv 3 0 0\nv 2 0 0\nusemtl hdr\nf 9/1 10/2 11/3 12/4\n");
    const char *scene = test_write_file(
        dir, "scene.json",
        "{\"camera\": {\"eye\": [1.5, 2.5, 2.5], \"target\": [1.5, 0, 0.5], \"up\": [0, 1, 0], "
        "\"fov_y\": 50},"
        " \"textures\": {\"h\": {\"file\": \"heights.png\", \"encoding\": \"linear\"},"
        " \"c\": {\"file\": \"colours.png\", \"wrap\": \"clamp\"},"
        " \"f\": {\"file\": \"floats.hdr\"}},"
        " \"materials\": {\"bumpy\": {\"type\": \"diffuse\", \"bump_map\": \"h\","
        " \"bump_scale\": 0.05},"
        " \"clamped\": {\"type\": \"diffuse\", \"albedo\": \"c\"},"
        " \"hdr\": {\"type\": \"diffuse\", \"albedo\": \"f\"}},"
        " \"objects\": [{\"obj\": \"quads.obj\"}],"
        " \"lights\": [{\"type\": \"point\", \"position\": [1.5, 1.5, 1.0],"
        " \"intensity\": [8, 8, 8]}]}");
    expect_same_bits(scene);
}

/* The list's one expansion into options names every feature, on or off (features.h PT_FEATURE
 * refuses a misspelt name only then); the summary names the set's features in the list's order. */
Test(program_features, options_and_summary_follow_the_list)
{
    char options[PROGRAM_FEATURE_OPTIONS_SIZE], summary[PROGRAM_FEATURE_SUMMARY_SIZE];
    program_features_options(FEATURE_ENV | FEATURE_MIX, options);
    cr_expect(strstr(options, " -DPT_FEATURES_GIVEN") == options, "%s", options);
    cr_expect(strstr(options, " -DPT_FEATURE_ENV=1") && strstr(options, " -DPT_FEATURE_MIX=1") &&
                  strstr(options, " -DPT_FEATURE_INSTANCES=0") &&
                  strstr(options, " -DPT_FEATURE_ROUGH_CONDUCTOR=0"),
              "%s", options);
    program_features_options(PROGRAM_FEATURES_ALL, options);
    cr_expect_eq(strlen(options) + 1, PROGRAM_FEATURE_OPTIONS_SIZE, "%s", options);
    program_features_summary(FEATURE_MIX | FEATURE_ENV | FEATURE_INSTANCES, summary);
    cr_expect_str_eq(summary, "mix, env, instances");
    program_features_summary(0u, summary);
    cr_expect_str_eq(summary, "none");
    program_features_summary(PROGRAM_FEATURES_ALL & ~(ProgramFeatures)FEATURE_ENV, summary);
    cr_expect_lt(strlen(summary) + 1, PROGRAM_FEATURE_SUMMARY_SIZE, "%s", summary);
#define COUNT_ONE(name, word) +1
    enum { MATERIAL_FEATURE_COUNT = 0 MATERIAL_FEATURES(COUNT_ONE) };
#undef COUNT_ONE
    cr_expect_eq(MATERIAL_FEATURE_ALL, (1u << MATERIAL_FEATURE_COUNT) - 1u,
                 "material features keep the low bits: %#x", MATERIAL_FEATURE_ALL);
    cr_expect_leq(PROGRAM_FEATURE_COUNT, 32, "a ProgramFeatures set is 32 bits");
}

/* The features are part of the kernel cache's key: a program built for another set is compiled,
 * not loaded from the entry of the first. */
Test(program_features, kernel_cache_keys_on_the_features, .timeout = 480)
{
    setenv("XDG_CACHE_HOME", test_temp_dir(), 1);
    unsetenv("PT_NO_CACHE");
    const char *spec = getenv("PT_TEST_DEVICE") ? getenv("PT_TEST_DEVICE") : "cpu";
    ProgramFeatures sets[3] = {PROGRAM_FEATURES_ALL, PROGRAM_FEATURES_ALL & ~(ProgramFeatures)FEATURE_ENV,
                               PROGRAM_FEATURES_ALL};
    bool expect_hit[3] = {false, false, true};
    for (int i = 0; i < 3; i++) {
        Device dev;
        Error err = {0};
        cr_assert(device_open(&dev, spec, &err) && device_build(&dev, sets[i], NULL, NULL, &err),
                  "%s", err.message);
        cr_expect_eq(dev.cache_hit, expect_hit[i], "build %d: cache_hit %d", i, dev.cache_hit);
        cr_expect_eq(dev.features, sets[i]);
        device_close(&dev);
    }
}
