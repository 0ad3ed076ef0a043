// SPDX-License-Identifier: MIT
/* media_scene_fixture.h: what tests/test_media_scene*.c share: scenes written to a temporary folder
 * around a fog-filled cube (cube.obj and its variants), loaded with scene_load, and the check that
 * a bad one is refused with one line naming its key. Header-only (static functions) so that each
 * test binary builds from its own .c alone. */
#ifndef PT_TESTS_MEDIA_SCENE_FIXTURE_H
#define PT_TESTS_MEDIA_SCENE_FIXTURE_H

#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "media_fixtures.h"
#include "scene/scene.h"
#include "support.h"

static char g_dir[64];

static inline const char *write_file(const char *name, const char *text)
{
    if (!g_dir[0])
        snprintf(g_dir, sizeof g_dir, "%s", test_temp_dir());
    return test_write_file(g_dir, name, text);
}

/* cube.obj: a closed cube of 12 triangles (outward, counter-clockwise); open.obj: one triangle;
 * seams.obj: the same cube with one normal per face, so that corners at one position become
 * distinct vertices (closed all the same); finned.obj: the cube plus a triangle on one of its
 * edges (three faces there). */
static inline void write_meshes(void)
{
    static const char cube[] = "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\n"
                               "v -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n";
    static const char faces[] = "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\n"
                                "f 4 8 7\nf 4 7 3\nf 1 5 8\nf 1 8 4\nf 2 3 7\nf 2 7 6\n";
    char text[2048];
    snprintf(text, sizeof text, "%s%s", cube, faces);
    write_file("cube.obj", text);
    write_file("open.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    snprintf(text, sizeof text, "%s%s", cube,
             "vn 0 0 -1\nvn 0 0 1\nvn 0 -1 0\nvn 0 1 0\nvn -1 0 0\nvn 1 0 0\n"
             "f 1//1 3//1 2//1\nf 1//1 4//1 3//1\nf 5//2 6//2 7//2\nf 5//2 7//2 8//2\n"
             "f 1//3 2//3 6//3\nf 1//3 6//3 5//3\nf 4//4 8//4 7//4\nf 4//4 7//4 3//4\n"
             "f 1//5 5//5 8//5\nf 1//5 8//5 4//5\nf 2//6 3//6 7//6\nf 2//6 7//6 6//6\n");
    write_file("seams.obj", text);
    snprintf(text, sizeof text, "%sv 0 -3 -3\n%sf 1 2 9\n", cube, faces);
    write_file("finned.obj", text);
    snprintf(text, sizeof text, "%s%s", cube,
             "f 1 2 3\nf 1 3 4\nf 5 7 6\nf 5 8 7\nf 1 6 2\nf 1 5 6\n"
             "f 4 7 8\nf 4 3 7\nf 1 8 5\nf 1 4 8\nf 2 7 3\nf 2 6 7\n");
    write_file("inside_out.obj", text);
    /* An open floor and a closed subsurface ball in one mesh (as the Cornell box's OBJ). */
    write_file("room.mtl", "newmtl floor\nKd 0.5 0.5 0.5\nnewmtl skin\nKd 0.8 0.6 0.5\n");
    snprintf(text, sizeof text, "mtllib room.mtl\n%sv -5 -2 -5\nv 5 -2 -5\nv 5 -2 5\nv -5 -2 5\n"
             "usemtl skin\n%susemtl floor\nf 9 12 11\nf 9 11 10\n", cube, faces);
    write_file("room.obj", text);
}

static const char camera[] = "\"camera\": {\"eye\": [0, 0, 5], \"target\": [0, 0, 0]}";

/* Loads {camera, json} (with its own "objects", else one fog-filled cube). */
static inline bool load_with(const char *json, InstancingMode mode, Scene *scene, Error *err)
{
    write_meshes();
    char text[8192];
    snprintf(text, sizeof text, "{%s%s%s%s}", strstr(json, "\"camera\"") ? "" : camera,
             strstr(json, "\"camera\"") ? "" : ", ",
             strstr(json, "\"objects\"") ? "" : "\"objects\": [{\"obj\": \"cube.obj\"}], ", json);
    const char *path = write_file("scene.json", text);
    return scene_load_with(path, mode, scene, err);
}

static inline bool load(const char *json, Scene *scene, Error *err)
{
    return load_with(json, INSTANCING_AUTO, scene, err);
}

static inline void load_ok(const char *json, Scene *scene)
{
    Error err = {0};
    cr_assert(load(json, scene, &err), "%s", err.message);
}

/* The scene must be refused with one line holding `needle` (the key and what is wrong). */
static inline void refused(const char *json, const char *needle)
{
    Scene scene;
    Error err = {0};
    bool ok = load(json, &scene, &err);
    if (ok)
        scene_free(&scene);
    cr_assert(!ok, "accepted; expected an error with \"%s\"", needle);
    cr_expect(strstr(err.message, needle), "\"%s\" does not hold \"%s\"", err.message, needle);
    cr_expect(!strchr(err.message, '\n'), "more than one line: %s", err.message);
}

static inline void expect_rgb(const float4 v, float r, float g, float b, const char *what)
{
    cr_expect(fabsf(v.s[0] - r) <= 1e-6f * fmaxf(1.0f, fabsf(r)) &&
                  fabsf(v.s[1] - g) <= 1e-6f * fmaxf(1.0f, fabsf(g)) &&
                  fabsf(v.s[2] - b) <= 1e-6f * fmaxf(1.0f, fabsf(b)),
              "%s: [%g, %g, %g], expected [%g, %g, %g]", what, v.s[0], v.s[1], v.s[2], r, g, b);
}

/* A Mitsuba .vol of res^3 float32 densities over the unit cube: value(i) at voxel i. */
static inline void write_vol(const char *name, int res, float (*value)(int))
{
    char path[256];
    snprintf(path, sizeof path, "%s/%s", g_dir, name);
    float *values = malloc((size_t)res * res * res * sizeof *values);
    cr_assert(values);
    for (int i = 0; i < res * res * res; i++)
        values[i] = value(i);
    const float lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    write_vol_file(path, res, res, res, values, lo, hi);
    free(values);
}

static inline float ramp(int i) { return (float)(i % 7) * 0.5f; }

#define FOG(body) "\"media\": {\"fog\": {\"type\": \"homogeneous\"" body "}}"

#endif
