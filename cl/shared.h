/* SPDX-License-Identifier: MIT */
/* shared.h: every struct and constant that crosses the host/device boundary. Compiled by the host C
 * compiler (through host/base/shared_types.h) and by the OpenCL C compiler (first file of the program).
 * Rules: only 4-byte scalars, float2/float4/uint4 (float8/uint8 in the 8-wide BVH); no float3, bool,
 * size_t, enum or pointers. SHARED_STRUCTS (end of file) lists every struct and field for the
 * layout checks on both sides. */
#ifndef PT_SHARED_H
#define PT_SHARED_H

#ifndef __OPENCL_C_VERSION__
/* Host prelude: map OpenCL C names onto <CL/cl.h> types. */
#include <CL/cl.h>
typedef cl_float4 float4;
typedef cl_float2 float2;
typedef cl_uint4 uint4;
typedef cl_float8 float8;
typedef cl_uint8 uint8;
typedef cl_uint uint;
#endif

/* The structs by concern, in dependency order (cl/shared/). The kernels' program lists them right
 * after this file instead (an OpenCL program is one text: Makefile CL_SOURCES). */
#ifndef __OPENCL_C_VERSION__
#include "shared/features.h"
#include "shared/program_parts.h"
#include "shared/geometry.h"
#include "shared/material.h"
#include "shared/medium.h"
#include "shared/render.h"
#endif

/* ---- Layout checks ------------------------------------------------------------------------- */

/* Every struct of the files in cl/shared/ with its size, then each of its fields in order. Host
 * and device expand it alike: host/base/shared_types.h asserts the sizes at compile time, the
 * report_layout test kernel (tests/cl/sizes.cl) writes sizeof and offsetof of every field, and
 * tests/test_device.c compares them with the host's and checks that the fields fill the struct
 * (none left out, no padding).
 * A new shared struct or field gets one line here. */
#define SHARED_STRUCTS(STRUCT, FIELD)                                                              \
    STRUCT(Triangle, 16) FIELD(Triangle, v)                                                         \
    STRUCT(BvhNode, 64) FIELD(BvhNode, lmin) FIELD(BvhNode, lmax) FIELD(BvhNode, rmin)              \
        FIELD(BvhNode, rmax)                                                                        \
    STRUCT(BvhNodeQuantized, 32) FIELD(BvhNodeQuantized, frame) FIELD(BvhNodeQuantized, refs)       \
    STRUCT(BvhTriangle, 48) FIELD(BvhTriangle, v0) FIELD(BvhTriangle, v1) FIELD(BvhTriangle, v2)    \
    STRUCT(BvhNode4, 112) FIELD(BvhNode4, lo) FIELD(BvhNode4, hi) FIELD(BvhNode4, child)            \
    STRUCT(TrianglePack4, 160) FIELD(TrianglePack4, v) FIELD(TrianglePack4, prim)                   \
    STRUCT(BvhNode8, 224) FIELD(BvhNode8, lo) FIELD(BvhNode8, hi) FIELD(BvhNode8, child)            \
    STRUCT(TrianglePack8, 320) FIELD(TrianglePack8, v) FIELD(TrianglePack8, prim)                   \
    STRUCT(Material, 192) FIELD(Material, base) FIELD(Material, emission) FIELD(Material, eta)     \
        FIELD(Material, k) FIELD(Material, absorption) FIELD(Material, specular_color)              \
        FIELD(Material, roughness) FIELD(Material, anisotropy) FIELD(Material, metallic)            \
        FIELD(Material, opacity) FIELD(Material, ior) FIELD(Material, specular)                     \
        FIELD(Material, weight) FIELD(Material, bump_scale) FIELD(Material, type)                   \
        FIELD(Material, flags) FIELD(Material, mix_a) FIELD(Material, mix_b) FIELD(Material, tex)   \
        FIELD(Material, interior) FIELD(Material, exterior) FIELD(Material, subsurface)             \
        FIELD(Material, pad0)                                                                       \
    STRUCT(TextureInfo, 48) FIELD(TextureInfo, offset) FIELD(TextureInfo, width)                    \
        FIELD(TextureInfo, height) FIELD(TextureInfo, format) FIELD(TextureInfo, flags)             \
        FIELD(TextureInfo, scale) FIELD(TextureInfo, transform)                                     \
    STRUCT(Camera, 64) FIELD(Camera, eye) FIELD(Camera, right) FIELD(Camera, up)                    \
        FIELD(Camera, forward)                                                                      \
    STRUCT(SceneParams, 48) FIELD(SceneParams, num_bvh_prims) FIELD(SceneParams, num_instances)    \
        FIELD(SceneParams, num_emissive) FIELD(SceneParams, num_analytic)                           \
        FIELD(SceneParams, emissive_power) FIELD(SceneParams, env_pick_pdf)                         \
        FIELD(SceneParams, env_width) FIELD(SceneParams, env_height)                                \
        FIELD(SceneParams, env_rotation) FIELD(SceneParams, num_media)                              \
        FIELD(SceneParams, world_medium) FIELD(SceneParams, camera_medium)                          \
    STRUCT(RenderParams, 192) FIELD(RenderParams, camera) FIELD(RenderParams, background)           \
        FIELD(RenderParams, scene) FIELD(RenderParams, width) FIELD(RenderParams, height)           \
        FIELD(RenderParams, seed) FIELD(RenderParams, max_depth) FIELD(RenderParams, sample_index)  \
        FIELD(RenderParams, aov) FIELD(RenderParams, flags) FIELD(RenderParams, window_start)       \
        FIELD(RenderParams, window_size) FIELD(RenderParams, shutter_open)                          \
        FIELD(RenderParams, shutter_close) FIELD(RenderParams, window_pixels)                       \
        FIELD(RenderParams, clamp_indirect) FIELD(RenderParams, pixel_offset)                       \
        FIELD(RenderParams, pad0) FIELD(RenderParams, pad1)                                         \
    STRUCT(LightEntry, 32) FIELD(LightEntry, prob) FIELD(LightEntry, alias)                         \
        FIELD(LightEntry, triangle) FIELD(LightEntry, pdf) FIELD(LightEntry, instance)              \
        FIELD(LightEntry, pad0) FIELD(LightEntry, pad1) FIELD(LightEntry, pad2)                     \
    STRUCT(Instance, 112) FIELD(Instance, to_world) FIELD(Instance, to_object)                      \
        FIELD(Instance, blas_root) FIELD(Instance, motion) FIELD(Instance, first_prim)              \
        FIELD(Instance, num_prims)                                                                  \
    STRUCT(InstanceMotion, 160) FIELD(InstanceMotion, translation) FIELD(InstanceMotion, rotation)  \
        FIELD(InstanceMotion, scale)                                                                \
    STRUCT(AnalyticLight, 80) FIELD(AnalyticLight, position) FIELD(AnalyticLight, color)            \
        FIELD(AnalyticLight, axis) FIELD(AnalyticLight, params) FIELD(AnalyticLight, type)          \
        FIELD(AnalyticLight, pad0) FIELD(AnalyticLight, pad1) FIELD(AnalyticLight, pad2)          \
    STRUCT(BlackHole, 96) FIELD(BlackHole, centre) FIELD(BlackHole, normal)                        \
        FIELD(BlackHole, tangent) FIELD(BlackHole, radii) FIELD(BlackHole, emission)               \
        FIELD(BlackHole, noise)                                                                     \
    STRUCT(Medium, 144) FIELD(Medium, sigma_a) FIELD(Medium, sigma_s) FIELD(Medium, emission)      \
        FIELD(Medium, to_index) FIELD(Medium, type) FIELD(Medium, flags) FIELD(Medium, res_x)       \
        FIELD(Medium, res_y) FIELD(Medium, res_z) FIELD(Medium, bricks_x) FIELD(Medium, bricks_y)   \
        FIELD(Medium, bricks_z) FIELD(Medium, brick_table) FIELD(Medium, values)                    \
        FIELD(Medium, majorants) FIELD(Medium, pad0)

/* Words written by report_layout: per struct its size, per field its offset and size. */
#define SHARED_LAYOUT_STRUCT_WORDS(type, size) +1
#define SHARED_LAYOUT_FIELD_WORDS(type, field) +2
#define SHARED_LAYOUT_WORDS (0 SHARED_STRUCTS(SHARED_LAYOUT_STRUCT_WORDS, SHARED_LAYOUT_FIELD_WORDS))

#endif
