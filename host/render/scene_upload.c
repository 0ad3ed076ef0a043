// SPDX-License-Identifier: MIT
#include "render/scene_upload.h"

#include <string.h>

#include "accel/bvh_wide.h"
#include "scene/lights.h"

/* Where one scene buffer's contents come from. */
typedef struct {
    size_t size;
    const void *data;
    bool given; /* false: scene_buffers_upload names no source for it (a bug) */
} BufferSource;

static BufferSource source(size_t count, size_t element_size, const void *data)
{
    return (BufferSource){count * element_size, data, true};
}

bool scene_buffers_upload(Device *dev, const SceneData *data, const Bvh *bvh, SceneBuffers *out,
                          Error *err)
{
    memset(out, 0, sizeof *out);
    size_t nv = data->num_vertices, nt = data->num_triangles;
    BvhLayout layout;
    bvh_layout(&layout, bvh, dev->bvh_width, dev->bvh_quantized);
    LightTable lights;
    light_table_build(&lights, data);
    struct {
#define SOURCE_MEMBER(type, name) BufferSource name;
        SCENE_BUFFERS(SOURCE_MEMBER)
#undef SOURCE_MEMBER
    } src = {0};
    src.bvh_nodes = source(layout.num_nodes, layout.node_size, layout.nodes);
    src.bvh_tris = source(layout.num_prims, layout.prim_size, layout.prims);
    src.positions = source(nv, sizeof(float4), data->positions);
    src.normals = source(nv, sizeof(float4), data->normals);
    src.uvs = source(nv, sizeof(float2), data->uvs);
    src.triangles = source(nt, sizeof(Triangle), data->triangles);
    src.material_ids = source(nt, sizeof(uint32_t), data->material_ids);
    src.materials = source(data->num_materials, sizeof(Material), data->materials);
    src.texels = source(data->textures.num_texels, sizeof(uint32_t), data->textures.texels);
    src.textures = source(data->textures.count, sizeof(TextureInfo), data->textures.infos);
    src.lights = source(lights.count, sizeof(LightEntry), lights.entries);
    src.analytic_lights = source(lights.num_analytic, sizeof(AnalyticLight), lights.analytic);
    out->num_analytic = lights.num_analytic;
    const Environment *env = &data->environment;
    size_t env_w = env->width, env_h = env->height;
    src.env_texels = source(env_w * env_h, sizeof(float4), env->texels);
    src.env_alias = source(env_w * env_h, sizeof(EnvAlias), env->alias);
    out->env_width = env->width;
    out->env_height = env->height;
    out->env_rotation = env->rotation;
    out->env_pick_pdf = lights.env_pick_pdf;
    out->num_bvh_prims = layout.num_prims;
    out->num_emissive = lights.count;
    out->emissive_power = lights.total_power;

#define UPLOAD(type, name)                                                                         \
    if (!src.name.given)                                                                           \
        die("scene_buffers_upload: no source for scene buffer " #name);                            \
    if (!error_is_set(err)) {                                                                      \
        out->name = device_buffer(dev, #name, CL_MEM_READ_ONLY, src.name.size, src.name.data, err); \
        out->bytes += src.name.size;                                                               \
    }
    SCENE_BUFFERS(UPLOAD)
#undef UPLOAD
    bvh_layout_free(&layout);
    light_table_free(&lights);
    if (error_is_set(err)) {
        scene_buffers_release(out);
        return false;
    }
    return true;
}

void scene_buffers_release(SceneBuffers *b)
{
#define RELEASE(type, name)                                                                        \
    if (b->name)                                                                                   \
        CL_CHECK(clReleaseMemObject(b->name));
    SCENE_BUFFERS(RELEASE)
#undef RELEASE
    memset(b, 0, sizeof *b);
}

cl_uint scene_buffers_set_args(const SceneBuffers *b, cl_kernel kernel, cl_uint first)
{
    cl_uint i = first;
#define SET_ARG(type, name) KERNEL_ARG(kernel, i++, b->name);
    SCENE_BUFFERS(SET_ARG)
#undef SET_ARG
    return i;
}
