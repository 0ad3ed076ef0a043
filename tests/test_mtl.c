// SPDX-License-Identifier: MIT
/* MTL loading (host/io/obj_loader.cc): the fields and texture paths of the public assets' MTL
 * files, every value a small MTL sets or leaves at its default, usemtl of an unknown material and
 * a missing MTL file as warnings that name it. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "io/obj_loader.h"
#include "support.h"

#define TRIANGLE_V "v 0 0 0\nv 1 0 0\nv 0 1 0\n"

/* Loads quietly; fails the test with the error message if it does not load. */
static void load_ok(const char *path, ObjMesh *mesh)
{
    Error err = {0};
    warnings_set_quiet(true);
    cr_assert(obj_load(path, mesh, &err), "%s: %s", path, err.message);
}

Test(obj_assets, mtl_fields_and_texture_paths)
{
    REQUIRE_ASSETS();
    ObjMesh mesh;
    load_ok(ASSETS_DIR "/cornell-box/CornellBox-Original.obj", &mesh);
    int light = -1;
    for (size_t m = 0; m < mesh.num_materials; m++)
        if (strcmp(mesh.materials[m].name, "light") == 0)
            light = (int)m;
    cr_assert_geq(light, 0);
    const ObjMaterial *l = &mesh.materials[light];
    cr_expect(l->ke[0] == 17 && l->ke[1] == 12 && l->ke[2] == 4, "Ke %g %g %g", l->ke[0], l->ke[1],
              l->ke[2]);
    cr_expect(l->kd[0] == 0.78f && l->illum == 2);
    size_t light_triangles = 0;
    for (size_t t = 0; t < mesh.num_triangles; t++)
        light_triangles += mesh.material_ids[t] == light;
    cr_expect_eq(light_triangles, 2, "the light quad gives 2 triangles");
    obj_free(&mesh);

    load_ok(ASSETS_DIR "/scrub-pine/scrubPine.obj", &mesh);
    cr_assert_eq(mesh.num_materials, 2);
    for (size_t m = 0; m < 2; m++) {
        FILE *texture = fopen(mesh.materials[m].map_kd, "rb");
        cr_expect(texture, "map_Kd %s does not resolve to a file", mesh.materials[m].map_kd);
        if (texture)
            fclose(texture);
        const char *folder = ASSETS_DIR "/scrub-pine/";
        cr_expect(strncmp(mesh.materials[m].map_kd, folder, strlen(folder)) == 0, "%s",
                  mesh.materials[m].map_kd);
    }
    obj_free(&mesh);

    /* holodeck: map_Ke carries "-mm 0 0.4"; its map_Kd still resolves. */
    load_ok(ASSETS_DIR "/holodeck/holodeck.obj", &mesh);
    bool screens = false;
    for (size_t m = 0; m < mesh.num_materials; m++) {
        screens = screens || strcmp(mesh.materials[m].name, "screens") == 0;
        if (strcmp(mesh.materials[m].name, "holodeckwirefrane") == 0)
            cr_expect_str_eq(mesh.materials[m].map_kd, ASSETS_DIR "/holodeck/wall.png");
    }
    cr_expect(screens);
    obj_free(&mesh);
}

Test(obj_details, mtl_values_defaults_and_warnings)
{
    const char *dir = test_temp_dir();
    test_write_file(dir, "m.mtl",
                    "newmtl glass\n  Kd 0.1 0.2 0.3\n  Ks 0.4 0.5 0.6\n  Ke 1 2 3\n  Tf 0.7 0.8 0.9\n"
                    "  Ni 1.5\n  d 0.25\n  illum 7\n  map_Kd -mm 0 0.4 tex.png\n"
                    "newmtl plain\n  Kd 1 1 1\n");
    const char *path = test_write_file(dir, "m.obj",
                                       "mtllib m.mtl\n" TRIANGLE_V "usemtl glass\nf 1 2 3\n"
                                       "usemtl plain\nf 1 2 3\nusemtl nosuch\nf 1 2 3\n");
    int before = warning_count();
    ObjMesh mesh;
    load_ok(path, &mesh);
    cr_expect_eq(warning_count(), before + 1, "one warning, for usemtl nosuch");
    cr_assert_eq(mesh.num_materials, 2);
    const ObjMaterial *glass = &mesh.materials[0], *plain = &mesh.materials[1];
    cr_expect_str_eq(glass->name, "glass");
    cr_expect(glass->kd[2] == 0.3f && glass->ks[1] == 0.5f && glass->ke[2] == 3.0f);
    cr_expect(glass->tf[0] == 0.7f && glass->ni == 1.5f && glass->d == 0.25f && glass->illum == 7);
    char texture[600];
    snprintf(texture, sizeof texture, "%s/tex.png", dir);
    cr_expect_str_eq(glass->map_kd, texture);
    cr_expect(plain->illum == -1 && plain->tf[0] == 1 && plain->ni == 1 && plain->d == 1,
              "absent illum -1, Tf 1, Ni 1, d 1");
    cr_expect_str_eq(plain->map_kd, "");
    cr_assert_eq(mesh.num_triangles, 3);
    cr_expect_eq(mesh.material_ids[0], 0);
    cr_expect_eq(mesh.material_ids[1], 1);
    cr_expect_eq(mesh.material_ids[2], -1);
    obj_free(&mesh);
    remove(path);
    remove(test_write_file(dir, "m.mtl", ""));
    rmdir(dir);
}

Test(obj_details, missing_mtl_is_a_warning_naming_it)
{
    const char *dir = test_temp_dir();
    const char *path =
        test_write_file(dir, "m.obj", "mtllib absent.mtl\n" TRIANGLE_V "usemtl red\nf 1 2 3\n");
    /* Catch what warn() prints: stderr goes to a file while loading. */
    char log_path[600];
    snprintf(log_path, sizeof log_path, "%s/stderr.txt", dir);
    fflush(stderr);
    int saved = dup(fileno(stderr));
    FILE *log = fopen(log_path, "w");
    cr_assert(log && saved >= 0);
    dup2(fileno(log), fileno(stderr));
    warnings_set_quiet(false);
    int before = warning_count();
    ObjMesh mesh;
    Error err = {0};
    bool loaded = obj_load(path, &mesh, &err);
    fflush(stderr);
    dup2(saved, fileno(stderr));
    close(saved);
    fclose(log);
    cr_assert(loaded, "%s", err.message);
    cr_expect_gt(warning_count(), before);
    char *printed = test_read_file(log_path, NULL);
    cr_assert(printed);
    cr_expect(strstr(printed, "absent.mtl") != NULL, "warnings do not name the MTL:\n%s", printed);
    for (char *line = printed; (line = strstr(line, "pt: warning: ")) != NULL; line++)
        cr_expect(strncmp(line + 13, path, strlen(path)) == 0 || strstr(line, "absent.mtl"),
                  "warning names neither the OBJ nor the MTL: %.80s", line);
    free(printed);
    cr_expect_eq(mesh.num_materials, 0);
    cr_expect_eq(mesh.material_ids[0], -1);
    obj_free(&mesh);
    remove(path);
    remove(log_path);
    rmdir(dir);
}
