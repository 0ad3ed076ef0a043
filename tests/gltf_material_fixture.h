/* SPDX-License-Identifier: MIT */
/* gltf_material_fixture.h: what the glTF material tests share: GltfMaterial records mapped through
 * gltf_materials_append and loaded (textures_load, materials_load) as scene_load loads JSON
 * materials, the equivalent JSON materials loaded the same way, and a field-by-field comparison
 * of the resulting Materials and of their textures (sampling and texels). Header-only (static
 * functions) so that each test binary builds from its own .c alone. */
#ifndef PT_TESTS_GLTF_MATERIAL_FIXTURE_H
#define PT_TESTS_GLTF_MATERIAL_FIXTURE_H

#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene/gltf_material.h"
#include "scene/material_json.h"
#include "support.h"

/* A file in the test's temporary folder (the JSON scene's folder too). */
static inline const char *fixture_path(const char *name)
{
    static char dir[256], paths[8][512];
    static int next;
    if (!dir[0])
        snprintf(dir, sizeof dir, "%s", test_temp_dir());
    char *p = paths[next++ % 8];
    snprintf(p, 512, "%s/%s", dir, name);
    return p;
}

/* images[i]: the file names[i] of the temporary folder. */
static inline void fixture_file_images(GltfImage *images, const char **names, int n)
{
    memset(images, 0, (size_t)n * sizeof *images);
    for (int i = 0; i < n; i++) {
        snprintf(images[i].path, sizeof images[i].path, "%s", fixture_path(names[i]));
        snprintf(images[i].json_path, sizeof images[i].json_path, "images[%d]", i);
    }
}

/* Loaded materials and the texture set they index. */
typedef struct {
    TextureSet set;
    Material *materials;
    int count;
} Loaded;

static inline bool fixture_load_descs(Loaded *out, const TextureDesc *td, int nt,
                                      const MaterialDesc *md, int nm, Error *err)
{
    memset(out, 0, sizeof *out);
    uint32_t *indices = calloc(nt ? (size_t)nt : 1, sizeof *indices);
    out->materials = calloc(nm ? (size_t)nm : 1, sizeof *out->materials);
    cr_assert(indices && out->materials);
    out->count = nm;
    bool ok = textures_load(td, nt, &out->set, indices, "test.gltf", err) &&
              materials_load(md, nm, td, &out->set, indices, 0, out->materials, "test.gltf", err);
    free(indices);
    return ok;
}

static inline void fixture_free(Loaded *l)
{
    texture_set_free(&l->set);
    free(l->materials);
}

/* gltf[0..n) mapped and loaded; false with err set when the mapping or the loading fails. */
static inline bool fixture_gltf(Loaded *out, const GltfMaterial *gltf, int n,
                                const GltfImage *images, int num_images, Error *err)
{
    MaterialDesc *md = NULL;
    TextureDesc *td = NULL;
    int nm = 0, nt = 0;
    bool ok = gltf_materials_append(gltf, n, images, num_images, "test.gltf", "test.gltf:", &md,
                                    &nm, &td, &nt, err) &&
              fixture_load_descs(out, td, nt, md, nm, err);
    free(md);
    free(td);
    return ok;
}

/* The one material of g (no images). */
static inline Material fixture_gltf_one(const GltfMaterial *g)
{
    Loaded l;
    Error err = {0};
    cr_assert(fixture_gltf(&l, g, 1, NULL, 0, &err), "%s", err.message);
    Material m = l.materials[0];
    fixture_free(&l);
    return m;
}

/* {"textures": {textures}, "materials": {materials}} read as scene_json reads them (paths against
 * the temporary folder) and loaded. */
static inline void fixture_json(Loaded *out, const char *materials, const char *textures)
{
    char text[8192];
    snprintf(text, sizeof text, "{\"textures\": {%s}, \"materials\": {%s}}", textures, materials);
    Error err = {0};
    JsonParser p = {fixture_path("scene.json"), text, &err};
    cJSON *root = json_parse_text(p.file, text, &err);
    cr_assert(root, "%s", err.message);
    TextureDesc *td = NULL;
    MaterialDesc *md = NULL;
    int nt = 0, nm = 0;
    cr_assert(textures_from_json(&p, json_member(root, "textures"), &td, &nt), "%s", err.message);
    cr_assert(materials_from_json(&p, json_member(root, "materials"), td, nt, &md, &nm), "%s",
              err.message);
    cr_assert(fixture_load_descs(out, td, nt, md, nm, &err), "%s", err.message);
    free(td);
    free(md);
    cJSON_Delete(root);
}

/* Texels of texture t as uints (its whole image). */
static inline size_t fixture_texel_uints(const TextureInfo *t)
{
    return (size_t)t->width * t->height * (t->format == TEXTURE_RGBA32F ? 4 : 1);
}

static inline void expect_same_texture(const Loaded *a, uint32_t ta, const Loaded *b, uint32_t tb,
                                       const char *what)
{
    cr_expect_eq(ta == NO_TEXTURE, tb == NO_TEXTURE, "%s: textured in one only", what);
    if (ta == NO_TEXTURE || tb == NO_TEXTURE)
        return;
    const TextureInfo *x = &a->set.infos[ta], *y = &b->set.infos[tb];
    cr_expect(x->width == y->width && x->height == y->height && x->format == y->format,
              "%s: %ux%u format %u vs %ux%u format %u", what, x->width, x->height, x->format,
              y->width, y->height, y->format);
    cr_expect_eq(x->flags, y->flags, "%s: flags %#x vs %#x", what, x->flags, y->flags);
    if (x->flags & TEXTURE_FLAG_SCALE)
        cr_expect(fabsf(x->scale - y->scale) < 1e-6f, "%s: scale %g vs %g", what, x->scale, y->scale);
    for (int i = 0; (x->flags & TEXTURE_FLAG_TRANSFORM) && i < 6; i++)
        cr_expect(fabsf(x->transform[i] - y->transform[i]) < 1e-6f, "%s: transform[%d] %g vs %g",
                  what, i, x->transform[i], y->transform[i]);
    if (x->width == y->width && x->height == y->height && x->format == y->format)
        cr_expect(memcmp(a->set.texels + x->offset, b->set.texels + y->offset,
                         fixture_texel_uints(x) * 4) == 0,
                  "%s: texels differ", what);
}

static inline void expect_close(float x, float y, const char *what, const char *field)
{
    cr_expect(fabsf(x - y) <= 1e-6f * (1.0f + fabsf(y)), "%s: %s %.9g vs %.9g", what, field, x, y);
}

static inline void expect_close4(const float4 *x, const float4 *y, int n, const char *what,
                                 const char *field)
{
    for (int c = 0; c < n; c++)
        expect_close(x->s[c], y->s[c], what, field);
}

/* Materials a[ia] and b[ib] equal in every field the kernels read: a constant that a texture
 * replaces (roughness, metallic, opacity, weight) is not compared; mixes compare their parts. */
static inline void expect_same_material(const Loaded *a, uint32_t ia, const Loaded *b, uint32_t ib,
                                        const char *what, int depth)
{
    cr_assert(ia < (uint32_t)a->count && ib < (uint32_t)b->count && depth < 4, "%s", what);
    const Material *x = &a->materials[ia], *y = &b->materials[ib];
    cr_expect_eq(x->type, y->type, "%s: type %u vs %u", what, x->type, y->type);
    cr_expect_eq(x->flags, y->flags, "%s: flags %#x vs %#x", what, x->flags, y->flags);
    expect_close4(&x->base, &y->base, (x->flags & MATERIAL_FLAG_ALPHA_MASK) ? 4 : 3, what, "base");
    expect_close4(&x->emission, &y->emission, 4, what, "emission");
    expect_close4(&x->eta, &y->eta, 3, what, "eta");
    expect_close4(&x->k, &y->k, 3, what, "k");
    expect_close4(&x->absorption, &y->absorption, 3, what, "absorption");
    expect_close4(&x->specular_color, &y->specular_color, 3, what, "specular_color");
    const uint32_t *tx = x->tex;
    if (tx[MATERIAL_TEX_ROUGHNESS] == NO_TEXTURE)
        expect_close(x->roughness, y->roughness, what, "roughness");
    if (tx[MATERIAL_TEX_METALLIC] == NO_TEXTURE)
        expect_close(x->metallic, y->metallic, what, "metallic");
    if (tx[MATERIAL_TEX_OPACITY] == NO_TEXTURE)
        expect_close(x->opacity, y->opacity, what, "opacity");
    if (tx[MATERIAL_TEX_WEIGHT] == NO_TEXTURE)
        expect_close(x->weight, y->weight, what, "weight");
    expect_close(x->anisotropy, y->anisotropy, what, "anisotropy");
    expect_close(x->ior, y->ior, what, "ior");
    expect_close(x->specular, y->specular, what, "specular");
    expect_close(x->bump_scale, y->bump_scale, what, "bump_scale");
    for (int s = 0; s < MATERIAL_TEX_COUNT; s++) {
        char slot[160];
        snprintf(slot, sizeof slot, "%s: texture slot %d", what, s);
        expect_same_texture(a, tx[s], b, y->tex[s], slot);
    }
    if (x->type == MATERIAL_MIX && y->type == MATERIAL_MIX) {
        char part[160];
        snprintf(part, sizeof part, "%s: mix a", what);
        expect_same_material(a, x->mix_a, b, y->mix_a, part, depth + 1);
        snprintf(part, sizeof part, "%s: mix b", what);
        expect_same_material(a, x->mix_b, b, y->mix_b, part, depth + 1);
    }
}

/* gltf[0]'s material equals the JSON material "m" (listed first) of json_materials. */
static inline void expect_gltf_equals_json(const GltfMaterial *gltf, int n, const GltfImage *images,
                                           int num_images, const char *json_materials,
                                           const char *json_textures, const char *what)
{
    Loaded a, b;
    Error err = {0};
    cr_assert(fixture_gltf(&a, gltf, n, images, num_images, &err), "%s: %s", what, err.message);
    fixture_json(&b, json_materials, json_textures);
    expect_same_material(&a, 0, &b, 0, what, 0);
    fixture_free(&a);
    fixture_free(&b);
}

#endif
