// SPDX-License-Identifier: MIT
#include "render/scene_upload.h"

#include <string.h>

#include "accel/bvh_wide.h"

static cl_mem upload(Device *dev, SceneBuffers *out, const char *name, size_t size, const void *data,
                     Error *err)
{
    if (error_is_set(err))
        return NULL;
    out->bytes += size;
    return device_buffer(dev, name, CL_MEM_READ_ONLY, size, data, err);
}

bool scene_buffers_upload(Device *dev, const SceneData *data, const Bvh *bvh, SceneBuffers *out,
                          Error *err)
{
    memset(out, 0, sizeof *out);
    size_t nv = data->num_vertices, nt = data->num_triangles;
    out->positions = upload(dev, out, "positions", nv * sizeof(float4), data->positions, err);
    out->normals = upload(dev, out, "normals", nv * sizeof(float4), data->normals, err);
    out->uvs = upload(dev, out, "uvs", nv * sizeof(float2), data->uvs, err);
    out->triangles = upload(dev, out, "triangles", nt * sizeof(Triangle), data->triangles, err);
    out->material_ids = upload(dev, out, "material_ids", nt * sizeof(uint32_t), data->material_ids, err);
    out->materials = upload(dev, out, "materials", data->num_materials * sizeof(Material),
                            data->materials, err);
    out->texels = upload(dev, out, "texels", data->textures.num_texels * sizeof(uint32_t),
                         data->textures.texels, err);
    out->textures = upload(dev, out, "textures", data->textures.count * sizeof(TextureInfo),
                           data->textures.infos, err);
    BvhLayout layout;
    bvh_layout(&layout, bvh, dev->bvh_width, dev->bvh_quantized);
    out->bvh_nodes = upload(dev, out, "bvh_nodes", layout.num_nodes * layout.node_size, layout.nodes,
                            err);
    out->bvh_tris = upload(dev, out, "bvh_triangles", layout.num_prims * layout.prim_size,
                           layout.prims, err);
    out->num_bvh_prims = layout.num_prims;
    bvh_layout_free(&layout);
    if (error_is_set(err)) {
        scene_buffers_release(out);
        return false;
    }
    return true;
}

void scene_buffers_release(SceneBuffers *b)
{
    cl_mem all[] = {b->positions, b->normals, b->uvs, b->triangles, b->material_ids,
                    b->materials, b->texels, b->textures, b->bvh_nodes, b->bvh_tris};
    for (size_t i = 0; i < sizeof all / sizeof all[0]; i++)
        if (all[i])
            CL_CHECK(clReleaseMemObject(all[i]));
    memset(b, 0, sizeof *b);
}
