// SPDX-License-Identifier: MIT
/* The scene's "textures" and "materials" blocks (host/scene/texture_json.c, material_json.c) and
 * objects[i].material: every type's keys land in the kernels' Material (constants and texture
 * slots), the flags follow DESIGN (Fresnel 1, cut-out), emission weights include the texture's
 * mean, mixes resolve to indices, a JSON material replaces the MTL material of the same name, and
 * every kind of bad value is one error naming the key and the value. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <stb_image_write.h>

#include "io/image_io.h"
#include "scene/scene.h"
#include "support.h"

static char g_dir[64];

static const char *write_file(const char *name, const char *text)
{
    if (!g_dir[0])
        snprintf(g_dir, sizeof g_dir, "%s", test_temp_dir());
    return test_write_file(g_dir, name, text);
}

/* two.obj: two triangles in MTL materials "red" and "blue", with UVs; other.obj: one in "red". */
static void write_meshes(void)
{
    write_file("two.mtl", "newmtl red\nKd 0.8 0.1 0.1\nnewmtl blue\nKd 0.1 0.1 0.8\n");
    write_file("two.obj", "mtllib two.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\n"
                          "vt 1 1\nvt 0 1\nusemtl red\nf 1/1 2/2 3/3\nusemtl blue\nf 1/1 3/3 4/4\n");
    write_file("red.mtl", "newmtl red\nKd 0.8 0.1 0.1\n");
    write_file("other.obj", "mtllib red.mtl\nv 0 0 1\nv 1 0 1\nv 1 1 1\nusemtl red\nf 1 2 3\n");
}

/* A 2 x 1 PNG with `channels` channels (values from `px`). */
static const char *write_png(const char *name, int channels, const unsigned char *px)
{
    if (!g_dir[0])
        snprintf(g_dir, sizeof g_dir, "%s", test_temp_dir());
    static char path[8][256];
    static int next;
    char *p = path[next++ % 8];
    snprintf(p, 256, "%s/%s", g_dir, name);
    cr_assert(stbi_write_png(p, 2, 1, channels, px, 2 * channels));
    return p;
}

/* Loads the scene `json` (objects added: two.obj unless the text has its own "objects"). */
static bool load(const char *json, Scene *scene, Error *err)
{
    write_meshes();
    char text[8192];
    if (strstr(json, "\"objects\""))
        snprintf(text, sizeof text, "{%s}", json);
    else
        snprintf(text, sizeof text, "{\"objects\": [{\"obj\": \"two.obj\"}], %s}", json);
    const char *path = write_file("scene.json", text);
    return scene_load(path, scene, err);
}

static Material load_one(const char *materials, const char *textures)
{
    char json[4096];
    snprintf(json, sizeof json, "\"textures\": {%s}, \"materials\": {\"m\": %s}", textures, materials);
    Scene scene;
    Error err = {0};
    cr_assert(load(json, &scene, &err), "%s", err.message);
    Material m = scene.data.materials[0];
    scene_free(&scene);
    return m;
}

static void expect_rgb(const float4 v, float r, float g, float b, const char *what)
{
    cr_expect(fabsf(v.s[0] - r) < 1e-6f && fabsf(v.s[1] - g) < 1e-6f && fabsf(v.s[2] - b) < 1e-6f,
              "%s: [%g, %g, %g], expected [%g, %g, %g]", what, v.s[0], v.s[1], v.s[2], r, g, b);
}

static void expect_no_textures(const Material *m)
{
    for (int s = 0; s < MATERIAL_TEX_COUNT; s++)
        cr_expect_eq(m->tex[s], NO_TEXTURE, "slot %d is textured", s);
}

Test(material_json, diffuse_albedo_colour_grey_default_and_texture)
{
    Material m = load_one("{\"type\": \"diffuse\", \"albedo\": [0.2, 0.4, 0.6]}", "");
    cr_expect_eq(m.type, MATERIAL_DIFFUSE);
    expect_rgb(m.base, 0.2f, 0.4f, 0.6f, "albedo");
    expect_no_textures(&m);
    cr_expect_eq(m.flags, 0u);
    cr_expect_eq(m.opacity, 1.0f);
    m = load_one("{\"type\": \"diffuse\", \"albedo\": 0.3}", "");
    expect_rgb(m.base, 0.3f, 0.3f, 0.3f, "grey albedo");
    m = load_one("{\"type\": \"diffuse\"}", "");
    expect_rgb(m.base, 0.8f, 0.8f, 0.8f, "default albedo");
    const unsigned char px[] = {255, 0, 0, 0, 255, 0};
    write_png("rg.png", 3, px);
    m = load_one("{\"type\": \"diffuse\", \"albedo\": \"bricks\"}", "\"bricks\": {\"file\": \"rg.png\"}");
    expect_rgb(m.base, 1.0f, 1.0f, 1.0f, "textured albedo's constant");
    cr_expect_eq(m.tex[MATERIAL_TEX_BASE], 0u);
}

Test(material_json, conductor_eta_k_roughness_anisotropy_and_fresnel_one)
{
    Material m = load_one("{\"type\": \"conductor\", \"eta\": [0.143, 0.374, 1.442], \"k\": [3.983, "
                          "2.385, 1.603], \"roughness\": 0.3, \"anisotropy\": 0.5, \"reflectance\": 0.9}",
                          "");
    cr_expect_eq(m.type, MATERIAL_CONDUCTOR);
    expect_rgb(m.eta, 0.143f, 0.374f, 1.442f, "eta");
    expect_rgb(m.k, 3.983f, 2.385f, 1.603f, "k");
    expect_rgb(m.base, 0.9f, 0.9f, 0.9f, "reflectance");
    cr_expect_eq(m.roughness, 0.3f);
    cr_expect_eq(m.anisotropy, 0.5f);
    cr_expect_eq(m.flags & MATERIAL_FLAG_FRESNEL_ONE, 0u, "eta and k given: complex Fresnel");
    m = load_one("{\"type\": \"conductor\"}", "");
    cr_expect_eq(m.flags & MATERIAL_FLAG_FRESNEL_ONE, MATERIAL_FLAG_FRESNEL_ONE, "no eta/k: Fresnel 1");
    cr_expect_eq(m.roughness, 0.0f, "default: a perfect mirror");
    expect_rgb(m.base, 1.0f, 1.0f, 1.0f, "default reflectance");
    m = load_one("{\"type\": \"conductor\", \"eta\": 1.5}", "");
    cr_expect_eq(m.flags & MATERIAL_FLAG_FRESNEL_ONE, 0u);
    expect_rgb(m.eta, 1.5f, 1.5f, 1.5f, "grey eta");
    expect_rgb(m.k, 0.0f, 0.0f, 0.0f, "eta alone: k 0");
}

Test(material_json, dielectric_ior_roughness_tint_absorption)
{
    Material m = load_one("{\"type\": \"dielectric\", \"ior\": 1.33, \"roughness\": 0.1, "
                          "\"tint\": [0.9, 1, 0.8], \"absorption\": [0, 0.5, 1]}", "");
    cr_expect_eq(m.type, MATERIAL_DIELECTRIC);
    cr_expect_eq(m.ior, 1.33f);
    cr_expect_eq(m.roughness, 0.1f);
    expect_rgb(m.base, 0.9f, 1.0f, 0.8f, "tint");
    expect_rgb(m.absorption, 0.0f, 0.5f, 1.0f, "absorption");
    m = load_one("{\"type\": \"dielectric\"}", "");
    cr_expect_eq(m.ior, 1.5f);
    cr_expect_eq(m.roughness, 0.0f);
    expect_rgb(m.base, 1.0f, 1.0f, 1.0f, "default tint");
    expect_rgb(m.absorption, 0.0f, 0.0f, 0.0f, "default absorption");
}

Test(material_json, principled_keys_defaults_and_textured_scalars)
{
    Material m = load_one("{\"type\": \"principled\", \"base_color\": [0.5, 0.25, 0.125], "
                          "\"metallic\": 0.75, \"roughness\": 0.2, \"specular\": 0.6, "
                          "\"specular_color\": [1, 0.5, 0.25], \"ior\": 1.45}", "");
    cr_expect_eq(m.type, MATERIAL_PRINCIPLED);
    expect_rgb(m.base, 0.5f, 0.25f, 0.125f, "base_color");
    cr_expect_eq(m.metallic, 0.75f);
    cr_expect_eq(m.roughness, 0.2f);
    cr_expect_eq(m.specular, 0.6f);
    expect_rgb(m.specular_color, 1.0f, 0.5f, 0.25f, "specular_color");
    cr_expect_eq(m.ior, 1.45f);
    m = load_one("{\"type\": \"principled\"}", "");
    cr_expect_eq(m.ior, 1.5f);
    cr_expect_eq(m.specular, 1.0f);
    cr_expect_eq(m.metallic, 0.0f);
    expect_rgb(m.specular_color, 1.0f, 1.0f, 1.0f, "default specular_color");
    const unsigned char px[] = {10, 10, 10, 200, 200, 200};
    write_png("grey.png", 3, px);
    m = load_one("{\"type\": \"principled\", \"metallic\": \"g\", \"roughness\": \"r\"}",
                 "\"g\": {\"file\": \"grey.png\", \"encoding\": \"linear\"}, \"r\": {\"type\": \"noise\"}");
    cr_expect_eq(m.tex[MATERIAL_TEX_METALLIC], 0u);
    cr_expect_eq(m.tex[MATERIAL_TEX_ROUGHNESS], 1u);
    cr_expect_eq(m.tex[MATERIAL_TEX_BASE], NO_TEXTURE);
}

Test(material_json, emission_strength_and_textured_emission_weight)
{
    Material m = load_one("{\"type\": \"diffuse\", \"emission\": [1, 2, 3], \"emission_strength\": 4}", "");
    expect_rgb(m.emission, 4.0f, 8.0f, 12.0f, "emission x strength");
    float lum = 0.2126f * 4 + 0.7152f * 8 + 0.0722f * 12;
    cr_expect(fabsf(m.emission.s[3] - lum) < 1e-4f, "w %g, luminance %g", m.emission.s[3], lum);
    /* A 2 x 1 texture, linear: texels 1 and 0: mean 0.5 in every channel. */
    const unsigned char px[] = {255, 255, 255, 0, 0, 0};
    write_png("half.png", 3, px);
    m = load_one("{\"type\": \"diffuse\", \"emission\": \"screen\", \"emission_strength\": 3}",
                 "\"screen\": {\"file\": \"half.png\", \"encoding\": \"linear\"}");
    expect_rgb(m.emission, 3.0f, 3.0f, 3.0f, "textured emission: strength");
    cr_expect_eq(m.tex[MATERIAL_TEX_EMISSION], 0u);
    cr_expect(fabsf(m.emission.s[3] - 1.5f) < 1e-4f, "w %g: strength 3 x mean luminance 0.5",
              m.emission.s[3]);
    m = load_one("{\"type\": \"diffuse\"}", "");
    cr_expect_eq(m.emission.s[3], 0.0f, "no emission");
}

Test(material_json, opacity_normal_and_bump_maps)
{
    const unsigned char px[] = {128, 128, 255, 128, 128, 255};
    write_png("n.png", 3, px);
    Material m = load_one("{\"type\": \"diffuse\", \"opacity\": 0.5, \"normal_map\": \"n\", "
                          "\"bump_map\": \"n\", \"bump_scale\": 2}",
                          "\"n\": {\"file\": \"n.png\", \"encoding\": \"linear\"}");
    cr_expect_eq(m.opacity, 0.5f);
    cr_expect(m.flags & MATERIAL_FLAG_CUTOUT);
    cr_expect_eq(m.tex[MATERIAL_TEX_NORMAL], 0u);
    cr_expect_eq(m.tex[MATERIAL_TEX_BUMP], 0u);
    cr_expect_eq(m.bump_scale, 2.0f);
    m = load_one("{\"type\": \"diffuse\", \"opacity\": \"n\"}",
                 "\"n\": {\"file\": \"n.png\", \"encoding\": \"linear\"}");
    cr_expect(m.flags & MATERIAL_FLAG_CUTOUT, "textured opacity is a cut-out");
    cr_expect_eq(m.tex[MATERIAL_TEX_OPACITY], 0u);
    m = load_one("{\"type\": \"diffuse\", \"opacity\": 1}", "");
    cr_expect_eq(m.flags & MATERIAL_FLAG_CUTOUT, 0u, "opaque");
}

Test(material_json, mix_resolves_names_to_scene_indices)
{
    Scene scene;
    Error err = {0};
    cr_assert(load("\"materials\": {\"m\": {\"type\": \"mix\", \"a\": \"x\", \"b\": \"y\", \"weight\": 0.25},"
                   " \"x\": {\"type\": \"diffuse\"}, \"y\": {\"type\": \"conductor\"}}",
                   &scene, &err), "%s", err.message);
    const Material *m = scene.data.materials;
    cr_expect_eq(m[0].type, MATERIAL_MIX);
    cr_expect_eq(m[0].mix_a, 1u);
    cr_expect_eq(m[0].mix_b, 2u);
    cr_expect_eq(m[0].weight, 0.25f);
    cr_expect_eq(m[m[0].mix_a].type, MATERIAL_DIFFUSE);
    cr_expect_eq(m[m[0].mix_b].type, MATERIAL_CONDUCTOR);
    scene_free(&scene);
}

/* `depth` mixes nested: m1 mixes m2, ..., m<depth> mixes two leaves. */
static void nested_mixes(char *json, size_t size, int depth)
{
    int n = snprintf(json, size, "\"materials\": {\"leaf\": {\"type\": \"diffuse\"}");
    for (int i = 1; i <= depth; i++) {
        char next[16];
        snprintf(next, sizeof next, i == depth ? "leaf" : "m%d", i + 1);
        n += snprintf(json + n, size - (size_t)n, ", \"m%d\": {\"type\": \"mix\", \"a\": \"%s\", \"b\": \"leaf\"}",
                      i, next);
    }
    snprintf(json + n, size - (size_t)n, "}");
}

Test(material_json, mix_depth_limit)
{
    char json[4096];
    Scene scene;
    Error err = {0};
    nested_mixes(json, sizeof json, MATERIAL_MIX_DEPTH_LIMIT);
    cr_expect(load(json, &scene, &err), "%u levels are allowed: %s", MATERIAL_MIX_DEPTH_LIMIT, err.message);
    scene_free(&scene);
    nested_mixes(json, sizeof json, MATERIAL_MIX_DEPTH_LIMIT + 1);
    Error deep = {0};
    cr_expect_not(load(json, &scene, &deep));
    cr_expect(strstr(deep.message, "materials.m1") && strstr(deep.message, "9 deep"), "%s", deep.message);
}

Test(material_json, json_material_replaces_the_mtl_material_everywhere)
{
    Scene scene;
    Error err = {0};
    cr_assert(load("\"objects\": [{\"obj\": \"two.obj\"}, {\"obj\": \"other.obj\"}], "
                   "\"materials\": {\"red\": {\"type\": \"conductor\"}}", &scene, &err), "%s", err.message);
    const SceneData *d = &scene.data;
    /* red (JSON) is material 0; two.obj adds blue only; other.obj adds nothing. */
    cr_expect_eq(d->num_materials, 2u);
    cr_expect_eq(d->materials[0].type, MATERIAL_CONDUCTOR);
    cr_expect_eq(d->material_ids[0], 0u, "two.obj's red triangle");
    cr_expect_eq(d->material_ids[1], 1u, "two.obj's blue triangle");
    cr_expect_eq(d->materials[1].type, MATERIAL_DIFFUSE);
    cr_expect(fabsf(d->materials[1].base.s[2] - 0.8f) < 1e-6f, "blue keeps its Kd");
    cr_expect_eq(d->material_ids[2], 0u, "other.obj's red triangle");
    scene_free(&scene);
}

Test(material_json, object_material_covers_the_whole_object)
{
    Scene scene;
    Error err = {0};
    cr_assert(load("\"objects\": [{\"obj\": \"two.obj\", \"material\": \"gold\"}, {\"obj\": \"other.obj\"}], "
                   "\"materials\": {\"gold\": {\"type\": \"conductor\"}}", &scene, &err), "%s", err.message);
    const SceneData *d = &scene.data;
    cr_expect_eq(d->material_ids[0], 0u);
    cr_expect_eq(d->material_ids[1], 0u);
    cr_expect_eq(d->num_materials, 2u, "gold and other.obj's red");
    cr_expect_eq(d->material_ids[2], 1u);
    cr_expect_eq(d->materials[1].type, MATERIAL_DIFFUSE);
    scene_free(&scene);
}

/* ---- Bad input: one error naming the file, the key and the value ---------------------------- */

static void expect_error(const char *json, ErrorCode code, const char *key, const char *value)
{
    Scene scene;
    Error err = {0};
    bool ok = load(json, &scene, &err);
    cr_expect_not(ok, "accepted: %s", json);
    if (ok) {
        scene_free(&scene);
        return;
    }
    cr_expect_eq(err.code, code, "%s instead of %s: %s", error_code_name(err.code),
                 error_code_name(code), err.message);
    cr_expect(strstr(err.message, "scene.json"), "names the file: %s", err.message);
    cr_expect(strstr(err.message, key), "message \"%s\" lacks the key %s", err.message, key);
    cr_expect(strstr(err.message, value), "message \"%s\" lacks the value %s", err.message, value);
    cr_expect(!strchr(err.message, '\n'), "one line: %s", err.message);
}

#define MAT(body) "\"materials\": {\"gold\": " body "}"

Test(material_json, out_of_range_values_name_key_and_value)
{
    expect_error(MAT("{\"type\": \"conductor\", \"roughness\": 1.5}"), ERR_JSON_VALUE,
                 "materials.gold.roughness", "1.5");
    expect_error(MAT("{\"type\": \"principled\", \"roughness\": -0.25}"), ERR_JSON_VALUE,
                 "materials.gold.roughness", "-0.25");
    expect_error(MAT("{\"type\": \"dielectric\", \"ior\": -1.5}"), ERR_JSON_VALUE,
                 "materials.gold.ior", "-1.5");
    expect_error(MAT("{\"type\": \"principled\", \"ior\": 0}"), ERR_JSON_VALUE,
                 "materials.gold.ior", "0 must be > 0");
    expect_error(MAT("{\"type\": \"dielectric\", \"ior\": 1e999}"), ERR_JSON_VALUE,
                 "materials.gold.ior", "inf");
    expect_error(MAT("{\"type\": \"conductor\", \"eta\": [0.1, -0.2, 1]}"), ERR_JSON_VALUE,
                 "materials.gold.eta", "-0.2");
    expect_error(MAT("{\"type\": \"conductor\", \"eta\": 1, \"k\": [1, 2, -3]}"), ERR_JSON_VALUE,
                 "materials.gold.k", "-3");
    expect_error(MAT("{\"type\": \"conductor\", \"k\": [1, 2, 3]}"), ERR_JSON_VALUE,
                 "materials.gold.k", "without \"eta\"");
    expect_error(MAT("{\"type\": \"dielectric\", \"absorption\": [0, -1, 0]}"), ERR_JSON_VALUE,
                 "materials.gold.absorption", "-1");
    expect_error(MAT("{\"type\": \"conductor\", \"anisotropy\": 1}"), ERR_JSON_VALUE,
                 "materials.gold.anisotropy", "1 is out of range [0, 1)");
    expect_error(MAT("{\"type\": \"diffuse\", \"albedo\": [0.5, 1.5, 0]}"), ERR_JSON_VALUE,
                 "materials.gold.albedo", "1.5");
    expect_error(MAT("{\"type\": \"diffuse\", \"opacity\": 2}"), ERR_JSON_VALUE,
                 "materials.gold.opacity", "2");
    expect_error(MAT("{\"type\": \"diffuse\", \"emission\": -1}"), ERR_JSON_VALUE,
                 "materials.gold.emission", "-1");
    expect_error(MAT("{\"type\": \"mix\", \"a\": \"x\", \"b\": \"x\", \"weight\": 1.25}, "
                     "\"x\": {\"type\": \"diffuse\"}"), ERR_JSON_VALUE, "materials.gold.weight", "1.25");
}

Test(material_json, wrong_types_and_unknown_keys)
{
    expect_error(MAT("{\"roughness\": 0.5}"), ERR_JSON_VALUE, "materials.gold.type", "missing");
    expect_error(MAT("{\"type\": \"metal\"}"), ERR_JSON_VALUE, "materials.gold.type", "\"metal\"");
    expect_error(MAT("{\"type\": \"diffuse\", \"roughness\": 0.5}"), ERR_JSON_UNKNOWN_KEY,
                 "materials.gold.roughness", "albedo");
    expect_error(MAT("{\"type\": \"diffuse\", \"albedo\": [1, 2]}"), ERR_JSON_TYPE,
                 "materials.gold.albedo", "3 numbers");
    expect_error(MAT("{\"type\": \"conductor\", \"eta\": \"tex\"}"), ERR_JSON_TYPE,
                 "materials.gold.eta", "[r, g, b] or a number");
    expect_error(MAT("{\"type\": \"diffuse\", \"normal_map\": 1}"), ERR_JSON_TYPE,
                 "materials.gold.normal_map", "texture name");
    expect_error("\"materials\": [1]", ERR_JSON_TYPE, "materials", "object");
    expect_error("\"textures\": {\"t\": {\"file\": \"a.png\", \"encoding\": \"gamma\"}}",
                 ERR_JSON_VALUE, "textures.t.encoding", "\"gamma\"");
    expect_error("\"textures\": {\"t\": {\"type\": \"voronoi\"}}", ERR_JSON_VALUE, "textures.t.type",
                 "\"voronoi\"");
    expect_error("\"textures\": {\"t\": {\"type\": \"noise\", \"octaves\": 0}}", ERR_JSON_VALUE,
                 "textures.t.octaves", "0");
    expect_error("\"textures\": {\"t\": {\"type\": \"noise\", \"frequency\": -2}}", ERR_JSON_VALUE,
                 "textures.t.frequency", "-2");
    expect_error("\"textures\": {\"t\": {\"type\": \"noise\", \"file\": \"a.png\"}}",
                 ERR_JSON_UNKNOWN_KEY, "textures.t.file", "color0");
    expect_error("\"textures\": {\"t\": {\"encoding\": \"srgb\"}}", ERR_JSON_VALUE, "textures.t.file",
                 "missing");
}

Test(material_json, unknown_names_self_reference_and_cycles)
{
    expect_error(MAT("{\"type\": \"diffuse\", \"albedo\": \"bricks\"}"), ERR_JSON_VALUE,
                 "materials.gold.albedo", "\"bricks\"");
    expect_error(MAT("{\"type\": \"conductor\", \"roughness\": \"rough\"}"), ERR_JSON_VALUE,
                 "materials.gold.roughness", "\"rough\"");
    expect_error(MAT("{\"type\": \"mix\", \"a\": \"silver\", \"b\": \"gold\"}"), ERR_JSON_VALUE,
                 "materials.gold.a", "\"silver\"");
    expect_error(MAT("{\"type\": \"mix\", \"a\": \"x\", \"b\": \"gold\"}, \"x\": {\"type\": \"diffuse\"}"),
                 ERR_JSON_VALUE, "materials.gold.b", "itself");
    expect_error(MAT("{\"type\": \"mix\", \"a\": \"x\", \"b\": \"y\"}, \"y\": {\"type\": \"diffuse\"}, "
                     "\"x\": {\"type\": \"mix\", \"a\": \"y\", \"b\": \"gold\"}"),
                 ERR_JSON_VALUE, "materials.gold", "cycle");
    expect_error(MAT("{\"type\": \"mix\", \"b\": \"gold\"}"), ERR_JSON_VALUE, "materials.gold.a",
                 "missing");
    expect_error("\"objects\": [{\"obj\": \"two.obj\", \"material\": \"brass\"}]", ERR_JSON_VALUE,
                 "objects[0].material", "\"brass\"");
}

Test(material_json, texture_files_that_do_not_decode_and_grey_normal_maps)
{
    write_file("junk.png", "not a png at all");
    expect_error("\"textures\": {\"t\": {\"file\": \"junk.png\"}}", ERR_TEXTURE, "textures.t.file",
                 "junk.png");
    expect_error("\"textures\": {\"t\": {\"file\": \"absent.png\"}}", ERR_FILE_MISSING,
                 "textures.t.file", "absent.png");
    const unsigned char grey[] = {128, 200};
    write_png("grey1.png", 1, grey);
    expect_error("\"textures\": {\"g\": {\"file\": \"grey1.png\", \"encoding\": \"linear\"}}, "
                 MAT("{\"type\": \"diffuse\", \"normal_map\": \"g\"}"),
                 ERR_TEXTURE, "materials.gold.normal_map", "1 channel");
}
