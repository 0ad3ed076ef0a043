// SPDX-License-Identifier: MIT
#define _XOPEN_SOURCE 700 /* realpath */
#include "support.h"

#include <criterion/criterion.h>
#include <dirent.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "accel/bvh_wide.h"

bool assets_available(void)
{
    struct stat st;
    return stat(ASSETS_DIR "/cornell-box/CornellBox-Original.obj", &st) == 0;
}

char *test_read_file(const char *path, size_t *size)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *data = malloc((size_t)n + 1);
    if (data && fread(data, 1, (size_t)n, f) != (size_t)n) {
        free(data);
        data = NULL;
    }
    fclose(f);
    if (data) {
        data[n] = '\0';
        if (size)
            *size = (size_t)n;
    }
    return data;
}

static int compare_names(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

/* Concatenates tests/cl/NAME.cl in name order, each after a #line marker. */
static char *test_kernel_source(void)
{
    DIR *dir = opendir("tests/cl");
    cr_assert(dir, "tests/cl not found: run the tests from the repository root");
    char *names[256];
    int count = 0;
    struct dirent *entry;
    while ((entry = readdir(dir)) && count < 256) {
        size_t n = strlen(entry->d_name);
        if (n > 3 && strcmp(entry->d_name + n - 3, ".cl") == 0)
            names[count++] = strdup(entry->d_name);
    }
    closedir(dir);
    qsort(names, (size_t)count, sizeof names[0], compare_names);
    size_t total = 1;
    char *source = calloc(1, 1);
    for (int i = 0; i < count; i++) {
        char path[512];
        snprintf(path, sizeof path, "tests/cl/%s", names[i]);
        size_t size = 0;
        char *text = test_read_file(path, &size);
        cr_assert(text, "cannot read %s", path);
        char marker[600];
        int m = snprintf(marker, sizeof marker, "\n#line 1 \"tests/cl/%s\"\n", names[i]);
        source = realloc(source, total + (size_t)m + size);
        memcpy(source + total - 1, marker, (size_t)m);
        memcpy(source + total - 1 + m, text, size);
        total += (size_t)m + size;
        source[total - 1] = '\0';
        free(text);
        free(names[i]);
    }
    return source;
}

/* Correctly rounded division and square root on every device the tests open, themselves or
 * through a pt they run (unless the caller chose): they compare a GPU's hits and values with the
 * host's, and pt's renders with their own, which NVIDIA's default rounding would move at
 * triangle edges (host/device/program.c). PoCL has them either way. Set before main, so that no
 * test opens a device or runs pt without it. */
__attribute__((constructor)) static void tests_ask_for_exact_maths(void)
{
    const char *value = getenv("PT_EXACT_MATHS");
    if (!value || !*value)
        setenv("PT_EXACT_MATHS", "1", 1);
}

Device *test_device(void) { return test_device_built_for(PROGRAM_FEATURES_ALL); }

Device *test_device_built_for(ProgramFeatures features)
{
    Device *dev = calloc(1, sizeof *dev);
    Error err = {0};
    const char *spec = getenv("PT_TEST_DEVICE");
    cr_assert(device_open(dev, spec ? spec : "cpu", &err), "device_open: %s", err.message);
    char *source = test_kernel_source();
    bool built = device_build(dev, features, source, "tests", &err);
    free(source);
    cr_assert(built, "device_build: %s", err.message);
    return dev;
}

void test_device_release(Device *dev)
{
    device_close(dev);
    free(dev);
}

const char *test_temp_dir(void)
{
    static char path[64];
    snprintf(path, sizeof path, "/tmp/pt-test-XXXXXX");
    cr_assert(mkdtemp(path), "mkdtemp failed");
    return path;
}

const char *test_write_file(const char *dir, const char *name, const char *text)
{
    static char paths[8][512];
    static int slot;
    char *path = paths[slot++ % 8];
    snprintf(path, 512, "%s/%s", dir, name);
    FILE *file = fopen(path, "wb");
    cr_assert(file, "cannot write %s", path);
    fputs(text, file);
    fclose(file);
    return path;
}

void render_fixture_open(RenderFixture *f, const char *scene_path, int width, int height)
{
    render_fixture_open_with(f, scene_path, width, height, INSTANCING_AUTO);
}

/* The fixture on dev, with the BVH's levels as dev's program walks them. */
static void render_fixture_load(RenderFixture *f, Device *dev, const char *scene_path, int width,
                                int height, InstancingMode instancing, BvhLevels levels)
{
    Error err = {0};
    f->dev = dev;
    cr_assert(scene_load_with(scene_path, instancing, &f->scene, &err), "scene_load %s: %s",
              scene_path, err.message);
    if (width)
        f->scene.desc.width = width;
    if (height)
        f->scene.desc.height = height;
    scene_accel_build(&f->bvh, &f->scene.data, f->dev, levels);
    cr_assert(scene_buffers_upload(f->dev, &f->scene.data, &f->bvh, &f->buffers, &err), "%s", err.message);
}

void render_fixture_open_with(RenderFixture *f, const char *scene_path, int width, int height,
                              InstancingMode instancing)
{
    render_fixture_load(f, test_device(), scene_path, width, height, instancing,
                        PT_TESTS_TWO_LEVEL ? BVH_TWO_LEVEL : BVH_ONE_LEVEL);
}

void render_fixture_open_flat(RenderFixture *f, const char *scene_path, int width, int height)
{
    render_fixture_load(f, test_device_built_for(PROGRAM_FEATURES_ALL & ~(ProgramFeatures)FEATURE_TLAS),
                        scene_path, width, height, INSTANCING_AUTO, BVH_FLAT);
    cr_assert(f->scene.data.two_level, "%s must have instances", scene_path);
}

/* The program pt builds for a one-level scene without cut-outs or media (the packet megakernel's). */
#define ONE_LEVEL_FEATURES \
    (PROGRAM_FEATURES_ALL & ~(ProgramFeatures)(FEATURE_INSTANCES | FEATURE_TLAS | FEATURE_CUTOUT | \
                                                FEATURE_MEDIA | FEATURE_GRID_MEDIA))

void render_fixture_open_one_level(RenderFixture *f, const char *scene_path, int width, int height)
{
    render_fixture_load(f, test_device_built_for(ONE_LEVEL_FEATURES), scene_path, width, height,
                        INSTANCING_AUTO, BVH_ONE_LEVEL);
    cr_assert(!f->scene.data.two_level, "%s must have one BVH level", scene_path);
}

void render_fixture_open_in_parts(RenderFixture *f, const char *scene_path, int width, int height)
{
    Device *dev = calloc(1, sizeof *dev);
    Error err = {0};
    const char *spec = getenv("PT_TEST_DEVICE");
    cr_assert(device_open(dev, spec ? spec : "cpu", &err), "device_open: %s", err.message);
    dev->use_cache = false;
    cr_assert(device_build(dev, ONE_LEVEL_FEATURES, NULL, NULL, &err), "device_build: %s", err.message);
    render_fixture_load(f, dev, scene_path, width, height, INSTANCING_AUTO, BVH_ONE_LEVEL);
    cr_assert(!f->scene.data.two_level, "%s must have one BVH level", scene_path);
}

void render_fixture_close(RenderFixture *f)
{
    scene_buffers_release(&f->buffers);
    scene_bvh_free(&f->bvh);
    scene_free(&f->scene);
    test_device_release(f->dev);
}

float *render_fixture_render(RenderFixture *f, RenderSettings s, RenderStats *stats_out)
{
    size_t n = (size_t)f->scene.desc.width * (size_t)f->scene.desc.height;
    float *rgb = malloc(n * 3 * sizeof *rgb);
    RenderStats stats;
    Error err = {0};
    cr_assert(wavefront_render(f->dev, &f->scene, &f->buffers, &s, rgb, &stats, &err), "%s", err.message);
    cr_assert_eq(stats.nonfinite, 0, "%u non-finite samples", stats.nonfinite);
    if (stats_out)
        *stats_out = stats;
    return rgb;
}

const char *test_pt_bin(void)
{
    static char path[PATH_MAX];
    const char *bin = getenv("PT_BIN");
    cr_assert(realpath(bin ? bin : "build/pt", path), "pt binary %s not found (make builds it; PT_BIN "
              "names another)", bin ? bin : "build/pt");
    return path;
}
