// SPDX-License-Identifier: MIT
/* Flattening (host/scene/scene_data.c): meshes appended one after another land at their offsets, corners
 * with the same (v, vt, vn) share one vertex, materials map from MTL as the README says, the default
 * material is added once, lights are exactly the emissive triangles, and bad or missing inputs give
 * the documented error or warning. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include <stb_image_write.h>

#include "base/clock.h"
#include "io/obj_loader.h"
#include "scene/scene.h"
#include "scene/scene_data.h"
#include "support.h"

static ObjMaterial obj_material(const char *name, float r, float g, float b)
{
    ObjMaterial m = {.kd = {r, g, b}, .ni = 1.0f, .d = 1.0f, .illum = 2};
    snprintf(m.name, sizeof m.name, "%s", name);
    return m;
}

/* Mesh 1: a quad (4 positions, 4 uvs, 1 normal) as two triangles sharing the diagonal's corners. */
static float quad_positions[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
static float quad_uvs[] = {0, 0, 1, 0, 1, 1, 0, 1};
static float quad_normals[] = {0, 0, 1};
static int32_t quad_corners[] = {0, 0, 0, 1, 1, 0, 2, 2, 0, /* */ 0, 0, 0, 2, 2, 0, 3, 3, 0};
static int32_t quad_materials[] = {0, 1};

/* Mesh 2: one position triple used twice, with a different vt at corner 0 the second time, then a
 * triangle without normals or uvs on the default material. */
static float tri_positions[] = {5, 5, 5, 6, 5, 5, 5, 6, 5, 7, 7, 7};
static float tri_uvs[] = {0.25f, 0.5f, 0.75f, 0.5f};
static float tri_normals[] = {0, 1, 0};
static int32_t tri_corners[] = {0, 0, 0, 1, 0, 0, 2, 0, 0, /* */ 0, 1, 0, 1, 0, 0, 2, 0, 0,
                                /* */ 1, -1, -1, 3, -1, -1, 2, -1, 0};
static int32_t tri_materials[] = {0, 0, -1};

static void make_meshes(Mesh *quad, Mesh *tri, ObjMaterial quad_mats[2], ObjMaterial *tri_mat,
                        const char *texture1, const char *texture2)
{
    quad_mats[0] = obj_material("red", 0.8f, 0.1f, 0.1f);
    quad_mats[1] = obj_material("textured", 0.5f, 0.5f, 0.5f);
    snprintf(quad_mats[1].map_kd, sizeof quad_mats[1].map_kd, "%s", texture1);
    *tri_mat = obj_material("blue", 0.1f, 0.1f, 0.9f);
    snprintf(tri_mat->map_kd, sizeof tri_mat->map_kd, "%s", texture2);
    *quad = (Mesh){.positions = quad_positions, .num_positions = 4, .texcoords = quad_uvs,
                      .num_texcoords = 4, .normals = quad_normals, .num_normals = 1,
                      .corners = quad_corners, .material_ids = quad_materials, .num_triangles = 2,
                      .num_faces = 1, .materials = quad_mats, .num_materials = 2};
    *tri = (Mesh){.positions = tri_positions, .num_positions = 4, .texcoords = tri_uvs,
                     .num_texcoords = 2, .normals = tri_normals, .num_normals = 1,
                     .corners = tri_corners, .material_ids = tri_materials, .num_triangles = 3,
                     .num_faces = 3, .materials = tri_mat, .num_materials = 1};
}

static uint32_t corner(const SceneData *d, uint32_t tri, int k) { return d->triangles[tri].v.s[k]; }

Test(flatten, two_meshes_land_at_their_offsets)
{
    const char *dir = test_temp_dir();
    char tex1[512], tex2[512];
    snprintf(tex1, sizeof tex1, "%s/a.png", dir);
    snprintf(tex2, sizeof tex2, "%s/b.png", dir);
    const unsigned char px[12] = {0};
    cr_assert(stbi_write_png(tex1, 2, 2, 3, px, 6));
    cr_assert(stbi_write_png(tex2, 3, 1, 3, px, 9));
    Mesh quad, tri;
    ObjMaterial quad_mats[2], tri_mat;
    make_meshes(&quad, &tri, quad_mats, &tri_mat, tex1, tex2);

    SceneData d;
    scene_data_init(&d);
    Error err = {0};
    cr_assert(scene_data_append_mesh(&d, &quad, "quad.obj", &err), "%s", err.message);
    uint32_t quad_vertices = d.num_vertices;
    cr_expect_eq(quad_vertices, 4, "the quad's diagonal corners are shared");
    cr_assert(scene_data_append_mesh(&d, &tri, "tri.obj", &err), "%s", err.message);
    cr_assert(scene_data_finish(&d, "test", &err), "%s", err.message);

    /* Mesh 2: 3 corners, the corner with the other vt, and the 3 corners of the last triangle
     * (their (v, vt, vn) triples differ from every earlier one). */
    cr_expect_eq(d.num_vertices, 4 + 4 + 3);
    cr_expect_eq(d.num_triangles, 5);
    for (uint32_t t = 2; t < 5; t++)
        for (int k = 0; k < 3; k++)
            cr_expect(corner(&d, t, k) >= quad_vertices && corner(&d, t, k) < d.num_vertices,
                      "triangle %u corner %d -> %u", t, k, corner(&d, t, k));
    for (uint32_t t = 0; t < 2; t++)
        for (int k = 0; k < 3; k++)
            cr_expect(corner(&d, t, k) < quad_vertices);

    /* Same (v, vt, vn) -> one vertex; a different vt -> a second vertex at the same position. */
    cr_expect_eq(corner(&d, 0, 0), corner(&d, 1, 0));
    cr_expect_eq(corner(&d, 0, 2), corner(&d, 1, 1));
    cr_expect_neq(corner(&d, 2, 0), corner(&d, 3, 0));
    cr_expect_eq(corner(&d, 2, 1), corner(&d, 3, 1));
    uint32_t va = corner(&d, 2, 0), vb = corner(&d, 3, 0);
    cr_expect(memcmp(&d.positions[va], &d.positions[vb], sizeof(float4)) == 0);
    cr_expect_eq(d.uvs[va].s[0], 0.25f);
    cr_expect_eq(d.uvs[vb].s[0], 0.75f);
    cr_expect_eq(d.positions[corner(&d, 0, 2)].s[0], 1.0f);
    cr_expect_eq(d.positions[corner(&d, 0, 2)].s[1], 1.0f);
    cr_expect_eq(d.positions[corner(&d, 0, 2)].s[3], 0.0f, "w is 0");
    cr_expect_eq(d.normals[corner(&d, 0, 0)].s[2], 1.0f);

    /* Flags: all corners with vn and vt, or none. */
    cr_expect_eq(d.triangles[0].v.s[3], TRIANGLE_HAS_NORMALS | TRIANGLE_HAS_UVS);
    cr_expect_eq(d.triangles[3].v.s[3], TRIANGLE_HAS_NORMALS | TRIANGLE_HAS_UVS);
    cr_expect_eq(d.triangles[4].v.s[3], 0u, "corners without vt/vn (one has vn): no flags");

    /* Materials: mesh 2's ids offset by mesh 1's count; one default material at the end. */
    cr_assert_eq(d.num_materials, 2 + 1 + 1);
    cr_expect_eq(d.material_ids[0], 0);
    cr_expect_eq(d.material_ids[1], 1);
    cr_expect_eq(d.material_ids[2], 2);
    cr_expect_eq(d.material_ids[3], 2);
    cr_expect_eq(d.material_ids[4], 3);
    cr_expect_eq(d.materials[2].base.s[2], 0.9f);
    cr_expect_eq(d.materials[3].base.s[0], 0.8f, "default grey");
    cr_expect_eq(d.materials[3].type, MATERIAL_DIFFUSE);
    cr_expect_eq(d.materials[3].tex[MATERIAL_TEX_BASE], NO_TEXTURE);

    /* Textures: one per material that has one, disjoint, inside the texel buffer. */
    cr_assert_eq(d.textures.count, 2);
    cr_expect_eq(d.materials[0].tex[MATERIAL_TEX_BASE], NO_TEXTURE);
    cr_expect_eq(d.materials[1].tex[MATERIAL_TEX_BASE], 0);
    cr_expect_eq(d.materials[2].tex[MATERIAL_TEX_BASE], 1);
    TextureInfo t0 = d.textures.infos[0], t1 = d.textures.infos[1];
    cr_expect_eq(t0.width * t0.height, 4);
    cr_expect_eq(t1.width * t1.height, 3);
    cr_expect(t0.offset + t0.width * t0.height <= t1.offset || t1.offset + 3 <= t0.offset);
    cr_expect(t0.offset + 4 <= d.textures.num_texels && t1.offset + 3 <= d.textures.num_texels);

    cr_expect_eq(d.bounds_min[0], 0.0f);
    cr_expect_eq(d.bounds_max[0], 7.0f);
    cr_expect_eq(d.bounds_max[2], 7.0f);
    cr_expect_eq(d.num_emissive, 0);
    scene_data_free(&d);
}

Test(flatten, unusable_normals_make_the_triangle_flat)
{
    float normals[] = {0, 0, 0, NAN, 0, 1};
    int32_t corners[] = {0, -1, 0, 1, -1, 1, 2, -1, 1, /* */ 0, -1, 1, 1, -1, 1, 2, -1, 1};
    int32_t materials[] = {-1, -1};
    Mesh mesh = {.positions = quad_positions, .num_positions = 4, .normals = normals,
                    .num_normals = 2, .corners = corners, .material_ids = materials,
                    .num_triangles = 2};
    SceneData d;
    scene_data_init(&d);
    Error err = {0};
    cr_assert(scene_data_append_mesh(&d, &mesh, "n.obj", &err), "%s", err.message);
    cr_assert(scene_data_finish(&d, "n.obj", &err), "%s", err.message);
    cr_expect_eq(d.triangles[0].v.s[3], 0u, "zero normal: flat");
    cr_expect_eq(d.triangles[1].v.s[3], 0u, "NaN normal: flat");
    for (uint32_t v = 0; v < d.num_vertices; v++)
        for (int i = 0; i < 3; i++)
            cr_expect(isfinite(d.normals[v].s[i]));
    cr_expect_eq(d.num_materials, 1, "default material added once");
    scene_data_free(&d);
}

Test(flatten, default_material_is_added_once_per_scene)
{
    int32_t corners[] = {0, -1, -1, 1, -1, -1, 2, -1, -1};
    int32_t materials[] = {-1};
    Mesh mesh = {.positions = quad_positions, .num_positions = 4, .corners = corners,
                    .material_ids = materials, .num_triangles = 1};
    SceneData d;
    scene_data_init(&d);
    Error err = {0};
    cr_assert(scene_data_append_mesh(&d, &mesh, "a.obj", &err), "%s", err.message);
    cr_assert(scene_data_append_mesh(&d, &mesh, "b.obj", &err), "%s", err.message);
    cr_assert(scene_data_finish(&d, "two.json", &err), "%s", err.message);
    cr_expect_eq(d.num_materials, 1);
    cr_expect_eq(d.material_ids[0], 0);
    cr_expect_eq(d.material_ids[1], 0);
    cr_expect_eq(d.num_vertices, 6, "vertices are not shared between meshes");
    cr_expect_eq(d.triangles[1].v.s[0], 3);
    scene_data_free(&d);
}

Test(flatten, non_finite_position_is_rejected)
{
    float positions[] = {0, 0, 0, INFINITY, 0, 0, 0, 1, 0};
    int32_t corners[] = {0, -1, -1, 1, -1, -1, 2, -1, -1};
    int32_t materials[] = {-1};
    Mesh mesh = {.positions = positions, .num_positions = 3, .corners = corners,
                    .material_ids = materials, .num_triangles = 1};
    SceneData d;
    scene_data_init(&d);
    Error err = {0};
    cr_expect_not(scene_data_append_mesh(&d, &mesh, "inf.obj", &err));
    cr_expect_eq(err.code, ERR_OBJ_NONFINITE, "%s", error_code_name(err.code));
    cr_expect(strstr(err.message, "inf.obj"), "%s", err.message);
    scene_data_free(&d);
}

/* ---- material_from_obj ---------------------------------------------------------------------- */

Test(flatten, materials_map_from_mtl)
{
    ObjMaterial m = obj_material("m", 0.5f, 0.25f, 0.125f);
    ObjTextures none = obj_textures_none(), kd = none;
    kd.kd = 7;
    Material out = material_from_obj(&m, &kd);
    cr_expect_eq(out.type, MATERIAL_DIFFUSE);
    cr_expect_eq(out.base.s[1], 0.25f);
    cr_expect_eq(out.tex[MATERIAL_TEX_BASE], 7);

    m.ni = 1.5f; /* Cornell box walls: Ni 1.5 without d < 1 stays diffuse */
    cr_expect_eq(material_from_obj(&m, &none).type, MATERIAL_DIFFUSE);

    m.illum = 3; /* mirror illum without Ks: diffuse */
    cr_expect_eq(material_from_obj(&m, &none).type, MATERIAL_DIFFUSE);
    m.ks[0] = m.ks[1] = m.ks[2] = 0.9f;
    out = material_from_obj(&m, &none);
    cr_expect_eq(out.type, MATERIAL_CONDUCTOR);
    cr_expect_eq(out.base.s[0], 0.9f);
    m.illum = 5;
    cr_expect_eq(material_from_obj(&m, &none).type, MATERIAL_CONDUCTOR);

    ObjMaterial glass = obj_material("glass", 0, 0, 0);
    glass.illum = 7;
    glass.ni = 2.5f;
    out = material_from_obj(&glass, &none);
    cr_expect_eq(out.type, MATERIAL_DIELECTRIC);
    cr_expect_eq(out.ior, 2.5f);
    cr_expect_eq(out.base.s[0], 1.0f, "absent Tf means untinted");
    glass.illum = 4;
    glass.ni = 1.0f;
    out = material_from_obj(&glass, &none);
    cr_expect_eq(out.type, MATERIAL_DIELECTRIC);
    cr_expect_eq(out.ior, 1.5f, "Ni <= 1 on a dielectric: 1.5");
    glass.tf[0] = 0.1f, glass.tf[1] = 0.2f, glass.tf[2] = 0.3f;
    cr_expect_eq(material_from_obj(&glass, &none).base.s[2], 0.3f);

    ObjMaterial water = obj_material("water", 0.5f, 0.5f, 0.5f);
    water.ni = 1.33f;
    water.d = 0.5f;
    out = material_from_obj(&water, &none);
    cr_expect_eq(out.type, MATERIAL_DIELECTRIC, "Ni > 1 with d < 1");
    cr_expect_eq(out.ior, 1.33f);
    water.ni = 1.0f;
    cr_expect_eq(material_from_obj(&water, &none).type, MATERIAL_DIFFUSE, "d < 1 alone is not glass");

    ObjMaterial light = obj_material("light", 0.78f, 0.78f, 0.78f);
    light.ke[0] = 17, light.ke[1] = 12, light.ke[2] = 4;
    out = material_from_obj(&light, &none);
    cr_expect_eq(out.emission.s[0], 17.0f);
    cr_expect(fabsf(out.emission.s[3] - (0.2126f * 17 + 0.7152f * 12 + 0.0722f * 4)) < 1e-4f);
}

/* ---- Through obj_load ----------------------------------------------------------------------- */

Test(flatten, cornell_box_lights_are_the_two_light_triangles)
{
    REQUIRE_ASSETS();
    Scene scene;
    Error err = {0};
    cr_assert(scene_load(ASSETS_DIR "/cornell-box/CornellBox-Original.obj", &scene, &err), "%s",
              err.message);
    const SceneData *d = &scene.data;
    cr_assert_eq(d->num_emissive, 2);
    for (uint32_t i = 0; i < d->num_emissive; i++) {
        uint32_t t = d->emissive_triangles[i];
        const Material *m = &d->materials[d->material_ids[t]];
        cr_expect_eq(m->emission.s[0], 17.0f);
        cr_expect_eq(m->emission.s[1], 12.0f);
        for (int k = 0; k < 3; k++) /* the light quad hangs just below the ceiling */
            cr_expect(fabsf(d->positions[d->triangles[t].v.s[k]].s[1] - 1.98f) < 1e-4f);
    }
    uint32_t emitting = 0;
    for (uint32_t t = 0; t < d->num_triangles; t++)
        emitting += d->materials[d->material_ids[t]].emission.s[3] > 0.0f;
    cr_expect_eq(emitting, 2);
    scene_free(&scene);
}

Test(flatten, missing_mtl_gives_the_default_material_and_a_warning)
{
    const char *dir = test_temp_dir();
    const char *obj = test_write_file(dir, "lonely.obj",
                                      "mtllib nowhere.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n");
    warnings_set_quiet(true);
    int before = warning_count();
    Scene scene;
    Error err = {0};
    cr_assert(scene_load(obj, &scene, &err), "%s", err.message);
    cr_expect_gt(warning_count(), before);
    cr_assert_eq(scene.data.num_materials, 1);
    cr_expect_eq(scene.data.material_ids[0], 0);
    cr_expect_eq(scene.data.materials[0].base.s[1], 0.8f);
    cr_expect_eq(scene.data.materials[0].type, MATERIAL_DIFFUSE);
    scene_free(&scene);
}

Test(flatten, missing_texture_warns_and_keeps_kd)
{
    const char *dir = test_temp_dir();
    test_write_file(dir, "t.mtl", "newmtl painted\nKd 0.3 0.4 0.5\nmap_Kd not-there.png\n");
    const char *obj = test_write_file(dir, "t.obj",
                                      "mtllib t.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nusemtl painted\n"
                                      "f 1/1 2/1 3/1\n");
    char log_path[512];
    snprintf(log_path, sizeof log_path, "%s/stderr.txt", dir);
    cr_assert(freopen(log_path, "w", stderr));
    int before = warning_count();
    Scene scene;
    Error err = {0};
    bool loaded = scene_load(obj, &scene, &err);
    fflush(stderr);
    cr_assert(loaded, "%s", err.message);
    cr_expect_gt(warning_count(), before);
    char *log = test_read_file(log_path, NULL);
    cr_assert(log);
    cr_expect(strstr(log, "not-there.png") && strstr(log, "painted"), "warning: %s", log);
    free(log);
    const Material *m = &scene.data.materials[scene.data.material_ids[0]];
    cr_expect_eq(m->tex[MATERIAL_TEX_BASE], NO_TEXTURE);
    cr_expect_eq(m->base.s[0], 0.3f);
    cr_expect_eq(m->base.s[2], 0.5f);
    cr_expect_eq(scene.data.textures.count, 0);
    scene_free(&scene);
}

Test(flatten, corrupt_texture_is_an_error_naming_the_file)
{
    const char *dir = test_temp_dir();
    test_write_file(dir, "broken.png", "\x89PNG but then nothing that a decoder could use");
    test_write_file(dir, "c.mtl", "newmtl broken\nKd 1 1 1\nmap_Kd broken.png\n");
    const char *obj = test_write_file(dir, "c.obj", "mtllib c.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
                                                    "usemtl broken\nf 1 2 3\n");
    Scene scene;
    Error err = {0};
    cr_expect_not(scene_load(obj, &scene, &err));
    cr_expect_eq(err.code, ERR_TEXTURE, "%s", error_code_name(err.code));
    cr_expect(strstr(err.message, "broken.png"), "%s", err.message);
}

Test(flatten, obj_without_faces_has_no_triangles)
{
    const char *dir = test_temp_dir();
    const char *obj = test_write_file(dir, "points.obj", "# only vertices\nv 0 0 0\nv 1 0 0\nv 0 1 0\n");
    Scene scene;
    Error err = {0};
    cr_expect_not(scene_load(obj, &scene, &err));
    cr_expect_eq(err.code, ERR_NO_TRIANGLES, "%s", error_code_name(err.code));
    cr_expect(strstr(err.message, "points.obj"), "%s", err.message);
    const char *empty = test_write_file(dir, "empty.obj", "");
    Error err2 = {0};
    cr_expect_not(scene_load(empty, &scene, &err2));
    cr_expect_eq(err2.code, ERR_NO_TRIANGLES, "%s", error_code_name(err2.code));
}

/* The 100k-triangle dragon unifies to one vertex per position (it has no normals or uvs). The time
 * is logged, not asserted (timed thresholds do not belong in tests): about 10 ms at -O2 here. */
Test(flatten, dragon_unifies_to_one_vertex_per_position)
{
    REQUIRE_ASSETS();
    warnings_set_quiet(true);
    Mesh mesh;
    Error err = {0};
    cr_assert(obj_load(ASSETS_DIR "/stanford-dragon/dragon.obj", &mesh, &err), "%s", err.message);
    SceneData d;
    scene_data_init(&d);
    double start = seconds_now();
    cr_assert(scene_data_append_mesh(&d, &mesh, "dragon.obj", &err), "%s", err.message);
    cr_assert(scene_data_finish(&d, "dragon.obj", &err), "%s", err.message);
    double seconds = seconds_now() - start;
    cr_log_info("dragon: %u triangles, %u vertices flattened in %.1f ms", d.num_triangles,
                d.num_vertices, 1e3 * seconds);
    cr_expect_eq(d.num_triangles, 100000);
    cr_expect_eq(d.num_vertices, 50000, "positions only: one vertex per position");
    scene_data_free(&d);
    mesh_free(&mesh);
}
