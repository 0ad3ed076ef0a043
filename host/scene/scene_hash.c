// SPDX-License-Identifier: MIT
#include "scene/scene_hash.h"

#include <stddef.h>
#include <string.h>

static const uint64_t K1 = 0xbf58476d1ce4e5b9ull, K2 = 0x9e3779b97f4a7c15ull;

static uint64_t load_le64(const uint8_t *p)
{
    uint64_t v = 0;
    for (int i = 7; i >= 0; i--)
        v = v << 8 | p[i];
    return v;
}

static void mix_word(Hash64 *s, uint64_t w)
{
    w *= K1;
    w ^= w >> 31;
    s->h = (s->h ^ w) * K2;
}

void hash64_init(Hash64 *s)
{
    memset(s, 0, sizeof *s);
    s->h = 0x243f6a8885a308d3ull; /* pi's digits: any odd constant */
}

void hash64_bytes(Hash64 *s, const void *data, size_t size)
{
    const uint8_t *p = data;
    size_t have = s->length % 8;
    s->length += size;
    if (have) {
        size_t take = 8 - have < size ? 8 - have : size;
        memcpy(s->tail + have, p, take);
        p += take, size -= take;
        if (have + take < 8)
            return;
        mix_word(s, load_le64(s->tail));
    }
    for (; size >= 8; p += 8, size -= 8)
        mix_word(s, load_le64(p));
    memcpy(s->tail, p, size);
}

void hash64_u32(Hash64 *s, uint32_t v)
{
    uint8_t b[4] = {(uint8_t)v, (uint8_t)(v >> 8), (uint8_t)(v >> 16), (uint8_t)(v >> 24)};
    hash64_bytes(s, b, sizeof b);
}

void hash64_u64(Hash64 *s, uint64_t v)
{
    hash64_u32(s, (uint32_t)v);
    hash64_u32(s, (uint32_t)(v >> 32));
}

void hash64_float(Hash64 *s, float v)
{
    uint32_t bits;
    memcpy(&bits, &v, sizeof bits);
    hash64_u32(s, bits);
}

uint64_t hash64_finish(const Hash64 *s)
{
    Hash64 t = *s;
    size_t have = t.length % 8;
    if (have) {
        memset(t.tail + have, 0, 8 - have);
        mix_word(&t, load_le64(t.tail));
    }
    uint64_t z = t.h ^ t.length;
    z = (z ^ (z >> 30)) * K1;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

uint64_t hash64(const void *data, size_t size)
{
    Hash64 s;
    hash64_init(&s);
    hash64_bytes(&s, data, size);
    return hash64_finish(&s);
}

/* An array: its count first, so that moving elements between two arrays changes the hash. The
 * element types are the device's (cl/shared.h), laid out without implicit padding. */
static void hash_array(Hash64 *s, const void *data, size_t count, size_t element_size)
{
    hash64_u64(s, count);
    if (count)
        hash64_bytes(s, data, count * element_size);
}

static void hash_floats(Hash64 *s, const float *v, int n)
{
    for (int i = 0; i < n; i++)
        hash64_float(s, v[i]);
}

static void hash_doubles(Hash64 *s, const double *v, int n)
{
    for (int i = 0; i < n; i++) {
        uint64_t bits;
        memcpy(&bits, &v[i], sizeof bits);
        hash64_u64(s, bits);
    }
}

/* Field by field: SceneInstance has padding after `moving`, whose bytes are not the scene's. */
static void hash_instance(Hash64 *s, const SceneInstance *in)
{
    hash64_u32(s, in->mesh);
    hash64_u32(s, (uint32_t)in->object);
    hash_doubles(s, &in->to_world.m[0][0], 12);
    hash64_u32(s, in->moving);
    for (int k = 0; k < 2 && in->moving; k++) {
        hash_doubles(s, in->motion[k].t, 3);
        hash_doubles(s, in->motion[k].q, 4);
        hash_doubles(s, &in->motion[k].s[0][0], 9);
    }
}

static void hash_mesh(Hash64 *s, const SceneMesh *m)
{
    hash64_u32(s, m->first_triangle), hash64_u32(s, m->num_triangles);
    hash64_u32(s, m->first_vertex), hash64_u32(s, m->num_vertices);
}

static void hash_camera(Hash64 *s, const CameraDesc *c)
{
    hash_floats(s, c->eye, 3), hash_floats(s, c->target, 3), hash_floats(s, c->up, 3);
    hash64_float(s, c->fov_y), hash64_float(s, c->aperture), hash64_float(s, c->focus_distance);
    hash64_float(s, c->shutter_open), hash64_float(s, c->shutter_close);
}

uint64_t scene_hash(const Scene *scene)
{
    const SceneData *d = &scene->data;
    const SceneDesc *desc = &scene->desc;
    Hash64 s;
    hash64_init(&s);
    hash64_bytes(&s, "pt scene 3", 10); /* bump when what is hashed changes */
    hash_array(&s, d->positions, d->num_vertices, sizeof *d->positions);
    hash_array(&s, d->normals, d->num_vertices, sizeof *d->normals);
    hash_array(&s, d->uvs, d->num_vertices, sizeof *d->uvs);
    hash_array(&s, d->triangles, d->num_triangles, sizeof *d->triangles);
    hash_array(&s, d->material_ids, d->num_triangles, sizeof *d->material_ids);
    /* Up to the last field: the struct may end in padding (float4 alignment). */
    hash64_u32(&s, d->num_materials);
    for (uint32_t m = 0; m < d->num_materials; m++)
        hash64_bytes(&s, &d->materials[m],
                     offsetof(Material, subsurface) + sizeof d->materials[m].subsurface);
    /* Media (shared/medium.h: no implicit padding, pad0 is zeroed by every writer) and grids. */
    hash_array(&s, d->media, d->num_media, sizeof *d->media);
    hash64_u32(&s, d->world_medium), hash64_u32(&s, d->camera_medium);
    hash_array(&s, d->grid_bricks, d->num_grid_bricks, sizeof *d->grid_bricks);
    hash_array(&s, d->grid_values, d->num_grid_values, sizeof *d->grid_values);
    hash_array(&s, d->grid_majorants, d->num_grid_majorants, sizeof *d->grid_majorants);
    hash_array(&s, d->textures.texels, d->textures.num_texels, sizeof *d->textures.texels);
    hash_array(&s, d->textures.infos, d->textures.count, sizeof *d->textures.infos);
    hash_array(&s, d->emissive_triangles, d->num_emissive, sizeof *d->emissive_triangles);
    hash64_u32(&s, d->num_meshes);
    for (uint32_t m = 0; m < d->num_meshes; m++)
        hash_mesh(&s, &d->meshes[m]);
    hash64_u32(&s, d->num_instances);
    for (uint32_t i = 0; i < d->num_instances; i++)
        hash_instance(&s, &d->instances[i]);
    hash64_u32(&s, d->two_level);
    hash64_u32(&s, d->keep_two_levels); /* two levels or a flat BVH: the hits' rounding differs */
    hash_array(&s, d->analytic_lights, d->num_analytic, sizeof *d->analytic_lights);
    const Environment *env = &d->environment;
    size_t env_texels = (size_t)env->width * env->height;
    hash64_u32(&s, env->width), hash64_u32(&s, env->height);
    hash_array(&s, env->texels, env_texels, sizeof *env->texels);
    hash_array(&s, env->cdf, environment_cdf_count(env), sizeof *env->cdf);
    hash64_float(&s, env->rotation);
    hash_array(&s, desc->black_holes, (size_t)desc->num_black_holes, sizeof *desc->black_holes);
    hash_camera(&s, &desc->camera);
    hash64_u32(&s, (uint32_t)desc->width), hash64_u32(&s, (uint32_t)desc->height);
    hash_floats(&s, desc->background, 3);
    return hash64_finish(&s);
}
