// SPDX-License-Identifier: MIT
/* MTL loading (host/io/obj_loader.cc): the fields and texture paths of the public assets' MTL
 * files, every value a small MTL sets or leaves at its default, usemtl of an unknown material and
 * a missing MTL file as warnings that name it; the MTL mapping onto Material (host/scene/
 * materials.c, DESIGN "MTL mapping"); unused statements and texture options named once per file,
 * and silent with --quiet. MTL texture paths (Windows backslashes, paths leaving the folder):
 * test_io_mtl_paths.c. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <stb_image_write.h>

#include "app/cli.h"
#include "base/fs.h"
#include "io/obj_loader.h"
#include "mtl_fixture.h"
#include "scene/scene.h"
#include "support.h"

Test(obj_assets, mtl_fields_and_texture_paths)
{
    REQUIRE_ASSETS();
    Mesh mesh;
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
    mesh_free(&mesh);

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
    mesh_free(&mesh);

    /* holodeck: map_Ke carries "-mm 0 0.4"; its map_Kd still resolves. */
    load_ok(ASSETS_DIR "/holodeck/holodeck.obj", &mesh);
    bool screens = false;
    for (size_t m = 0; m < mesh.num_materials; m++) {
        screens = screens || strcmp(mesh.materials[m].name, "screens") == 0;
        if (strcmp(mesh.materials[m].name, "holodeckwirefrane") == 0)
            cr_expect_str_eq(mesh.materials[m].map_kd, ASSETS_DIR "/holodeck/wall.png");
    }
    cr_expect(screens);
    mesh_free(&mesh);
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
    Mesh mesh;
    load_ok(path, &mesh);
    cr_expect_eq(warning_count(), before + 2, "two warnings: usemtl nosuch, map_Kd's -mm");
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
    mesh_free(&mesh);
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
    Mesh mesh;
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
    mesh_free(&mesh);
    remove(path);
    remove(log_path);
    rmdir(dir);
}

/* ---- The MTL mapping (shared/DESIGN.md "MTL mapping"), through scene_load ------------------- */

static char g_dir[64];

static const char *in_dir(const char *name)
{
    if (!g_dir[0])
        snprintf(g_dir, sizeof g_dir, "%s", test_temp_dir());
    static char path[4][256];
    static int next;
    char *p = path[next++ % 4];
    snprintf(p, 256, "%s/%s", g_dir, name);
    return p;
}

/* 2 x 1 images: rgb (a normal map), grey (a height or scalar map), rgba with and without cut-outs,
 * and a half-white emission map (mean luminance 0.5 after sRGB decoding: texels 255 and 0). */
static void write_images(void)
{
    const unsigned char rgb[] = {128, 128, 255, 128, 128, 255}, grey[] = {50, 200};
    const unsigned char cut[] = {9, 9, 9, 255, 9, 9, 9, 0}, opaque[] = {9, 9, 9, 255, 9, 9, 9, 255};
    const unsigned char half[] = {255, 255, 255, 0, 0, 0};
    cr_assert(stbi_write_png(in_dir("n.png"), 2, 1, 3, rgb, 6));
    cr_assert(stbi_write_png(in_dir("g.png"), 2, 1, 1, grey, 2));
    cr_assert(stbi_write_png(in_dir("cut.png"), 2, 1, 4, cut, 8));
    cr_assert(stbi_write_png(in_dir("opaque.png"), 2, 1, 4, opaque, 8));
    cr_assert(stbi_write_png(in_dir("half.png"), 2, 1, 3, half, 6));
}

/* Loads one triangle in a material whose MTL statements are `mtl` (after "newmtl m"). */
static Material mtl_material(const char *mtl, Scene *scene)
{
    write_images();
    char text[2048];
    snprintf(text, sizeof text, "newmtl m\n%s\n", mtl);
    test_write_file(g_dir, "m.mtl", text);
    const char *obj = test_write_file(g_dir, "m.obj", "mtllib m.mtl\n" TRIANGLE_V "usemtl m\nf 1 2 3\n");
    Error err = {0};
    warnings_set_quiet(true);
    cr_assert(scene_load(obj, scene, &err), "%s", err.message);
    warnings_set_quiet(false);
    return scene->data.materials[scene->data.material_ids[0]];
}

static Material mapped(const char *mtl)
{
    Scene scene;
    Material m = mtl_material(mtl, &scene);
    scene_free(&scene);
    return m;
}

Test(mtl_mapping, pbr_extension_is_principled)
{
    Scene scene;
    Material m = mtl_material("Kd 0.5 0.4 0.3\nPr 0.35\nPm 1\nmap_Pr g.png\nmap_Pm g.png", &scene);
    cr_expect_eq(m.type, MATERIAL_PRINCIPLED);
    cr_expect_eq(m.roughness, 0.35f);
    cr_expect_eq(m.metallic, 1.0f);
    cr_expect_eq(m.base.s[1], 0.4f, "Kd is the base colour");
    uint32_t pr = m.tex[MATERIAL_TEX_ROUGHNESS];
    cr_assert_neq(pr, NO_TEXTURE);
    cr_expect_eq(m.tex[MATERIAL_TEX_METALLIC], pr, "one file, one texture");
    cr_expect_eq(scene.data.textures.infos[pr].format, TEXTURE_RGBA8_LINEAR, "map_Pr is linear");
    scene_free(&scene);
    m = mapped("Kd 0.5 0.4 0.3\nPm 0.5");
    cr_expect_eq(m.type, MATERIAL_PRINCIPLED, "Pm alone");
    cr_expect_eq(m.metallic, 0.5f);
    cr_expect_eq(m.roughness, 0.5f, "Pr absent: 0.5");
    m = mapped("Kd 0.5 0.4 0.3\nPr 0");
    cr_expect_eq(m.type, MATERIAL_PRINCIPLED, "Pr 0 is present");
}

Test(mtl_mapping, conductor_and_dielectric_take_pr)
{
    Material m = mapped("Ks 0.9 0.8 0.7\nillum 3\nPr 0.2\nmap_Pr g.png");
    cr_expect_eq(m.type, MATERIAL_CONDUCTOR, "illum 3 with Ks wins over Pr");
    cr_expect(m.flags & MATERIAL_FLAG_FRESNEL_ONE);
    cr_expect_eq(m.base.s[2], 0.7f, "reflectance Ks");
    cr_expect_eq(m.roughness, 0.2f);
    cr_expect_neq(m.tex[MATERIAL_TEX_ROUGHNESS], NO_TEXTURE);
    m = mapped("Ks 0.9 0.8 0.7\nillum 5");
    cr_expect_eq(m.type, MATERIAL_CONDUCTOR);
    cr_expect_eq(m.roughness, 0.0f, "no Pr: a mirror");
    m = mapped("Ni 1.45\nTf 0.9 0.8 0.7\nillum 7\nPr 0.1\nd 0.5");
    cr_expect_eq(m.type, MATERIAL_DIELECTRIC);
    cr_expect_eq(m.ior, 1.45f);
    cr_expect_eq(m.base.s[1], 0.8f, "tint Tf");
    cr_expect_eq(m.roughness, 0.1f);
    cr_expect_eq(m.flags & MATERIAL_FLAG_CUTOUT, 0u, "d < 1 on glass is not a cut-out");
    cr_expect_eq(m.opacity, 1.0f);
}

Test(mtl_mapping, illum_2_with_ks_and_ns_is_glossy_principled)
{
    Material m = mapped("Kd 0.2 0.3 0.4\nKs 0.5 0.5 0.5\nNs 250\nillum 2");
    cr_expect_eq(m.type, MATERIAL_PRINCIPLED);
    cr_expect_eq(m.metallic, 0.0f);
    cr_expect(fabsf(m.roughness - 0.5f) < 1e-6f, "1 - sqrt(250/1000): %g", m.roughness);
    cr_expect_eq(m.base.s[2], 0.4f);
    m = mapped("Kd 0.2 0.3 0.4\nKs 0.5 0.5 0.5\nNs 5000\nillum 2");
    cr_expect(fabsf(m.roughness) < 1e-6f, "Ns over 1000 is clamped: %g", m.roughness);
    cr_expect_eq(mapped("Kd 0.2 0.3 0.4\nKs 0.5 0.5 0.5\nillum 2").type, MATERIAL_DIFFUSE, "no Ns");
    cr_expect_eq(mapped("Kd 0.2 0.3 0.4\nKs 0 0 0\nNs 250\nillum 2").type, MATERIAL_DIFFUSE, "Ks 0");
    cr_expect_eq(mapped("Kd 0.2 0.3 0.4\nKs 0.5 0.5 0.5\nNs 250\nillum 1").type, MATERIAL_DIFFUSE,
                 "illum 1");
}

Test(mtl_mapping, emission_from_ke_and_map_ke)
{
    Scene scene;
    Material m = mtl_material("Kd 0 0 0\nKe 2 2 2\nmap_Ke half.png", &scene);
    uint32_t ke = m.tex[MATERIAL_TEX_EMISSION];
    cr_assert_neq(ke, NO_TEXTURE);
    cr_expect_eq(scene.data.textures.infos[ke].format, TEXTURE_RGBA8_SRGB, "map_Ke is a colour");
    cr_expect_eq(m.emission.s[0], 2.0f);
    cr_expect(fabsf(m.emission.s[3] - 1.0f) < 1e-4f, "w = luminance 2 x mean 0.5: %g", m.emission.s[3]);
    cr_expect_eq(scene.data.num_emissive, 1u, "a light");
    scene_free(&scene);
    m = mapped("Kd 0 0 0\nmap_Ke half.png");
    cr_expect_eq(m.emission.s[1], 1.0f, "map_Ke without Ke: the texture is the radiance");
    cr_expect(fabsf(m.emission.s[3] - 0.5f) < 1e-4f, "%g", m.emission.s[3]);
}

Test(mtl_mapping, normal_and_bump_maps)
{
    Material m = mapped("Kd 1 1 1\nnorm -bm 0.5 n.png");
    cr_expect_neq(m.tex[MATERIAL_TEX_NORMAL], NO_TEXTURE);
    cr_expect_eq(m.bump_scale, 0.5f, "-bm scales the normal map's xy");
    m = mapped("Kd 1 1 1\nmap_Bump n.png");
    cr_expect_neq(m.tex[MATERIAL_TEX_NORMAL], NO_TEXTURE, "an rgb map_Bump is a normal map");
    cr_expect_eq(m.bump_scale, 1.0f);
    m = mapped("Kd 1 1 1\nbump -bm 2 g.png");
    cr_expect_eq(m.tex[MATERIAL_TEX_NORMAL], NO_TEXTURE);
    cr_expect_neq(m.tex[MATERIAL_TEX_BUMP], NO_TEXTURE, "a grey bump is a height map");
    cr_expect_eq(m.bump_scale, 2.0f);
}

Test(mtl_mapping, opacity_from_map_d_d_and_rgba_map_kd)
{
    Scene scene;
    Material m = mtl_material("Kd 1 1 1\nmap_d g.png", &scene);
    uint32_t d = m.tex[MATERIAL_TEX_OPACITY];
    cr_assert_neq(d, NO_TEXTURE);
    cr_expect_eq(scene.data.textures.infos[d].format, TEXTURE_RGBA8_LINEAR, "map_d is linear");
    cr_expect(m.flags & MATERIAL_FLAG_CUTOUT);
    scene_free(&scene);
    m = mapped("Kd 1 1 1\nd 0.25");
    cr_expect_eq(m.type, MATERIAL_DIFFUSE);
    cr_expect_eq(m.opacity, 0.25f);
    cr_expect(m.flags & MATERIAL_FLAG_CUTOUT);
    m = mapped("Kd 1 1 1\nmap_Kd cut.png");
    cr_expect_eq(m.flags & (MATERIAL_FLAG_BASE_ALPHA | MATERIAL_FLAG_CUTOUT),
                 MATERIAL_FLAG_BASE_ALPHA | MATERIAL_FLAG_CUTOUT, "alpha-tested foliage");
    m = mapped("Kd 1 1 1\nmap_Kd opaque.png");
    cr_expect_eq(m.flags, 0u, "an RGBA map_Kd whose alpha is all 1 is opaque");
    cr_expect_eq(m.opacity, 1.0f);
}

/* Loads an MTL with unused statements and options in two materials, printing warnings to a file;
 * returns what was printed. */
static char *unused_warnings(const char *mtl)
{
    test_write_file(g_dir[0] ? g_dir : in_dir(""), "u.mtl", mtl);
    write_images();
    const char *obj = test_write_file(g_dir, "u.obj", "mtllib u.mtl\n" TRIANGLE_V "usemtl a\nf 1 2 3\n");
    char log_path[300];
    snprintf(log_path, sizeof log_path, "%s/stderr.txt", g_dir);
    fflush(stderr);
    int saved = dup(fileno(stderr));
    FILE *log = fopen(log_path, "w");
    cr_assert(log && saved >= 0);
    dup2(fileno(log), fileno(stderr));
    warnings_set_quiet(false);
    Mesh mesh;
    Error err = {0};
    bool loaded = obj_load(obj, &mesh, &err);
    fflush(stderr);
    dup2(saved, fileno(stderr));
    close(saved);
    fclose(log);
    cr_assert(loaded, "%s", err.message);
    mesh_free(&mesh);
    return test_read_file(log_path, NULL);
}

static int count(const char *text, const char *needle)
{
    int n = 0;
    for (const char *s = strstr(text, needle); s; s = strstr(s + 1, needle))
        n++;
    return n;
}

Test(mtl_mapping, unused_statements_and_options_are_named_once_per_file)
{
    char *printed = unused_warnings("newmtl a\nKa 1 1 1\nKd 1 1 1\nsharpness 60\n"
                                    "map_Kd -s 2 2 1 -o -0.5 0 n.png\nnewmtl b\nKa 0 0 0\n"
                                    "map_Ka n.png\nmap_Kd -s 1 1 1 -clamp on n.png\nnorm -bm 0.5 n.png\n");
    cr_assert(printed);
    cr_expect_eq(count(printed, "pt: warning:"), 4, "sharpness, -s, -o, -clamp:\n%s", printed);
    /* The ambient Ka and map_Ka, on almost every MTL, are harmless: no word (issue 36). */
    cr_expect_eq(count(printed, "'Ka'"), 0, "%s", printed);
    cr_expect_eq(count(printed, "'map_Ka'"), 0, "%s", printed);
    cr_expect_eq(count(printed, "'sharpness'"), 1, "%s", printed);
    cr_expect_eq(count(printed, "-s (map_Kd)"), 1, "%s", printed);
    cr_expect_eq(count(printed, "-o (map_Kd)"), 1, "%s", printed);
    cr_expect_eq(count(printed, "-clamp (map_Kd)"), 1, "%s", printed);
    /* "option -bm", not "-bm": the temporary folder's random name may hold "-bm" too. */
    cr_expect(!strstr(printed, "option -bm"), "-bm on norm is used: %s", printed);
    cr_expect(!strstr(printed, "option -0.5"), "a negative value is not an option: %s", printed);
    cr_expect(strstr(printed, "u.mtl"), "names the file: %s", printed);
    free(printed);
}

Test(mtl_mapping, quiet_silences_unused_statement_warnings)
{
    char *argv[] = {"pt", "render", "x.obj", "--quiet", NULL};
    Options o;
    Error err = {0};
    cr_assert(cli_parse(4, argv, &o, &err), "%s", err.message);
    char *printed = unused_warnings("newmtl a\nKa 1 1 1\nmap_Kd -s 2 2 1 n.png\n");
    cr_assert(printed);
    cr_expect(!strstr(printed, "not used by pt"), "--quiet: %s", printed);
    free(printed);
    obj_loader_set_quiet(false);
}

Test(mtl_mapping, a_junk_mtl_gets_16_names_and_a_count)
{
    char mtl[2048] = "newmtl a\n";
    for (int i = 0; i < 30; i++)
        snprintf(mtl + strlen(mtl), sizeof mtl - strlen(mtl), "junk%02d\xff 1\n", i);
    char *printed = unused_warnings(mtl);
    cr_assert(printed);
    cr_expect_eq(count(printed, "pt: warning:"), 17, "%s", printed);
    cr_expect(strstr(printed, "14 more statements"), "%s", printed);
    cr_expect(strstr(printed, "'junk00?'"), "non-printable bytes as '?': %s", printed);
    free(printed);
}
