/* SPDX-License-Identifier: MIT */
/* bvh_node_2wide.cl: the 2-wide tree's nodes as the walks read them (host/accel/bvh_build.c's
 * float node, host/accel/bvh_quantized.c's quantised one): child references and leaves, the walk's
 * packed leaf entries, and test_children, both child boxes of a node at once. The walks are in
 * bvh_traverse.cl and bvh_traverse_speculative.cl. */
#if BVH_WIDTH == 2 /* else cl/geometry/bvh_traverse_wide.cl */
/* A child reference is an inner node index, or a leaf (sign bit set) whose triangle range is
 * spelled differently by the two node formats: the float node has ~first in the reference and the
 * count in a lane of its own (`lane`), the quantised one packs both into the reference. */
inline bool child_is_leaf(uint ref) { return as_int(ref) < 0; }

/* A leaf as an entry of a walk (its next node, its stack, trace_scene_bvh's node) when it is not
 * intersected at once: sign bit, first triangle (a TLAS's: instance) << 4, count. The quantised
 * reference is already this; the float node's leaf is packed so on entry, which bounds its
 * triangles and instances as the quantised layout's (host/accel/scene_bvh.c). */
inline uint walk_leaf(uint first, uint count)
{
    return BVH_QUANTIZED_LEAF | (first << BVH_QUANTIZED_COUNT_BITS) | count;
}
inline uint walk_leaf_first(uint entry)
{
    return (entry & ~BVH_QUANTIZED_LEAF) >> BVH_QUANTIZED_COUNT_BITS;
}
inline uint walk_leaf_count(uint entry)
{
    return entry & ((1u << BVH_QUANTIZED_COUNT_BITS) - 1u);
}

#if BVH_QUANTIZED
inline uint leaf_first(uint ref, uint lane) { return walk_leaf_first(ref); }
inline uint leaf_count(uint ref, uint lane) { return walk_leaf_count(ref); }

/* The frame of a quantised node, as seen by one ray: the distance to the frame's origin planes
 * and the distance per step, per axis (plane = origin + q * step, so t = q * per_step + at_origin). */
typedef struct {
    float3 at_origin, per_step;
} QuantizedFrame;

inline float3 frame_origin(uint4 frame)
{
    return (float3)(as_float(frame.x & ~0xffu), as_float(frame.y & ~0xffu), as_float(frame.z & ~0xffu));
}
inline float3 frame_step(uint4 frame)
{
    return (float3)(as_float((frame.x & 0xffu) << 23), as_float((frame.y & 0xffu) << 23),
                    as_float((frame.z & 0xffu) << 23));
}

inline float box_slack(const global BvhNodeQuantized *root, float3 origin, WatertightRay tray)
{
    float3 lo = frame_origin(root->frame);
    return box_slack_of(lo, lo + 255.0f * frame_step(root->frame), origin, tray);
}

inline float quantized_plane(uint word, uint shift) { return (float)((word >> shift) & 0xffu); }

/* box_entry for the child whose plane bytes start at bit `base` of each axis word (0: left, 16:
 * right). Byte base + 0 is the box's low plane, base + 8 its high one: the entry plane is the
 * high one where the direction is negative. NaN (a ray in a plane, or 0 steps times an infinite
 * inverse direction) is dropped as in box_entry: the box is kept, never wrongly culled. */
inline bool quantized_box_entry(BoxRay ray, QuantizedFrame f, uint3 words, uint base, float tmin,
                                float tmax, float *t_entry)
{
    uint sx = base + ((uint)ray.dir_negative.x & 8u);
    uint sy = base + ((uint)ray.dir_negative.y & 8u);
    uint sz = base + ((uint)ray.dir_negative.z & 8u);
    float t0 = max_into(fma(quantized_plane(words.x, sx), f.per_step.x, f.at_origin.x), tmin);
    t0 = max_into(fma(quantized_plane(words.y, sy), f.per_step.y, f.at_origin.y), t0);
    t0 = max_into(fma(quantized_plane(words.z, sz), f.per_step.z, f.at_origin.z), t0);
    float t1 = min_into(fma(quantized_plane(words.x, sx ^ 8u), f.per_step.x, f.at_origin.x), tmax);
    t1 = min_into(fma(quantized_plane(words.y, sy ^ 8u), f.per_step.y, f.at_origin.y), t1);
    t1 = min_into(fma(quantized_plane(words.z, sz ^ 8u), f.per_step.z, f.at_origin.z), t1);
    *t_entry = t0;
    return t0 <= t1 * BOX_EXIT_SCALE;
}

/* Both children of a node: whether the ray meets each box within [tmin, tmax], where it enters,
 * and the child's reference (lane unused). */
inline void test_children(const global BvhNodeQuantized *node, BoxRay ray, float tmin, float tmax,
                          bool hit[2], float t[2], uint ref[2], uint lane[2])
{
    uint4 frame = node->frame, refs = node->refs;
    QuantizedFrame f;
    f.at_origin = (frame_origin(frame) - ray.origin) * ray.inv_dir;
    f.per_step = frame_step(frame) * ray.inv_dir;
    uint3 words = (uint3)(frame.w, refs.x, refs.y);
    hit[0] = quantized_box_entry(ray, f, words, 0u, tmin, tmax, &t[0]);
    hit[1] = quantized_box_entry(ray, f, words, 16u, tmin, tmax, &t[1]);
    ref[0] = refs.z;
    ref[1] = refs.w;
    lane[0] = lane[1] = 0u;
}
#else
inline uint leaf_first(uint ref, uint lane) { return ~ref; }
inline uint leaf_count(uint ref, uint lane) { return lane; }

inline float box_slack(const global BvhNode *root, float3 origin, WatertightRay tray)
{
    float3 lo = fmin(xyz(root->lmin), xyz(root->rmin));
    float3 hi = fmax(xyz(root->lmax), xyz(root->rmax));
    return box_slack_of(lo, hi, origin, tray);
}

/* The float node: references in the w lanes of the box minima, leaf counts in those of the maxima. */
inline void test_children(const global BvhNode *node, BoxRay ray, float tmin, float tmax,
                          bool hit[2], float t[2], uint ref[2], uint lane[2])
{
    float4 lmin = node->lmin, lmax = node->lmax, rmin = node->rmin, rmax = node->rmax;
    hit[0] = box_entry(ray, lmin, lmax, tmin, tmax, &t[0]);
    hit[1] = box_entry(ray, rmin, rmax, tmin, tmax, &t[1]);
    ref[0] = as_uint(lmin.w);
    ref[1] = as_uint(rmin.w);
    lane[0] = as_uint(lmax.w);
    lane[1] = as_uint(rmax.w);
}
#endif

/* A child reference as a walk entry: inner nodes as they are, leaves as walk_leaf (the quantised
 * reference already is one). */
inline uint walk_entry(uint ref, uint lane)
{
#if BVH_QUANTIZED
    return ref;
#else
    return child_is_leaf(ref) ? walk_leaf(~ref, lane) : ref;
#endif
}
#endif /* BVH_WIDTH == 2 */
