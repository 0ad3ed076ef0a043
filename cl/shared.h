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

/* ---- Geometry ------------------------------------------------------------------------------ */

/* Triangle corner indices into the vertex arrays (positions, normals, uvs share one index space),
 * w = TRIANGLE_* flags. Per-triangle material ids live in their own array. */
#define TRIANGLE_HAS_NORMALS 1u /* interpolate normals[]; otherwise shade with the geometric normal */
#define TRIANGLE_HAS_UVS 2u     /* interpolate uvs[]; otherwise uv = barycentrics */
typedef struct {
    uint4 v; /* x, y, z: vertex indices; w: flags */
} Triangle;

/* Hit.prim and the path state's hit.w (as_float) of a ray that hit nothing. */
#define HIT_NONE 0xffffffffu

/* BVH node, 2-wide with both children's boxes in the parent (Aila & Laine 2009): one 64-byte fetch
 * decides which children to visit. For each child: box min in xyz, box max in xyz; the w lanes hold
 * the child reference: child_index >= 0 is an inner node, otherwise ~first_triangle with the count
 * in the matching count lane. */
typedef struct {
    float4 lmin; /* left child box min; w: as_float(left reference) */
    float4 lmax; /* left child box max; w: as_float(left triangle count, 0 for an inner node) */
    float4 rmin; /* right child box min; w: as_float(right reference) */
    float4 rmax; /* right child box max; w: as_float(right triangle count) */
} BvhNode;

/* The same node quantised to 32 bytes, one memory sector of a GPU, for the 2-wide traversal with
 * -DBVH_QUANTIZED=1 (host/accel/bvh_quantized.c; after Ylitie, Karras & Laine 2017, "Efficient incoherent
 * ray traversal on GPUs through compressed wide BVHs"). Each child box plane is an 8-bit step count
 * in a per-node frame, plane = origin + q * step along each axis, rounded outwards so that the
 * quantised box holds the exact one. frame.xyz: the origin's float bits with the low 8 mantissa
 * bits replaced by the biased exponent of step (step = 2^(e - 127); the origin is rounded down to
 * fit). Plane words, one per axis (frame.w: x, refs.x: y, refs.y: z): bytes [left lo, left hi,
 * right lo, right hi]. refs.zw: left and right child, an inner node index or
 * BVH_QUANTIZED_LEAF | first_triangle << 4 | count. */
typedef struct {
    uint4 frame;
    uint4 refs;
} BvhNodeQuantized;
#define BVH_QUANTIZED_LEAF 0x80000000u
#define BVH_QUANTIZED_COUNT_BITS 4u
/* first_triangle < this limit */
#define BVH_QUANTIZED_MAX_TRIANGLES (1u << (31u - BVH_QUANTIZED_COUNT_BITS))

/* Triangle in BVH leaf order, precomputed for the intersection test. */
typedef struct {
    float4 v0; /* w: as_float(original triangle index) */
    float4 v1;
    float4 v2;
} BvhTriangle;

/* Entries of the traversal's private stack; host/accel/bvh_build.c bounds the tree's depth so it never
 * overflows. */
#define BVH_STACK_SIZE 64
/* Two levels (PT_FEATURE_INSTANCES): a TLAS walk's entries, then one BLAS's, each bounded as one
 * tree's. */
#define BVH_SCENE_STACK_SIZE (2 * BVH_STACK_SIZE)

/* Wide BVH for CPUs (host/accel/bvh_wide.c, cl/geometry/bvh_traverse_wide.cl): the 2-wide tree collapsed to 4 or 8
 * children per node, stored lane by lane so that one SIMD instruction tests every child box, and
 * leaves of triangle packs tested 4 or 8 at a time. A CPU runs a work item on one core lane by
 * lane; these float4/float8 operations are what keep its SIMD units busy. GPUs keep the 2-wide
 * layout (a work item already is a SIMD lane there). Child lane i: box lo[axis].si .. hi[axis].si
 * (an unused lane holds the empty box +inf .. -inf and child 0); child.si >= 0: inner node index,
 * else a leaf ~(first_pack << 2 | (pack_count - 1)). Pack lane i: corners v[3 * corner + axis].si,
 * original triangle index prim.si; a leaf's last pack repeats its last triangle in unused lanes. */
#define BVH_WIDE_LEAF_PACK_BITS 2u
typedef struct {
    float4 lo[3];
    float4 hi[3];
    uint4 child;
} BvhNode4;
typedef struct {
    float4 v[9];
    uint4 prim;
} TrianglePack4;
typedef struct {
    float8 lo[3];
    float8 hi[3];
    uint8 child;
} BvhNode8;
typedef struct {
    float8 v[9];
    uint8 prim;
} TrianglePack8;
/* The wide traversal's stack: each level of the wide tree pushes at most width - 1 children; the
 * collapse (bvh_layout) checks that no path needs more. */
#define BVH_WIDE_STACK_SIZE 192
#define BVH_WIDE_SCENE_STACK_SIZE (2 * BVH_WIDE_STACK_SIZE)

/* The layout the kernels are compiled for: -DBVH_WIDTH=2 (default), 4 or 8 (host/device/program.c). */
#ifdef __OPENCL_C_VERSION__
#ifndef BVH_WIDTH
#define BVH_WIDTH 2
#endif
#ifndef BVH_QUANTIZED
#define BVH_QUANTIZED 0
#endif
#if BVH_WIDTH == 8
typedef BvhNode8 TraversalNode;
typedef TrianglePack8 TraversalPrim;
#elif BVH_WIDTH == 4
typedef BvhNode4 TraversalNode;
typedef TrianglePack4 TraversalPrim;
#elif BVH_WIDTH == 2 && BVH_QUANTIZED
typedef BvhNodeQuantized TraversalNode;
typedef BvhTriangle TraversalPrim;
#elif BVH_WIDTH == 2
typedef BvhNode TraversalNode;
typedef BvhTriangle TraversalPrim;
#else
#error "BVH_WIDTH must be 2, 4 or 8"
#endif
#endif

/* ---- Instances (shared/DESIGN.md "Objects"; host/scene/instances.c, cl/geometry/instance.cl) -- */

/* A scene is a set of instances of meshes. Every mesh (an OBJ with its material override) is
 * flattened once into the vertex and triangle arrays, in object space, and has one BVH (BLAS) in
 * bvh_nodes/bvh_tris; a top-level BVH (TLAS) over the instances' world boxes comes first in
 * bvh_nodes (root 0) and its leaves name instances. Objects without a transform whose mesh is
 * used once are merged into one mesh in world space (instance 0, the identity); a scene that has
 * nothing else is built one-level (-DPT_FEATURE_INSTANCES=0: bvh_nodes is that mesh's BVH, as in
 * v1). Triangle indices (Hit.prim, LightEntry.triangle) are global, into triangles[]. */
/* What the kernels assume without -DPT_FEATURE_INSTANCES (tests and tools build so), and so the
 * layout the tests' scenes are built with (tests/support.h PT_TESTS_TWO_LEVEL). */
#define PT_FEATURE_INSTANCES_DEFAULT 1
#define INSTANCE_STATIC 0xffffffffu /* Instance.motion of an instance that does not move */
typedef struct {
    float4 to_world[3];  /* rows of the 3x4 object-to-world matrix M (p' = M p); a moving
                            instance's at shutter open (the light table's reference) */
    float4 to_object[3]; /* rows of M^-1 */
    uint blas_root;      /* the mesh's BLAS root, an index into bvh_nodes */
    uint motion;         /* index into instance_motion, or INSTANCE_STATIC */
    uint first_prim;     /* the mesh's entries of bvh_tris (triangles or packs): the brute-force */
    uint num_prims;      /* ablation's range */
} Instance;

/* The motion of a moving instance: M(s) = T(s) R(s) S(s) with s = (time - open) / (close - open),
 * T and S linear in s, R slerped along the shortest arc (host/base/transform.h trs_*). */
typedef struct {
    float4 translation[2]; /* T at open and close; w unused */
    float4 rotation[2];    /* unit quaternions (x, y, z, w); dot(open, close) >= 0 */
    float4 scale[6];       /* rows of the symmetric 3x3 S: 0-2 at open, 3-5 at close; w unused */
} InstanceMotion;

/* ---- Materials and textures ---------------------------------------------------------------- */

/* Material types: X(NAME, "json name"). The values are the kernels' Material.type. */
#define MATERIAL_TYPES(X)                                                                          \
    X(DIFFUSE, "diffuse")       /* Lambert */                                                      \
    X(CONDUCTOR, "conductor")   /* GGX, complex Fresnel; roughness 0 = perfect mirror */           \
    X(DIELECTRIC, "dielectric") /* GGX (Walter 2007); roughness 0 = smooth glass */                \
    X(PRINCIPLED, "principled") /* glTF 2.0 metallic-roughness */                                  \
    X(MIX, "mix")               /* (1 - weight) a + weight b, resolved stochastically per hit */
#define MATERIAL_TYPE_ENUM(name, json) MATERIAL_##name,
enum { MATERIAL_TYPES(MATERIAL_TYPE_ENUM) MATERIAL_TYPE_COUNT };
#undef MATERIAL_TYPE_ENUM

/* Texture slots of a Material: X(NAME, "json key"). A slot holds a texture index or NO_TEXTURE;
 * a textured colour multiplies the constant, a textured scalar replaces it (its red channel). */
#define MATERIAL_TEXTURE_SLOTS(X)                                                                  \
    X(BASE, "base")           /* albedo | reflectance | tint | base_color (rgb, multiplies) */     \
    X(EMISSION, "emission")   /* rgb, multiplies emission */                                       \
    X(ROUGHNESS, "roughness") /* scalar */                                                         \
    X(METALLIC, "metallic")   /* scalar */                                                         \
    X(OPACITY, "opacity")     /* scalar (an RGBA base texture's alpha is put here by the host) */  \
    X(WEIGHT, "weight")       /* scalar, mix */                                                    \
    X(NORMAL, "normal_map")   /* tangent-space normal, linear */                                   \
    X(BUMP, "bump_map")       /* height, red channel */
#define MATERIAL_TEXTURE_SLOT_ENUM(name, json) MATERIAL_TEX_##name,
enum { MATERIAL_TEXTURE_SLOTS(MATERIAL_TEXTURE_SLOT_ENUM) MATERIAL_TEX_COUNT };
#undef MATERIAL_TEXTURE_SLOT_ENUM

#define MATERIAL_FLAG_FRESNEL_ONE 1u  /* conductor without eta/k: Fresnel 1 */
#define MATERIAL_FLAG_CUTOUT 2u       /* opacity < 1 somewhere: rays may pass through */
#define MATERIAL_FLAG_BASE_ALPHA 4u   /* the BASE texture's alpha multiplies the opacity */

#define NO_TEXTURE 0xffffffffu
/* Material features a scene may use. The kernels are built with -DPT_MATERIAL_FEATURES=mask of the
 * scene's (host/scene/materials.c material_features; cl/core/util.cl defaults to all): the code of
 * the others leaves shade_surface, whose registers it would cost plain scenes (measured on the
 * H200: every lobe inlined made a diffuse-only box's shading 50% slower). */
#define MATERIAL_FEATURE_ROUGH_CONDUCTOR 1u   /* a conductor that is not a perfect mirror */
#define MATERIAL_FEATURE_CONDUCTOR_FRESNEL 2u /* a conductor with eta/k (not Fresnel 1) */
#define MATERIAL_FEATURE_ROUGH_DIELECTRIC 4u  /* a dielectric that is not smooth */
#define MATERIAL_FEATURE_PRINCIPLED 8u
#define MATERIAL_FEATURE_MIX 16u
#define MATERIAL_FEATURE_SURFACE_DETAIL 32u   /* normal or bump map, or anisotropy */
#define MATERIAL_FEATURE_TEXTURED_SCALARS 64u /* roughness, metallic or mix weight from a texture */
#define MATERIAL_FEATURE_ABSORPTION 128u      /* a dielectric with Beer-Lambert absorption */
#define MATERIAL_FEATURE_NOISE_TEXTURE 256u   /* a procedural texture (fBm, inlined at every lookup) */
#define MATERIAL_FEATURE_EMISSION_TEXTURE 512u
#define MATERIAL_FEATURE_ALL 0x3ffu

/* Mixes nest at most this deep (the host refuses deeper ones and cycles). */
#define MATERIAL_MIX_DEPTH_LIMIT 8u

/* One material as the kernels see it (shared/DESIGN.md "Materials"); textures are looked up at
 * the hit. Unused members of a type are 0 (textures NO_TEXTURE). */
typedef struct {
    float4 base;           /* rgb: diffuse albedo, conductor reflectance, dielectric tint or
                              principled base_color; w unused */
    float4 emission;       /* rgb: emitted radiance times emission_strength (one-sided, front =
                              counter-clockwise side); w: luminance, times the emission texture's
                              mean luminance when textured (the light table's weight) */
    float4 eta;            /* rgb: conductor eta; w unused */
    float4 k;              /* rgb: conductor k; w unused */
    float4 absorption;     /* rgb: dielectric Beer-Lambert sigma per scene unit; w unused */
    float4 specular_color; /* rgb: principled specular_color; w unused */
    float roughness;       /* [0, 1]; GGX alpha = roughness^2 */
    float anisotropy;      /* [0, 1) */
    float metallic;        /* principled */
    float opacity;         /* [0, 1]; 1 = opaque */
    float ior;             /* dielectric and principled */
    float specular;        /* principled (KHR_materials_specular) */
    float weight;          /* mix: weight of b */
    float bump_scale;
    uint type;             /* MATERIAL_* */
    uint flags;            /* MATERIAL_FLAG_* */
    uint mix_a, mix_b;     /* mix: material indices */
    uint tex[MATERIAL_TEX_COUNT]; /* MATERIAL_TEX_* slots: texture index or NO_TEXTURE */
} Material;

#define TEXTURE_RGBA8_SRGB 0u /* one uint per texel, r in the low byte, sRGB-encoded rgb */
#define TEXTURE_RGBA32F 1u    /* four uints per texel (float bits), linear */
/* Procedural fBm Perlin noise in object space: `offset` points to 9 uints, color0 rgb, color1 rgb,
 * frequency (float bits), octaves, seed (uint); width = height = 1. */
#define TEXTURE_NOISE 2u

typedef struct {
    uint offset; /* first uint of the texture in the texel buffer */
    uint width;
    uint height;
    uint format; /* TEXTURE_* */
} TextureInfo;

/* ---- Camera and per-render parameters ------------------------------------------------------- */

typedef struct {
    float4 eye;     /* xyz: position; w: lens radius (0 = pinhole) */
    float4 right;   /* unit vector, image +x; w: focus distance */
    float4 up;      /* unit vector, image -y (rows go down); w: tan(fov_y / 2) */
    float4 forward; /* unit vector toward the target; w: aspect (width / height) */
} Camera;

#define AOV_ALBEDO 0u
#define AOV_NORMAL 1u
#define AOV_DEPTH 2u

typedef struct {
    Camera camera;
    float4 background; /* radiance of escaped rays */
    uint width;
    uint height;
    uint seed;
    uint max_depth;
    uint sample_index;   /* sample index of the batch's first path */
    uint num_bvh_prims;  /* entries of bvh_tris: triangles (2-wide) or triangle packs (wide) */
    uint num_emissive;   /* emissive triangles in the light table */
    uint aov;            /* AOV_* for render_aov */
    float emissive_power; /* total emitted power of the light table (for pdfs) */
    uint flags;          /* RENDER_* */
    uint batch_start;    /* pixel of the window's first sample (see PATH_STATE_FIELDS) */
    uint batch_size;     /* samples in the window */
    uint env_width;      /* environment map texels across (0: no map, background is the sky) */
    uint env_height;
    float env_rotation;  /* the map's rotation theta as a fraction of a turn */
    float env_pick_pdf;  /* probability that the light table picks the environment */
    uint num_analytic;   /* entries of analytic_lights (escaped rays look for suns there) */
    float shutter_open;  /* camera.shutter: each camera path draws its time uniformly in */
    float shutter_close; /* [open, close] (PT_FEATURE_MOTION); equal: no motion blur */
    uint num_instances;  /* entries of instances */
} RenderParams;

#define RENDER_NO_NEE 1u
#define RENDER_SHADOW_QUEUE 2u /* shadow rays appended to a queue (else: a flag per active slot) */

/* ---- Lights --------------------------------------------------------------------------------- */

/* One entry of the alias table over emissive triangles, chosen in proportion to emitted power
 * (area x luminance of Ke). Vose's method, built on the host (host/scene/lights.c). */
typedef struct {
    float prob;    /* probability of keeping this entry rather than its alias */
    uint alias;    /* entry taken otherwise */
    uint triangle; /* emissive triangle index, or LIGHT_ENVIRONMENT */
    float pdf;     /* probability of choosing this triangle */
    uint instance; /* the instance whose triangle it is (each instance's emitters are lights) */
    uint pad0, pad1, pad2;
} LightEntry;
/* LightEntry.triangle of the environment map's entry (its power: mean luminance x 4 pi R^2, R the
 * scene's bounding-sphere radius; triangles count area x luminance: both are power / pi). */
#define LIGHT_ENVIRONMENT 0xffffffffu
/* LightEntry.triangle of analytic light i (analytic_lights[i]): LIGHT_ANALYTIC_BASE + i. Triangle
 * indices stay far below (BVH_QUANTIZED_MAX_TRIANGLES). */
#define LIGHT_ANALYTIC_BASE 0x80000000u

/* One entry of the environment map's alias table over its texels (host/scene/environment.c):
 * texel i is kept with probability prob, else its alias is taken. */
typedef struct {
    float prob;
    uint alias;
} EnvAlias;

/* Analytic lights (JSON "lights", shared/DESIGN.md "Lights"; host/scene/analytic_lights.c). */
#define LIGHT_POINT 0u
#define LIGHT_SPOT 1u
#define LIGHT_DIRECTIONAL 2u
#define LIGHT_SUN 3u
typedef struct {
    float4 position; /* point/spot: position; directional/sun: unit direction the light travels */
    float4 color;    /* point/spot: intensity (W/sr, rgb); directional/sun: irradiance; w: luminance */
    float4 axis;     /* spot: unit axis (where it shines) */
    float4 params;   /* spot: x cone, y falloff half-angles (radians); sun: x cos(half-angle),
                        y radiance / irradiance = 1 / (pi sin^2(half-angle)), z 1 / cone solid angle
                        (0 for angle 0: a delta light); w: the light table's pick probability */
    uint type;       /* LIGHT_POINT .. LIGHT_SUN */
    uint pad0, pad1, pad2;
} AnalyticLight;

/* ---- Scene buffers ------------------------------------------------------------------------- */

/* The scene's read-only device buffers: element type (as the kernels see it) and name. The
 * host's SceneBuffers, its upload and release (host/render/scene_upload.c), the kernels' parameter
 * list (SCENE_PARAMS, cl/stages/path_state.cl), the host's argument binding and the SceneView
 * that kernels hand to their helpers all expand from this list: a new buffer is one line here
 * plus where its data comes from in scene_buffers_upload. bvh_tris holds BvhTriangles (2-wide)
 * or triangle packs (wide layouts). */
#define SCENE_BUFFERS(X)                                                                           \
    X(TraversalNode, bvh_nodes)                                                                     \
    X(TraversalPrim, bvh_tris)                                                                      \
    X(float4, positions)                                                                            \
    X(float4, normals)                                                                              \
    X(float2, uvs)                                                                                  \
    X(Triangle, triangles)                                                                          \
    X(uint, material_ids)                                                                           \
    X(Material, materials)                                                                          \
    X(uint, texels)                                                                                 \
    X(TextureInfo, textures)                                                                        \
    X(LightEntry, lights)                                                                           \
    X(AnalyticLight, analytic_lights)                                                               \
    X(float4, env_texels)      /* rgb radiance; w: pdf per unit uv area (host/scene/environment.h) */ \
    X(EnvAlias, env_alias)     /* the texels' alias table, env_width * env_height */           \
    X(Instance, instances)                                                                          \
    X(InstanceMotion, instance_motion) /* one per moving instance (at least one entry) */

#define SCENE_BUFFER_COUNT_ONE(type, name) +1
#define SCENE_BUFFER_COUNT (0 SCENE_BUFFERS(SCENE_BUFFER_COUNT_ONE))

#ifdef __OPENCL_C_VERSION__
/* The scene as kernels pass it to helpers: one private struct of the kernel's own buffer
 * parameters, built at kernel entry (OpenCL C 1.2 allows pointers to global memory in a private
 * struct, not in a kernel argument). Helpers take `const SceneView *scene`; once inlined, each
 * member is the kernel parameter itself, restrict and read-only. */
#define SCENE_VIEW_MEMBER(type, name) const global type *restrict name;
typedef struct {
    SCENE_BUFFERS(SCENE_VIEW_MEMBER)
} SceneView;
#undef SCENE_VIEW_MEMBER
#endif

/* ---- Wavefront path state ------------------------------------------------------------------ */

/* Structure of arrays. The host renders a window of batch_size samples at a time: window sample k
 * traces pixel (batch_start + k) % num_pixels, sample index sample_index + (batch_start + k) /
 * num_pixels. A pool of path slots (often fewer than the window's samples) traces them: a slot
 * whose path ends is refilled with the window's next sample (generate_camera_rays), so the pool
 * stays full until the window runs dry. PATH_STATE_FIELDS are per slot, SAMPLE_STATE_FIELDS per
 * window sample. The host's buffers, the clSetKernelArg loop and the kernels' parameter lists all
 * expand from these lists. */
#define PATH_STATE_FIELDS(X)                                                                       \
    X(float4, ray_origin)          /* xyz; w unused */                                              \
    X(float4, ray_direction)       /* xyz; w: solid-angle pdf of the BSDF sample, 0 if specular */  \
    X(float4, throughput)          /* rgb path weight; w unused */                                 \
    X(float4, hit)                 /* t, u, v, as_float(triangle) or HIT_NONE */                    \
    X(float4, shadow_origin)       /* xyz; w: tmax of the shadow ray */                            \
    X(float4, shadow_direction)    /* xyz; w unused */                                             \
    X(float4, shadow_contribution) /* rgb added if unoccluded; w: 1 when a shadow ray waits */     \
    X(uint, hit_instance)          /* the instance hit (PT_FEATURE_INSTANCES; else unused) */     \
    X(float, path_time)            /* shutter fraction s in [0, 1) (PT_FEATURE_MOTION, else 0) */ \
    X(uint, sample_id)             /* the window sample k the slot traces */                       \
    X(uint, path_depth)            /* depth of the ray to trace (1: camera ray); 0: free slot */
#define SAMPLE_STATE_FIELDS(X)                                                                     \
    X(float4, radiance)            /* rgb gathered so far by sample k's path */

/* Wavefront counters (one uint buffer). */
#define COUNTER_NONFINITE 0   /* samples whose radiance was NaN or Inf (dropped) */
#define COUNTER_SHADOW_RAYS 1 /* shadow rays traced in the current batch */
#define COUNTER_EXTENSION_RAYS 2 /* closest-hit rays traced in the current batch */
#define COUNTER_COUNT 4

/* ---- Film ---------------------------------------------------------------------------------- */

/* The film: FILM_WORDS 64-bit words per pixel (a ulong4 on the device, cl_ulong on the host):
 * the sums of r, g and b in fixed point, FILM_FRACTION_BITS bits after the point, then the
 * sample count. Each channel of a sample is clamped to [0, FILM_SAMPLE_MAX] and rounded to the
 * nearest step 2^-FILM_FRACTION_BITS; sums saturate at 2^64 - 1. Saturating integer addition of
 * non-negative numbers is associative and commutative, so the film's bits do not depend on how
 * the samples are split or in which order they arrive. Read it with film_sums_to_rgb
 * (host/render/film.h). */
#define FILM_WORDS 4
#define FILM_FRACTION_BITS 24
#define FILM_SAMPLE_MAX 1048576.0f /* 2^20 */

/* ---- Layout checks ------------------------------------------------------------------------- */

/* Every struct above with its size, then each of its fields in order. Host and device expand it
 * alike: host/base/shared_types.h asserts the sizes at compile time, the report_layout test kernel
 * (tests/cl/sizes.cl) writes sizeof and offsetof of every field, and tests/test_device.c compares
 * them with the host's and checks that the fields fill the struct (none left out, no padding).
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
    STRUCT(Material, 176) FIELD(Material, base) FIELD(Material, emission) FIELD(Material, eta)     \
        FIELD(Material, k) FIELD(Material, absorption) FIELD(Material, specular_color)              \
        FIELD(Material, roughness) FIELD(Material, anisotropy) FIELD(Material, metallic)            \
        FIELD(Material, opacity) FIELD(Material, ior) FIELD(Material, specular)                     \
        FIELD(Material, weight) FIELD(Material, bump_scale) FIELD(Material, type)                   \
        FIELD(Material, flags) FIELD(Material, mix_a) FIELD(Material, mix_b) FIELD(Material, tex)   \
    STRUCT(TextureInfo, 16) FIELD(TextureInfo, offset) FIELD(TextureInfo, width)                    \
        FIELD(TextureInfo, height) FIELD(TextureInfo, format)                                       \
    STRUCT(Camera, 64) FIELD(Camera, eye) FIELD(Camera, right) FIELD(Camera, up)                    \
        FIELD(Camera, forward)                                                                      \
    STRUCT(RenderParams, 160) FIELD(RenderParams, camera) FIELD(RenderParams, background)           \
        FIELD(RenderParams, width) FIELD(RenderParams, height) FIELD(RenderParams, seed)            \
        FIELD(RenderParams, max_depth) FIELD(RenderParams, sample_index)                            \
        FIELD(RenderParams, num_bvh_prims) FIELD(RenderParams, num_emissive)                        \
        FIELD(RenderParams, aov) FIELD(RenderParams, emissive_power) FIELD(RenderParams, flags)     \
        FIELD(RenderParams, batch_start) FIELD(RenderParams, batch_size)                            \
        FIELD(RenderParams, env_width) FIELD(RenderParams, env_height)                              \
        FIELD(RenderParams, env_rotation) FIELD(RenderParams, env_pick_pdf)                         \
        FIELD(RenderParams, num_analytic) FIELD(RenderParams, shutter_open)                         \
        FIELD(RenderParams, shutter_close) FIELD(RenderParams, num_instances)                       \
    STRUCT(LightEntry, 32) FIELD(LightEntry, prob) FIELD(LightEntry, alias)                         \
        FIELD(LightEntry, triangle) FIELD(LightEntry, pdf) FIELD(LightEntry, instance)              \
        FIELD(LightEntry, pad0) FIELD(LightEntry, pad1) FIELD(LightEntry, pad2)                     \
    STRUCT(Instance, 112) FIELD(Instance, to_world) FIELD(Instance, to_object)                      \
        FIELD(Instance, blas_root) FIELD(Instance, motion) FIELD(Instance, first_prim)              \
        FIELD(Instance, num_prims)                                                                  \
    STRUCT(InstanceMotion, 160) FIELD(InstanceMotion, translation) FIELD(InstanceMotion, rotation)  \
        FIELD(InstanceMotion, scale)                                                                \
    STRUCT(EnvAlias, 8) FIELD(EnvAlias, prob) FIELD(EnvAlias, alias)                               \
    STRUCT(AnalyticLight, 80) FIELD(AnalyticLight, position) FIELD(AnalyticLight, color)            \
        FIELD(AnalyticLight, axis) FIELD(AnalyticLight, params) FIELD(AnalyticLight, type)          \
        FIELD(AnalyticLight, pad0) FIELD(AnalyticLight, pad1) FIELD(AnalyticLight, pad2)

/* Words written by report_layout: per struct its size, per field its offset and size. */
#define SHARED_LAYOUT_STRUCT_WORDS(type, size) +1
#define SHARED_LAYOUT_FIELD_WORDS(type, field) +2
#define SHARED_LAYOUT_WORDS (0 SHARED_STRUCTS(SHARED_LAYOUT_STRUCT_WORDS, SHARED_LAYOUT_FIELD_WORDS))

#endif
