// SPDX-License-Identifier: MIT
/* Objects as meshes and instances (host/scene/load_objects.c, shared/DESIGN.md "Objects"): the same
 * file named twice is loaded once; objects without a transform and with a file of their own are
 * merged into one world-space mesh (one level); --instancing always / never; baking applies the
 * transform (mirrors keep their front); moving objects get a swept box that holds both ends. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "scene/load_objects.h"
#include "scene/scene.h"
#include "support.h"

/* An asymmetric triangle with a vertex normal: (0,0,0), (1,0,0), (0,2,0), normal +z (front: the
 * counter-clockwise side). */
static const char *const triangle_obj = "v 0 0 0\nv 1 0 0\nv 0 2 0\nvn 0 0 1\nf 1//1 2//1 3//1\n";

/* A SceneDesc of n objects naming the files given, with identity transforms. */
static void desc_init(SceneDesc *d, int n, const char *const *files)
{
    memset(d, 0, sizeof *d);
    snprintf(d->path, sizeof d->path, "%s/scene.json", test_temp_dir());
    d->num_objects = n;
    d->objects = calloc((size_t)n, sizeof *d->objects);
    d->object_options = calloc((size_t)n, sizeof *d->object_options);
    d->object_transforms = calloc((size_t)n, sizeof *d->object_transforms);
    cr_assert(d->objects && d->object_options && d->object_transforms);
    for (int i = 0; i < n; i++) {
        snprintf(d->objects[i], sizeof d->objects[i], "%s", files[i]);
        d->object_options[i].material = NO_MATERIAL;
        d->object_transforms[i].transform = d->object_transforms[i].transform_end = affine_identity();
    }
}

static void load(SceneData *data, const SceneDesc *d, InstancingMode mode)
{
    Error err = {0};
    scene_data_init(data);
    cr_assert(scene_load_objects(data, d, mode, NULL, &err), "%s", err.message);
    cr_assert(scene_data_finish(data, d->path, &err), "%s", err.message);
}

Test(instances_scene, same_file_twice_is_loaded_once)
{
    const char *dir = test_temp_dir();
    const char *a = test_write_file(dir, "a.obj", triangle_obj);
    char dotted[1100];
    snprintf(dotted, sizeof dotted, "%s/./a.obj", dir); /* another spelling of the same file */
    const char *files[] = {a, dotted};
    SceneDesc d;
    desc_init(&d, 2, files);
    d.object_transforms[1].transform = affine_translate(5, 0, 0);
    SceneData data;
    load(&data, &d, INSTANCING_AUTO);
    cr_expect_eq(data.num_triangles, 1, "one copy of the triangle, not %u", data.num_triangles);
    cr_expect_eq(data.num_meshes, 1);
    cr_expect_eq(data.num_instances, 2);
    cr_expect(data.two_level);
    cr_expect_eq(data.instances[0].object, 0);
    cr_expect_eq(data.instances[1].object, 1);
    cr_expect_float_eq(data.bounds_max[0], 6.0f, 1e-5f, "the moved instance's box is in the bounds");
    scene_data_free(&data);
    scene_desc_free(&d);
}

Test(instances_scene, untransformed_single_use_objects_stay_one_level)
{
    const char *dir = test_temp_dir();
    const char *files[] = {test_write_file(dir, "a.obj", triangle_obj),
                           test_write_file(dir, "b.obj", triangle_obj)};
    SceneDesc d;
    desc_init(&d, 2, files);
    SceneData data;
    load(&data, &d, INSTANCING_AUTO);
    cr_expect_eq(data.num_meshes, 1, "both merged into mesh 0");
    cr_expect_eq(data.num_instances, 1);
    cr_expect_not(data.two_level, "a v1 scene keeps the one-level path");
    cr_expect_eq(data.num_triangles, 2);
    scene_data_free(&data);
    /* always: each object its own instance. */
    load(&data, &d, INSTANCING_ALWAYS);
    cr_expect_eq(data.num_meshes, 2);
    cr_expect_eq(data.num_instances, 2);
    cr_expect(data.two_level);
    scene_data_free(&data);
    scene_desc_free(&d);
}

Test(instances_scene, material_override_makes_another_mesh)
{
    const char *a = test_write_file(test_temp_dir(), "a.obj", triangle_obj);
    const char *files[] = {a, a, a};
    SceneDesc d;
    desc_init(&d, 3, files);
    d.num_materials = 0;
    d.object_options[2].material = 0; /* an index is enough for the key */
    SceneData data;
    scene_data_init(&data);
    data.materials = calloc(1, sizeof *data.materials);
    data.materials[0] = material_default();
    data.num_materials = 1;
    Error err = {0};
    cr_assert(scene_load_objects(&data, &d, INSTANCING_AUTO, NULL, &err), "%s", err.message);
    cr_assert(scene_data_finish(&data, d.path, &err), "%s", err.message);
    cr_expect_eq(data.num_meshes, 2, "objects 0 and 1 share a mesh, object 2 has its own");
    cr_assert_eq(data.num_instances, 3);
    /* Object 2 is used once without a transform: merged (instance 0, object -1). */
    cr_expect_eq(data.instances[0].object, -1);
    cr_expect_eq(data.instances[0].mesh, 0);
    cr_expect_eq(data.instances[1].object, 0);
    cr_expect_eq(data.instances[2].object, 1);
    cr_expect_eq(data.instances[1].mesh, data.instances[2].mesh);
    cr_expect_neq(data.instances[1].mesh, 0);
    cr_expect_eq(data.material_ids[data.meshes[0].first_triangle], 0, "the override's material");
    scene_data_free(&data);
    scene_desc_free(&d);
}

/* never: the transform is baked into the vertices, and a mirror reverses the corners so that the
 * geometric normal (counter-clockwise) is the transformed normal (DESIGN "Objects"). */
Test(instances_scene, never_bakes_and_mirrors_keep_their_front)
{
    const char *a = test_write_file(test_temp_dir(), "a.obj", triangle_obj);
    const char *files[] = {a, a};
    SceneDesc d;
    desc_init(&d, 2, files);
    Affine mirror = affine_scale(1, 1, -1), shift = affine_translate(0, 0, 3);
    d.object_transforms[0].transform = affine_mul(&shift, &mirror);
    d.object_transforms[1].transform = affine_translate(2, 0, 0);
    SceneData data;
    load(&data, &d, INSTANCING_NEVER);
    cr_assert_not(data.two_level);
    cr_assert_eq(data.num_triangles, 2);
    for (uint32_t t = 0; t < 2; t++) {
        uint4 v = data.triangles[t].v;
        const float *p0 = data.positions[v.s[0]].s, *p1 = data.positions[v.s[1]].s,
                    *p2 = data.positions[v.s[2]].s;
        float e1[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
        float e2[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
        float nz = e1[0] * e2[1] - e1[1] * e2[0];
        float shading_z = data.normals[v.s[0]].s[2];
        /* Mirror in z: the normal (0,0,1) becomes (0,0,-1); so must the winding's. */
        float expected = t == 0 ? -1.0f : 1.0f;
        cr_expect(nz * expected > 0.0f, "triangle %u: geometric normal z %g, expected sign %g", t,
                  nz, expected);
        cr_expect_float_eq(shading_z, expected, 1e-6f, "triangle %u: vertex normal z", t);
        cr_expect_float_eq(p0[2], t == 0 ? 3.0f : 0.0f, 1e-6f);
    }
    scene_data_free(&data);
    scene_desc_free(&d);
}

Test(instances_scene, moving_objects_sweep_their_box)
{
    const char *a = test_write_file(test_temp_dir(), "a.obj", triangle_obj);
    const char *files[] = {a, a};
    SceneDesc d;
    desc_init(&d, 2, files);
    d.camera.shutter_open = 0.0f, d.camera.shutter_close = 1.0f;
    d.object_transforms[0].transform_end = affine_translate(0, 0, 10);
    d.object_transforms[0].has_end = true;
    /* transform_end equal to transform: static, the same as without it. */
    d.object_transforms[1].transform = d.object_transforms[1].transform_end = affine_translate(4, 0, 0);
    d.object_transforms[1].has_end = true;
    SceneData data;
    load(&data, &d, INSTANCING_AUTO);
    cr_assert_eq(data.num_instances, 2);
    cr_expect(data.instances[0].moving);
    cr_expect_not(data.instances[1].moving, "an unchanged transform_end does not move");
    cr_expect_eq(data.num_moving, 1);
    cr_expect_leq(data.instances[0].bounds_min[2], 0.0f);
    cr_expect_geq(data.instances[0].bounds_max[2], 10.0f, "the box reaches the closing pose");
    scene_data_free(&data);
    /* Without a shutter interval nothing moves. */
    d.camera.shutter_close = 0.0f;
    load(&data, &d, INSTANCING_AUTO);
    cr_expect_eq(data.num_moving, 0);
    scene_data_free(&data);
    scene_desc_free(&d);
}
