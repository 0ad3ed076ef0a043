// SPDX-License-Identifier: MIT
/* Smooth shading for meshes without vn (objects[i].smooth, host/scene/vertex_normals.c): the
 * default stays flat, smooth: true gives each vertex the sum of its triangles' normals weighted by
 * area times corner angle, shared across UV seams, and leaves corners that have vn alone. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "scene/scene.h"
#include "support.h"

/* Loads `obj` as the only object of a scene, with `options` added to the object. */
static void load(const char *obj, const char *options, Scene *scene)
{
    const char *dir = test_temp_dir();
    test_write_file(dir, "m.obj", obj);
    char json[512];
    snprintf(json, sizeof json, "{\"objects\": [{\"obj\": \"m.obj\"%s}]}", options);
    const char *path = test_write_file(dir, "scene.json", json);
    Error err = {0};
    cr_assert(scene_load(path, scene, &err), "%s", err.message);
}

/* The normal of the vertex at `position` in triangle t. */
static const float *normal_at(const SceneData *d, uint32_t t, const float position[3])
{
    for (int k = 0; k < 3; k++) {
        uint32_t v = d->triangles[t].v.s[k];
        if (memcmp(d->positions[v].s, position, 3 * sizeof(float)) == 0)
            return d->normals[v].s;
    }
    cr_assert_fail("triangle %u has no vertex at (%g, %g, %g)", t, position[0], position[1], position[2]);
    return NULL;
}

/* Two triangles meeting at the origin: T1 in z = 0 (normal +z, area 2, angle 90 degrees at the
 * origin) and T2 in x = 0 (normal +x, area 0.5, angle 45 degrees). Area x angle weights give
 * (0.5 * pi/4, 0, 2 * pi/2) ~ (1, 0, 8); angle alone would give (1, 0, 2), area alone (1, 0, 4). */
static const char *hinge = "v 0 0 0\nv 2 0 0\nv 0 2 0\nv 0 1 0\nv 0 1 1\nf 1 2 3\nf 1 4 5\n";

Test(vertex_normals, default_is_flat)
{
    Scene scene;
    load(hinge, "", &scene);
    for (uint32_t t = 0; t < scene.data.num_triangles; t++)
        cr_expect_eq(scene.data.triangles[t].v.s[3] & TRIANGLE_HAS_NORMALS, 0u, "triangle %u", t);
    scene_free(&scene);
    load(hinge, ", \"smooth\": false", &scene);
    cr_expect_eq(scene.data.triangles[0].v.s[3] & TRIANGLE_HAS_NORMALS, 0u);
    scene_free(&scene);
}

Test(vertex_normals, area_and_angle_weighted)
{
    Scene scene;
    load(hinge, ", \"smooth\": true", &scene);
    const SceneData *d = &scene.data;
    for (uint32_t t = 0; t < d->num_triangles; t++)
        cr_expect(d->triangles[t].v.s[3] & TRIANGLE_HAS_NORMALS, "triangle %u is smooth", t);
    const float origin[3] = {0, 0, 0}, far[3] = {2, 0, 0}, top[3] = {0, 1, 1};
    float len = sqrtf(65.0f);
    for (uint32_t t = 0; t < 2; t++) {
        const float *n = normal_at(d, t, origin);
        cr_expect(fabsf(n[0] - 1.0f / len) < 1e-5f && fabsf(n[1]) < 1e-6f && fabsf(n[2] - 8.0f / len) < 1e-5f,
                  "origin in triangle %u: (%g, %g, %g), expected (1, 0, 8)/sqrt(65)", t, n[0], n[1], n[2]);
    }
    const float *n = normal_at(d, 0, far);
    cr_expect(n[0] == 0.0f && n[1] == 0.0f && n[2] == 1.0f, "a vertex of T1 only: its face normal");
    n = normal_at(d, 1, top);
    cr_expect(n[0] == 1.0f && n[1] == 0.0f && n[2] == 0.0f, "a vertex of T2 only: its face normal");
    scene_free(&scene);
}

Test(vertex_normals, shared_across_uv_seams_and_vn_kept)
{
    /* The hinge again, with T2's corner at the origin using another vt (a seam): both copies of
     * the origin get the same normal. A third triangle with vn keeps its normals. */
    Scene scene;
    load("v 0 0 0\nv 2 0 0\nv 0 2 0\nv 0 1 0\nv 0 1 1\nv 5 5 5\nvt 0 0\nvt 1 0\nvn 0 1 0\n"
         "f 1/1 2/1 3/1\nf 1/2 4/1 5/1\nf 6//1 2//1 3//1\n", ", \"smooth\": true", &scene);
    const SceneData *d = &scene.data;
    const float origin[3] = {0, 0, 0}, far[3] = {2, 0, 0};
    const float *a = normal_at(d, 0, origin), *b = normal_at(d, 1, origin);
    cr_expect(d->triangles[0].v.s[0] != d->triangles[1].v.s[0], "two vertices at the origin (seam)");
    cr_expect(memcmp(a, b, 3 * sizeof(float)) == 0, "(%g %g %g) vs (%g %g %g)", a[0], a[1], a[2],
              b[0], b[1], b[2]);
    cr_expect(a[2] > 0.99f && a[0] > 0.1f, "the hinge's weighted normal: (%g, %g, %g)", a[0], a[1], a[2]);
    const float *kept = normal_at(d, 2, far);
    cr_expect(kept[0] == 0.0f && kept[1] == 1.0f && kept[2] == 0.0f, "vn kept: (%g, %g, %g)", kept[0],
              kept[1], kept[2]);
    scene_free(&scene);
}

Test(vertex_normals, smooth_must_be_a_boolean)
{
    const char *dir = test_temp_dir();
    test_write_file(dir, "m.obj", hinge);
    const char *path = test_write_file(dir, "scene.json", "{\"objects\": [{\"obj\": \"m.obj\", \"smooth\": 1}]}");
    SceneDesc desc;
    Error err = {0};
    cr_expect_not(scene_desc_load(path, &desc, &err));
    cr_expect(strstr(err.message, "objects[0].smooth") && strstr(err.message, "true or false"), "%s",
              err.message);
}
