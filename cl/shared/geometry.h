/* SPDX-License-Identifier: MIT */
/* shared/geometry.h: triangles, BVH node layouts and instances. Part of cl/shared.h (read its rules); the host includes it through
 * shared.h, the kernels' program has it right after shared.h (Makefile CL_SOURCES). */
#ifndef PT_SHARED_GEOMETRY_H
#define PT_SHARED_GEOMETRY_H

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
/* Two levels (FEATURE_INSTANCES with FEATURE_TLAS): a TLAS walk's entries, then one BLAS's, each
 * bounded as one tree's. */
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
 * flattened once into the vertex and triangle arrays, in object space. With two BVH levels
 * (FEATURE_TLAS) each mesh has one BVH (BLAS) in bvh_nodes/bvh_tris, and a top-level BVH (TLAS)
 * over the instances' world boxes comes first in bvh_nodes (root 0), its leaves naming instances;
 * with a flat BVH (FEATURE_INSTANCES alone, host/accel/scene_bvh.h BVH_FLAT) bvh_nodes/bvh_tris
 * hold one BVH over every instance's triangles in world space and flat_prims maps them back.
 * Objects without a transform whose mesh is used once are merged into one mesh in world space
 * (instance 0, the identity); a scene that has nothing else is built one-level (without
 * FEATURE_INSTANCES, shared/features.h: bvh_nodes is that mesh's BVH, as in v1). Triangle
 * indices (Hit.prim, LightEntry.triangle) are global, into triangles[]. */
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

#endif
