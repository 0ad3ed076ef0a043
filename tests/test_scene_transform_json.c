// SPDX-License-Identifier: MIT
/* objects[i].transform / transform_end and camera.shutter in the scene file
 * (host/scene/transform_json.c, camera_json.c): operations compose in the order written, rotate
 * and matrix follow DESIGN's sense and layout, transform_end needs a shutter interval (else a
 * warning and a static object), and every bad value is one error naming the object and key. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "scene/scene.h"
#include "support.h"

static char g_dir[64];

/* Reads the scene {"camera": camera, "objects": objects} (camera may be ""). */
static bool load_desc(const char *camera, const char *objects, SceneDesc *desc, Error *err)
{
    if (!g_dir[0])
        snprintf(g_dir, sizeof g_dir, "%s", test_temp_dir());
    char text[8192];
    snprintf(text, sizeof text,
             "{\"camera\": {\"eye\": [0, 0, 5], \"target\": [0, 0, 0]%s%s},\n \"objects\": %s}",
             camera[0] ? ", " : "", camera, objects);
    return scene_desc_load(test_write_file(g_dir, "scene.json", text), desc, err);
}

/* The composed transform of one object with the given "transform" list. */
static Affine transform_of(const char *list)
{
    char objects[4096];
    snprintf(objects, sizeof objects, "[{\"obj\": \"a.obj\", \"transform\": %s}]", list);
    SceneDesc desc;
    Error err = {0};
    cr_assert(load_desc("", objects, &desc, &err), "%s: %s", list, err.message);
    Affine a = desc.object_transforms[0].transform;
    cr_expect_not(desc.object_transforms[0].has_end);
    scene_desc_free(&desc);
    return a;
}

static void expect_maps(const char *list, double x, double y, double z, double ex, double ey,
                        double ez)
{
    Affine a = transform_of(list);
    double p[3] = {x, y, z};
    affine_point(&a, p, p);
    cr_expect(fabs(p[0] - ex) < 1e-12 && fabs(p[1] - ey) < 1e-12 && fabs(p[2] - ez) < 1e-12,
              "%s maps (%g, %g, %g) to (%.15g, %.15g, %.15g), expected (%g, %g, %g)", list, x, y,
              z, p[0], p[1], p[2], ex, ey, ez);
}

Test(transform_json, operations_apply_in_the_order_written)
{
    expect_maps("[{\"scale\": 2}, {\"translate\": [1, 0, 0]}]", 1, 0, 0, 3, 0, 0);
    expect_maps("[{\"translate\": [1, 0, 0]}, {\"scale\": 2}]", 1, 0, 0, 4, 0, 0);
    expect_maps("[{\"scale\": [1, 2, 3]}]", 1, 1, 1, 1, 2, 3);
    expect_maps("[{\"translate\": [0, 0, 1]}, {\"rotate\": {\"axis\": [0, 1, 0], \"angle\": 90}}]",
                0, 0, 0, 1, 0, 0);
    expect_maps("[{\"rotate\": {\"axis\": [0, 1, 0], \"angle\": 90}}, {\"translate\": [0, 0, 1]}]",
                0, 0, 0, 0, 0, 1);
    expect_maps("[]", 1, 2, 3, 1, 2, 3);
}

Test(transform_json, rotation_is_counter_clockwise_seen_from_the_axis_tip)
{
    expect_maps("[{\"rotate\": {\"axis\": [0, 0, 1], \"angle\": 90}}]", 1, 0, 0, 0, 1, 0);
    expect_maps("[{\"rotate\": {\"axis\": [0, 1, 0], \"angle\": 90}}]", 0, 0, 1, 1, 0, 0);
    expect_maps("[{\"rotate\": {\"axis\": [3, 0, 0], \"angle\": 90}}]", 0, 1, 0, 0, 0, 1);
    expect_maps("[{\"rotate\": {\"angle\": -90, \"axis\": [0, 0, 1]}}]", 1, 0, 0, 0, -1, 0);
}

Test(transform_json, matrix_is_row_major_with_column_vectors)
{
    const char *m = "[{\"matrix\": [0, -1, 0, 1,  1, 0, 0, 2,  0, 0, 1, 3,  0, 0, 0, 1]}]";
    expect_maps(m, 0, 0, 0, 1, 2, 3);
    expect_maps(m, 1, 0, 0, 1, 3, 3);
    expect_maps("[{\"matrix\": [1, 0, 0, 0,  0, 1, 0, 0,  0, 0, 1, 0,  0, 0, 0, 1]}, "
                "{\"translate\": [1, 1, 1]}, {\"matrix\": [2, 0, 0, 0,  0, 2, 0, 0,  0, 0, 2, 0,  0, 0, 0, 1]}]",
                1, 0, 0, 4, 2, 2);
    Affine mirror = transform_of("[{\"scale\": [-1, 1, 1]}]");
    cr_expect(affine_det(&mirror) < 0, "a mirror is accepted, det < 0");
}

Test(transform_json, transform_end_with_a_shutter_moves)
{
    SceneDesc desc;
    Error err = {0};
    cr_assert(load_desc("\"shutter\": [0, 1]",
                        "[{\"obj\": \"a.obj\"}, {\"obj\": \"a.obj\", \"transform\": [{\"translate\": [1, 0, 0]}],"
                        " \"transform_end\": [{\"translate\": [2, 0, 0]}]}]", &desc, &err), "%s", err.message);
    cr_expect(desc.camera.shutter_open == 0.0f && desc.camera.shutter_close == 1.0f);
    const ObjectTransform *still = &desc.object_transforms[0], *moving = &desc.object_transforms[1];
    cr_expect(affine_is_identity(&still->transform) && affine_is_identity(&still->transform_end) &&
              !still->has_end, "an object without a transform stays at the identity");
    cr_expect(moving->has_end);
    cr_expect(moving->transform.m[0][3] == 1.0 && moving->transform_end.m[0][3] == 2.0);
    scene_desc_free(&desc);
}

Test(transform_json, transform_end_without_a_shutter_is_a_warning)
{
    const char *cameras[] = {"", "\"shutter\": [0.5, 0.5]"};
    warnings_set_quiet(true);
    for (int i = 0; i < 2; i++) {
        SceneDesc desc;
        Error err = {0};
        int warnings = warning_count();
        cr_assert(load_desc(cameras[i],
                            "[{\"obj\": \"a.obj\", \"transform\": [{\"translate\": [1, 0, 0]}],"
                            " \"transform_end\": [{\"translate\": [2, 0, 0]}]}]", &desc, &err),
                  "%s", err.message);
        cr_expect_eq(warning_count(), warnings + 1, "camera {%s}: one warning", cameras[i]);
        const ObjectTransform *o = &desc.object_transforms[0];
        cr_expect(!o->has_end && affine_equal(&o->transform, &o->transform_end) &&
                  o->transform.m[0][3] == 1.0, "camera {%s}: static at transform", cameras[i]);
        scene_desc_free(&desc);
    }
    warnings_set_quiet(false);
}

static void expect_error(const char *camera, const char *objects, const char *needle)
{
    SceneDesc desc;
    Error err = {0};
    warnings_set_quiet(true);
    bool ok = load_desc(camera, objects, &desc, &err);
    warnings_set_quiet(false);
    if (ok)
        scene_desc_free(&desc);
    cr_expect_not(ok, "%s / %s: accepted", camera, objects);
    cr_expect(strstr(err.message, needle) != NULL, "%s: message \"%s\" lacks \"%s\"", objects,
              err.message, needle);
    cr_expect(strchr(err.message, '\n') == NULL, "one line: %s", err.message);
}

/* objects[1] gets the bad list as "key" (object 0 is a plain one, so the index must be right). */
static void expect_bad(const char *key, const char *list, const char *needle)
{
    char objects[4096];
    snprintf(objects, sizeof objects, "[{\"obj\": \"a.obj\"}, {\"obj\": \"a.obj\", \"%s\": %s}]", key, list);
    expect_error("\"shutter\": [0, 1]", objects, needle);
}

Test(transform_json, bad_transforms_name_the_object_and_key)
{
    const char *keys[] = {"transform", "transform_end"};
    for (int k = 0; k < 2; k++) {
        const char *key = keys[k];
        char needle[128];
#define BAD(list, suffix)                                                                          \
    do {                                                                                           \
        snprintf(needle, sizeof needle, "objects[1].%s%s", key, suffix);                          \
        expect_bad(key, list, needle);                                                             \
    } while (0)
        BAD("{\"scale\": 2}", ": expected an array");
        BAD("[{\"scale\": 0}]", "[0].scale");
        BAD("[{\"translate\": [1, 0, 0]}, {\"scale\": [1, 0, 1]}]", "[1].scale");
        BAD("[{\"scale\": 1e999}]", "[0].scale");
        BAD("[{\"translate\": [1, 1e999, 0]}]", "[0].translate");
        BAD("[{\"translate\": [1, 0]}]", "[0].translate");
        BAD("[{\"translate\": [1, \"x\", 0]}]", "[0].translate");
        BAD("[{\"rotate\": {\"axis\": [0, 0, 0], \"angle\": 30}}]", "[0].rotate.axis");
        BAD("[{\"rotate\": {\"axis\": [0, 1, 0], \"angle\": -1e999}}]", "[0].rotate.angle");
        BAD("[{\"rotate\": {\"axis\": [0, 1, 0]}}]", "[0].rotate.angle");
        BAD("[{\"rotate\": {\"angle\": 3}}]", "[0].rotate.axis");
        BAD("[{\"rotate\": {\"axis\": [0, 1, 0], \"angle\": 3, \"pivot\": [0, 0, 0]}}]",
            "[0].rotate.pivot");
        BAD("[{\"rotate\": 30}]", "[0].rotate");
        BAD("[{\"shear\": 1}]", "[0].shear");
        BAD("[{\"scale\": 2, \"translate\": [1, 0, 0]}]", "[0]");
        BAD("[{}]", "[0]");
        BAD("[[1, 0, 0]]", "[0]");
        BAD("[{\"matrix\": [1, 0, 0, 0,  0, 1, 0, 0,  0, 0, 1, 0]}]", "[0].matrix");
        BAD("[{\"matrix\": [1, 0, 0, 0,  0, 1, 0, 0,  0, 0, 1, 0,  0, 0, 1, 1]}]", "[0].matrix");
        BAD("[{\"matrix\": [1, 0, 0, 0,  0, 1, 0, 0,  0, 0, 1, 0,  0, 0, 0, 2]}]", "[0].matrix");
        BAD("[{\"matrix\": [1, 2, 3, 0,  2, 4, 6, 0,  0, 0, 1, 0,  0, 0, 0, 1]}]", "[0].matrix");
        BAD("[{\"matrix\": [1, 0, 0, 1e999,  0, 1, 0, 0,  0, 0, 1, 0,  0, 0, 0, 1]}]", "[0].matrix");
        /* Each operation regular, the composition singular or overflowing. */
        BAD("[{\"scale\": 1e-200}, {\"scale\": 1e-200}]", ": the composed transform is singular");
        BAD("[{\"translate\": [1e308, 0, 0]}, {\"scale\": 1e10}]", ": the composed transform is not finite");
        BAD("[{\"scale\": 1e200}, {\"scale\": 1e200}]", ": the composed transform is not finite");
        BAD("[{\"matrix\": [1e200, 0, 0, 0,  0, 1e200, 0, 0,  0, 0, 1, 0,  0, 0, 0, 1]}]", "[0].matrix: is not finite");
        /* Finite, but past float once it places a point (a motion's bound of inf hung the BVH). */
        BAD("[{\"translate\": [0, 1e300, 0]}]", ": the composed transform has an entry 1e+300 beyond");
        BAD("[{\"scale\": 1e16}]", ": the composed transform has an entry 1e+16 beyond");
#undef BAD
    }
}

Test(transform_json, bad_shutters_are_errors)
{
    const char *objects = "[{\"obj\": \"a.obj\"}]";
    expect_error("\"shutter\": [1, 0]", objects, "camera.shutter: [1, 0]");
    expect_error("\"shutter\": [0]", objects, "camera.shutter: expected");
    expect_error("\"shutter\": [0, 1, 2]", objects, "camera.shutter: expected");
    expect_error("\"shutter\": 1", objects, "camera.shutter: expected");
    expect_error("\"shutter\": [0, 1e999]", objects, "camera.shutter: inf");
    expect_error("\"shutter\": [\"a\", 1]", objects, "camera.shutter: expected");
}
