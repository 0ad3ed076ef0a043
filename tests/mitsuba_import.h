/* SPDX-License-Identifier: MIT */
/* mitsuba_import.h: what the Mitsuba importer tests (test_import_mitsuba.c,
 * test_import_mitsuba_materials.c) share: a scene body imported from a fresh folder, a quiet
 * sensor, and lookups in the imported JSON tree (header only). */
#ifndef PT_TEST_MITSUBA_IMPORT_H
#define PT_TEST_MITSUBA_IMPORT_H

#include <criterion/criterion.h>
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "scene/import_mitsuba.h"
#include "support.h"

static const char *scene_dir;

/* Imports <scene version="3.0.0"> body </scene> written to a fresh folder; the tree in s. */
static inline bool import_body(const char *body, ImportedScene *s, Error *err)
{
    scene_dir = test_temp_dir();
    char text[16384];
    snprintf(text, sizeof text, "<scene version=\"3.0.0\">\n%s\n</scene>\n", body);
    memset(s, 0, sizeof *s);
    return mitsuba_import(test_write_file(scene_dir, "scene.xml", text), s, err);
}

/* A sensor that draws no warning (box filter), for tests that count warnings. */
#define QUIET_SENSOR "<sensor type=\"perspective\"><film type=\"hdrfilm\"><rfilter type=\"box\"/></film></sensor>"


static inline cJSON *get(const cJSON *o, const char *path)
{
    char key[128];
    const cJSON *item = o;
    while (item && *path) {
        size_t n = strcspn(path, ".");
        snprintf(key, sizeof key, "%.*s", (int)n, path);
        item = cJSON_IsArray(item) ? cJSON_GetArrayItem(item, atoi(key))
                                   : cJSON_GetObjectItemCaseSensitive(item, key);
        path += n + (path[n] == '.');
    }
    cr_assert(item, "no %s in the imported tree", path);
    return (cJSON *)item;
}

static inline double num(const cJSON *o, const char *path) { return get(o, path)->valuedouble; }

static inline void expect_near(double got, double want, const char *what)
{
    cr_expect(fabs(got - want) < 1e-9 * fmax(1.0, fabs(want)), "%s: %.12g, expected %.12g", what, got, want);
}

/* The material of object i. */
static inline const cJSON *material_of(const ImportedScene *s, int i)
{
    const cJSON *object = cJSON_GetArrayItem(get(s->root, "objects"), i);
    cr_assert(object, "no object %d", i);
    return get(get(s->root, "materials"), get(object, "material")->valuestring);
}

#endif
