// SPDX-License-Identifier: MIT
/* Bad environment input (shared/DESIGN.md "Environment"): each is one clear error naming the file
 * or key, or, for unusable texels, a warning with their count and a map that still works. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <stb_image_write.h>

#include "io/image_io.h"
#include "scene/environment.h"
#include "scene/scene.h"
#include "support.h"

static const char *scene_with(const char *dir, const char *environment)
{
    test_write_file(dir, "t.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    char text[1024];
    snprintf(text, sizeof text, "{\"objects\": [{\"obj\": \"t.obj\"}], \"environment\": %s}\n", environment);
    return test_write_file(dir, "scene.json", text);
}

static void expect_load_error(const char *dir, const char *environment, const char *needle)
{
    Scene scene;
    Error err = {0};
    cr_assert_not(scene_load(scene_with(dir, environment), &scene, &err), "%s loaded", environment);
    cr_expect(strstr(err.message, needle), "%s: message \"%s\" does not name \"%s\"", environment,
              err.message, needle);
}

Test(environment_input, missing_corrupt_and_unknown_files_are_named)
{
    const char *dir = test_temp_dir();
    expect_load_error(dir, "{\"file\": \"nowhere.hdr\"}", "nowhere.hdr");
    test_write_file(dir, "broken.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 4 +X 8\nxx");
    expect_load_error(dir, "{\"file\": \"broken.hdr\"}", "broken.hdr");
    test_write_file(dir, "broken.exr", "v/1\x01 not an exr at all");
    expect_load_error(dir, "{\"file\": \"broken.exr\"}", "broken.exr");
    test_write_file(dir, "sky.png", "png");
    expect_load_error(dir, "{\"file\": \"sky.png\"}", "sky.png");
}

Test(environment_input, bad_keys_are_named)
{
    const char *dir = test_temp_dir();
    expect_load_error(dir, "{\"file\": \"a.hdr\", \"scale\": -1}", "environment.scale");
    expect_load_error(dir, "{\"scale\": 2}", "environment.file");
    expect_load_error(dir, "{\"file\": 3}", "environment.file");
    expect_load_error(dir, "{\"file\": \"a.hdr\", \"rotation\": \"east\"}", "environment.rotation");
    expect_load_error(dir, "{\"file\": \"a.hdr\", \"tint\": 1}", "tint");
    expect_load_error(dir, "\"sky.hdr\"", "environment");
}

Test(environment_input, a_black_map_cannot_light)
{
    const char *dir = test_temp_dir();
    float black[8 * 4 * 3] = {0};
    char path[512];
    snprintf(path, sizeof path, "%s/black.exr", dir);
    Error err = {0};
    cr_assert(image_write_exr(path, black, 8, 4, &err), "%s", err.message);
    expect_load_error(dir, "{\"file\": \"black.exr\"}", "zero total power");
    /* scale 0 makes any map black */
    float one[8 * 4 * 3];
    for (int i = 0; i < 8 * 4 * 3; i++)
        one[i] = 1.0f;
    snprintf(path, sizeof path, "%s/one.hdr", dir);
    cr_assert(stbi_write_hdr(path, 8, 4, 3, one));
    expect_load_error(dir, "{\"file\": \"one.hdr\", \"scale\": 0}", "zero total power");
}

/* NaN, Inf and negative texels become 0, with one warning giving their count. */
Test(environment_input, unusable_texels_are_clamped_with_one_warning)
{
    float rgb[4 * 2 * 3];
    for (int i = 0; i < 4 * 2 * 3; i++)
        rgb[i] = 1.0f;
    rgb[0] = NAN, rgb[4] = INFINITY, rgb[8] = -2.0f;
    Environment env;
    Error err = {0};
    warnings_set_quiet(true);
    int before = warning_count();
    cr_assert(environment_build(&env, rgb, 4, 2, 2.0f, 0.0f, "bad.exr", &err), "%s", err.message);
    cr_expect_eq(warning_count(), before + 1, "one warning");
    cr_expect_eq(env.texels[0].s[0], 0.0f);
    cr_expect_eq(env.texels[1].s[1], 0.0f);
    cr_expect_eq(env.texels[2].s[2], 0.0f);
    cr_expect_eq(env.texels[3].s[0], 2.0f, "scale multiplies");
    for (int t = 0; t < 8; t++)
        cr_expect(isfinite(env.texels[t].s[3]) && env.texels[t].s[3] >= 0.0f, "pdf of texel %d", t);
    environment_free(&env);
    warnings_set_quiet(false);
}
