// SPDX-License-Identifier: MIT
/* MTL texture paths (host/io/obj_loader.cc): an MTL written on Windows with backslash
 * separators, and texture paths that leave the MTL's folder refused unless allowed. The rest of
 * MTL loading and its mapping onto Material: test_io_mtl.c. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include <stb_image_write.h>

#include "base/fs.h"
#include "io/obj_loader.h"
#include "mtl_fixture.h"
#include "support.h"

/* An MTL written on Windows: `map_Kd .\\SpiderTex.jpg` and `map_Kd tex\\wood.png` name files
 * that exist with '/' separators; a name that exists as written is kept as written. */
Test(mtl_mapping, windows_backslash_paths_are_found)
{
    const char *dir = test_temp_dir();
    char sub[512], path[600];
    snprintf(sub, sizeof sub, "%s/tex", dir);
    cr_assert_eq(mkdir(sub, 0777), 0);
    const unsigned char pixel[3] = {255, 0, 0};
    snprintf(path, sizeof path, "%s/tex/wood.png", dir);
    cr_assert(stbi_write_png(path, 1, 1, 3, pixel, 3));
    snprintf(path, sizeof path, "%s/SpiderTex.png", dir);
    cr_assert(stbi_write_png(path, 1, 1, 3, pixel, 3));
    snprintf(path, sizeof path, "%s/odd\\name.png", dir); /* a real backslash in a Unix name */
    cr_assert(stbi_write_png(path, 1, 1, 3, pixel, 3));
    test_write_file(dir, "win.mtl", "newmtl a\nmap_Kd tex\\wood.png\nnewmtl b\nmap_Kd .\\SpiderTex.png\n"
                                    "newmtl c\nmap_Kd odd\\name.png\nnewmtl d\nmap_Kd gone\\x.png\n");
    const char *obj = test_write_file(dir, "win.obj", "mtllib win.mtl\n" TRIANGLE_V "usemtl a\nf 1 2 3\n"
                                                     "usemtl b\nf 1 2 3\nusemtl c\nf 1 2 3\nusemtl d\nf 1 2 3\n");
    Mesh mesh;
    load_ok(obj, &mesh);
    cr_assert_eq(mesh.num_materials, 4);
    char expected[4][600];
    snprintf(expected[0], sizeof expected[0], "%s/tex/wood.png", dir);
    snprintf(expected[1], sizeof expected[1], "%s/./SpiderTex.png", dir);
    snprintf(expected[2], sizeof expected[2], "%s/odd\\name.png", dir);
    snprintf(expected[3], sizeof expected[3], "%s/gone\\x.png", dir); /* found by neither: as written */
    for (int m = 0; m < 4; m++)
        cr_expect_str_eq(mesh.materials[m].map_kd, expected[m]);
    mesh_free(&mesh);
}

/* A texture path in an MTL stays inside the MTL's folder (issue 42): "../" above it or an
 * absolute path is refused before any file is opened, naming the MTL, the material, the
 * statement and the path; --allow-outside-paths (fs_set_allow_outside_paths) reads it. A
 * sub-folder and a ".." that stays inside are fine. */
Test(mtl_paths, texture_paths_that_leave_the_folder_are_refused_unless_allowed)
{
    static const struct {
        const char *statement, *path;
    } escaping[] = {{"map_Kd", "../outside.png"},     {"map_Ke", "/etc/hostname"},
                    {"map_Pr", "a/../../outside.png"}, {"map_d", "../../../../etc/passwd"},
                    {"norm", "/dev/zero"},             {"map_Bump", "../n.png"}};
    const char *dir = test_temp_dir();
    char sub[600];
    snprintf(sub, sizeof sub, "%s/scene", dir);
    cr_assert_eq(mkdir(sub, 0700), 0);
    const char *obj = test_write_file(sub, "m.obj", "mtllib m.mtl\n" TRIANGLE_V "usemtl red\nf 1 2 3\n");
    warnings_set_quiet(true);
    for (size_t i = 0; i < sizeof escaping / sizeof escaping[0]; i++) {
        char mtl[600];
        snprintf(mtl, sizeof mtl, "newmtl red\nKd 1 0 0\n%s %s\n", escaping[i].statement,
                 escaping[i].path);
        const char *mtl_path = test_write_file(sub, "m.mtl", mtl);
        Mesh mesh;
        Error err = {0};
        fs_set_allow_outside_paths(false);
        cr_expect(!obj_load(obj, &mesh, &err), "%s %s accepted", escaping[i].statement,
                  escaping[i].path);
        cr_expect_eq(err.code, ERR_PATH_ESCAPES, "%s", err.message);
        cr_expect(strstr(err.message, mtl_path) && strstr(err.message, "material 'red'") &&
                      strstr(err.message, escaping[i].statement) &&
                      strstr(err.message, escaping[i].path) &&
                      strstr(err.message, "--allow-outside-paths"),
                  "%s", err.message);
        fs_set_allow_outside_paths(true);
        cr_expect(obj_load(obj, &mesh, &err), "allowed: %s", err.message);
        fs_set_allow_outside_paths(false);
        mesh_free(&mesh);
    }
    test_write_file(sub, "m.mtl", "newmtl red\nmap_Kd tex/../tex/red.png\nmap_Ke tex/glow.png\n");
    Mesh mesh;
    Error err = {0};
    cr_assert(obj_load(obj, &mesh, &err), "%s", err.message);
    char expected[700];
    snprintf(expected, sizeof expected, "%s/tex/glow.png", sub);
    cr_expect_str_eq(mesh.materials[0].map_ke, expected);
    mesh_free(&mesh);
}
