// SPDX-License-Identifier: MIT
#include "render/scene_upload.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/transform.h"
#include "scene/camera.h"
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

/* The TLAS's box of a static instance: its mesh's vertices transformed one by one (exact), not
 * the transformed corners of the mesh's box (SceneInstance.bounds_*), which grows by up to sqrt(2)
 * per axis for a turned instance and sends rays into instances they miss. Within a budget of
 * vertices over the whole scene, so that 10^4 instances of a 10^5-vertex mesh keep the corners'
 * box (bench/README.md "GPU throughput"). Only the TLAS takes these: the scene's bounds, which
 * frame the default camera and rig, stay as they were. */
#define EXACT_INSTANCE_BOX_BUDGET (8u << 20) /* vertices transformed, whole scene */
static void instance_tlas_box(const SceneData *data, const SceneInstance *si, uint64_t *budget,
                              float lo[3], float hi[3])
{
    const SceneMesh *mesh = &data->meshes[si->mesh];
    memcpy(lo, si->bounds_min, 3 * sizeof *lo);
    memcpy(hi, si->bounds_max, 3 * sizeof *hi);
    if (si->moving || mesh->num_vertices == 0 || mesh->num_vertices > *budget ||
        affine_is_identity(&si->to_world))
        return;
    *budget -= mesh->num_vertices;
    float elo[3], ehi[3];
    affine_points_box(&si->to_world, &data->positions[mesh->first_vertex], mesh->num_vertices,
                      elo, ehi);
    for (int k = 0; k < 3; k++) /* never larger than the corners' box: both hold the mesh */
        lo[k] = fmaxf(lo[k], elo[k]), hi[k] = fminf(hi[k], ehi[k]);
}

uint64_t scene_traced_triangles(const SceneData *data)
{
    if (!data->two_level)
        return data->num_triangles;
    uint64_t all = 0;
    for (uint32_t i = 0; i < data->num_instances; i++)
        all += data->meshes[data->instances[i].mesh].num_triangles;
    return all;
}

BvhLevels scene_accel_levels(const SceneData *data)
{
    if (!data->two_level)
        return BVH_ONE_LEVEL;
    if (data->keep_two_levels || data->num_moving > 0)
        return BVH_TWO_LEVEL;
    uint64_t baked = scene_traced_triangles(data);
    return baked > 0 && baked <= FLAT_BVH_TRIANGLE_BUDGET ? BVH_FLAT : BVH_TWO_LEVEL;
}

void scene_accel_build(SceneBvh *out, const SceneData *data, const Device *dev, BvhLevels levels)
{
    uint32_t nm = data->num_meshes, ni = data->num_instances;
    BvhMesh *meshes = malloc((nm ? nm : 1) * sizeof *meshes);
    BvhInstance *instances = malloc((ni ? ni : 1) * sizeof *instances);
    if (!meshes || !instances)
        die("out of memory for %u instances", ni);
    for (uint32_t m = 0; m < nm; m++)
        meshes[m] = (BvhMesh){data->meshes[m].first_triangle, data->meshes[m].num_triangles};
    uint64_t budget = EXACT_INSTANCE_BOX_BUDGET;
    for (uint32_t i = 0; i < ni; i++) {
        const SceneInstance *si = &data->instances[i];
        instances[i].mesh = si->mesh;
        instances[i].to_world = si->to_world;
        if (levels == BVH_TWO_LEVEL)
            instance_tlas_box(data, si, &budget, instances[i].lo, instances[i].hi);
    }
    /* One level: the whole triangle array is one world-space mesh. */
    BvhMesh all = {0, data->num_triangles};
    if (levels == BVH_ONE_LEVEL)
        scene_bvh_build(out, data->positions, data->triangles, &all, 1, NULL, 0, dev->bvh_width,
                        dev->bvh_quantized, BVH_ONE_LEVEL);
    else
        scene_bvh_build(out, data->positions, data->triangles, meshes, nm, instances, ni,
                        dev->bvh_width, dev->bvh_quantized, levels);
    free(meshes);
    free(instances);
}

void scene_instances_for_device(const SceneData *data, const SceneBvh *bvh, Instance **instances,
                                InstanceMotion **motions)
{
    uint32_t n = data->num_instances, nm = data->num_moving;
    *instances = calloc(n ? n : 1, sizeof **instances);
    *motions = calloc(nm ? nm : 1, sizeof **motions);
    if (!*instances || !*motions)
        die("out of memory for %u instances", n);
    uint32_t moving = 0;
    for (uint32_t i = 0; i < n; i++) {
        const SceneInstance *si = &data->instances[i];
        Instance *inst = &(*instances)[i];
        Affine inverse;
        if (!affine_invert(&si->to_world, &inverse))
            die("instance %u: singular transform (the scene loader refuses these)", i);
        affine_to_rows(&si->to_world, inst->to_world);
        affine_to_rows(&inverse, inst->to_object);
        uint32_t mesh = bvh->levels == BVH_TWO_LEVEL ? si->mesh : 0;
        inst->blas_root = bvh->blas_root[mesh];
        inst->first_prim = bvh->first_prim[mesh];
        inst->num_prims = bvh->num_mesh_prims[mesh];
        inst->motion = INSTANCE_STATIC;
        if (si->moving) {
            InstanceMotion *m = &(*motions)[moving];
            for (int key = 0; key < 2; key++) {
                const Trs *trs = &si->motion[key];
                for (int k = 0; k < 3; k++) {
                    m->translation[key].s[k] = (float)trs->t[k];
                    for (int j = 0; j < 3; j++)
                        m->scale[3 * key + k].s[j] = (float)trs->s[k][j];
                }
                for (int k = 0; k < 4; k++)
                    m->rotation[key].s[k] = (float)trs->q[k];
            }
            inst->motion = moving++;
        }
    }
}

bool scene_buffers_upload(Device *dev, const SceneData *data, const SceneBvh *bvh,
                          SceneBuffers *out, Error *err)
{
    memset(out, 0, sizeof *out);
    size_t nv = data->num_vertices, nt = data->num_triangles;
    Instance *instances;
    InstanceMotion *motions;
    scene_instances_for_device(data, bvh, &instances, &motions);
    LightTable lights;
    light_table_build(&lights, data);
    struct {
#define SOURCE_MEMBER(type, name) BufferSource name;
        SCENE_BUFFERS(SOURCE_MEMBER)
#undef SOURCE_MEMBER
    } src = {0};
    src.bvh_nodes = source(bvh->num_nodes, bvh->node_size, bvh->nodes);
    src.bvh_tris = source(bvh->num_prims, bvh->prim_size, bvh->prims);
    src.instances = source(data->num_instances, sizeof(Instance), instances);
    src.instance_motion = source(data->num_moving ? data->num_moving : 1, sizeof(InstanceMotion),
                                 motions);
    out->params.num_instances = data->num_instances;
    static const uint32_t no_flat_prim[2] = {0, 0};
    src.flat_prims = bvh->num_flat_prims
                         ? source(bvh->num_flat_prims, 2 * sizeof(uint32_t), bvh->flat_prims)
                         : source(1, sizeof no_flat_prim, no_flat_prim);
    src.positions = source(nv, sizeof(float4), data->positions);
    src.normals = source(nv, sizeof(float4), data->normals);
    src.uvs = source(nv, sizeof(float2), data->uvs);
    src.triangles = source(nt, sizeof(Triangle), data->triangles);
    src.material_ids = source(nt, sizeof(uint32_t), data->material_ids);
    src.materials = source(data->num_materials, sizeof(Material), data->materials);
    src.texels = source(data->textures.num_texels, sizeof(uint32_t), data->textures.texels);
    src.textures = source(data->textures.count, sizeof(TextureInfo), data->textures.infos);
    src.srgb_decode = source(TEXTURE_SRGB_CODES, sizeof(float), texture_srgb_decode_table());
    src.lights = source(lights.count, sizeof(LightEntry), lights.entries);
    src.analytic_lights = source(lights.num_analytic, sizeof(AnalyticLight), lights.analytic);
    out->params.num_analytic = lights.num_analytic;
    const Environment *env = &data->environment;
    size_t env_w = env->width, env_h = env->height;
    src.env_texels = source(env_w * env_h, sizeof(float4), env->texels);
    src.env_cdf = source(environment_cdf_count(env), sizeof(uint32_t), env->cdf);
    out->params.env_width = env->width;
    out->params.env_height = env->height;
    out->params.env_rotation = env->rotation;
    out->params.env_pick_pdf = lights.env_pick_pdf;
    /* Kernels index these only through a medium; an empty one still needs a buffer. */
    static const Medium no_medium;
    static const uint32_t no_brick = MEDIUM_NO_BRICK;
    static const float no_value;
    src.media = data->num_media ? source(data->num_media, sizeof(Medium), data->media)
                                : source(1, sizeof(Medium), &no_medium);
    src.grid_bricks = data->num_grid_bricks
                          ? source(data->num_grid_bricks, sizeof(uint32_t), data->grid_bricks)
                          : source(1, sizeof(uint32_t), &no_brick);
    src.grid_values = data->num_grid_values
                          ? source(data->num_grid_values, sizeof(float), data->grid_values)
                          : source(1, sizeof(float), &no_value);
    src.grid_majorants =
        data->num_grid_majorants
            ? source(data->num_grid_majorants, sizeof(float), data->grid_majorants)
            : source(1, sizeof(float), &no_value);
    out->params.num_media = data->num_media;
    out->params.world_medium = data->world_medium;
    out->params.camera_medium = data->camera_medium;
    out->params.num_bvh_prims = bvh->num_prims;
    out->params.num_emissive = lights.count;
    out->params.emissive_power = lights.total_power;

#define UPLOAD(type, name)                                                                         \
    if (!src.name.given)                                                                           \
        die("scene_buffers_upload: no source for scene buffer " #name);                            \
    if (!error_is_set(err)) {                                                                      \
        out->name = device_buffer(dev, #name, CL_MEM_READ_ONLY, src.name.size, src.name.data, err); \
        out->bytes += src.name.size;                                                               \
    }
    SCENE_BUFFERS(UPLOAD)
#undef UPLOAD
    free(instances);
    free(motions);
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
        device_release_buffer(b->name);
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

RenderParams render_params_for_scene(const SceneDesc *desc, const SceneBuffers *buffers)
{
    return (RenderParams){
        .camera = camera_from_desc(&desc->camera, desc->width, desc->height),
        .background = {{desc->background[0], desc->background[1], desc->background[2], 0.0f}},
        .scene = buffers->params,
        .width = (uint)desc->width,
        .height = (uint)desc->height,
        .shutter_open = desc->camera.shutter_open,
        .shutter_close = desc->camera.shutter_close,
    };
}
