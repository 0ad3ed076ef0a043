/* SPDX-License-Identifier: MIT */
/* support.h: helpers shared by the Criterion test binaries (tests/test_*.c). Tests run from the
 * repository root; the public assets are read from ../shared/assets when present. */
#ifndef PT_TEST_SUPPORT_H
#define PT_TEST_SUPPORT_H

#include <stdbool.h>
#include <stddef.h>

#include "accel/scene_bvh.h"
#include "device/device.h"
#include "scene/scene.h"
#include "render/scene_upload.h"
#include "render/wavefront.h"

#define ASSETS_DIR "../shared/assets"

/* True when ../shared/assets exists; tests that need it skip otherwise. */
bool assets_available(void);
#define REQUIRE_ASSETS()                                             \
    do {                                                             \
        if (!assets_available())                                     \
            cr_skip_test("../shared/assets not found: skipped");     \
    } while (0)

/* Opens the test device (PT_TEST_DEVICE, default "cpu" = PoCL) and builds the program: the
 * embedded cl/ sources plus every tests/cl/NAME.cl in name order, so all tests share one build (and
 * PoCL's kernel cache). Fails the test with the error on failure. */
Device *test_device(void);
/* The same built for a set of FEATURE_* bits (cl/shared/features.h), as pt builds it for a scene. */
Device *test_device_built_for(ProgramFeatures features);
void test_device_release(Device *dev);

/* The absolute path of the pt binary the tests run: PT_BIN (the Makefile sets it), else
 * build/pt. `make test` builds it, so a missing binary fails the test rather than skipping it. */
const char *test_pt_bin(void);

/* Reads a whole file; NULL when it cannot. */
char *test_read_file(const char *path, size_t *size);

/* A fresh temporary folder under /tmp; returned string is static per call site use. */
const char *test_temp_dir(void);
/* Writes text to dir/name (failing the test when it cannot) and returns that path, which stays
 * valid for the next 7 calls. */
const char *test_write_file(const char *dir, const char *name, const char *text);

/* The tests' program has every feature (test_device), so its traversal is two-level;
 * fixtures build the matching layout. */
#define PT_TESTS_TWO_LEVEL ((PROGRAM_FEATURES_ALL & FEATURE_INSTANCES) != 0)

/* A scene loaded onto the test device, ready to render many times. */
typedef struct {
    Device *dev;
    Scene scene;
    SceneBvh bvh;
    SceneBuffers buffers;
} RenderFixture;

/* width/height 0 keep the scene's film size. */
void render_fixture_open(RenderFixture *f, const char *scene_path, int width, int height);
/* The same with a choice of instancing (scene/scene.h). */
void render_fixture_open_with(RenderFixture *f, const char *scene_path, int width, int height,
                              InstancingMode instancing);
/* The same with the instances baked into one flat BVH (host/accel/scene_bvh.h BVH_FLAT), on a
 * program built as pt builds it for those (every feature but FEATURE_TLAS); the scene must have
 * instances (data.two_level), in INSTANCING_AUTO's layout. */
void render_fixture_open_flat(RenderFixture *f, const char *scene_path, int width, int height);
/* The same on a program built as pt builds it for scenes of one mesh level without cut-out
 * materials nor media (every feature but FEATURE_INSTANCES, FEATURE_CUTOUT and the media ones, the
 * one-level BVH): the
 * kernels that only such programs have (trace_paths_packets). */
void render_fixture_open_one_level(RenderFixture *f, const char *scene_path, int width, int height);
/* The same program built in parts as pt builds it (no kernels of the tests': program parts, the
 * wavefront's tail built on a thread of its own), without the kernel cache. */
void render_fixture_open_in_parts(RenderFixture *f, const char *scene_path, int width, int height);
void render_fixture_close(RenderFixture *f);
/* Renders quietly and asserts no sample was NaN/Inf; returns malloc'ed rgb. */
float *render_fixture_render(RenderFixture *f, RenderSettings s, RenderStats *stats_out);

#endif
