/* SPDX-License-Identifier: MIT */
/* shared/render.h: camera and per-render parameters, lights, the scene buffers, the wavefront path state and the film. Part of cl/shared.h (read its rules); the host includes it through
 * shared.h, the kernels' program has it right after shared.h (Makefile CL_SOURCES). */
#ifndef PT_SHARED_RENDER_H
#define PT_SHARED_RENDER_H

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

/* The scalars that go with the scene's buffers (SCENE_BUFFERS below): their counts, the light
 * table's totals and the environment map's shape. Filled once, where the buffers are made
 * (scene_buffers_upload, host/render/scene_upload.c), and carried whole into every RenderParams;
 * kernels read p->scene.<field>. The camera, shutter and background stay in RenderParams: they
 * come from the scene description with the view, not from the uploaded data. */
typedef struct {
    uint num_bvh_prims;   /* entries of bvh_tris: triangles (2-wide) or triangle packs (wide) */
    uint num_instances;   /* entries of instances */
    uint num_emissive;    /* entries of the light table (lights) */
    uint num_analytic;    /* entries of analytic_lights (escaped rays look for suns there) */
    float emissive_power; /* total emitted power of the light table (for pdfs) */
    float env_pick_pdf;   /* probability that the light table picks the environment */
    uint env_width;       /* environment map texels across (0: no map, background is the sky) */
    uint env_height;
    float env_rotation;   /* the map's rotation theta as a fraction of a turn */
    uint num_media;       /* entries of media (shared/medium.h) */
    uint world_medium;    /* the medium slot that fills the world (0: none) */
    uint camera_medium;   /* the medium slot camera rays start in */
} SceneParams;

typedef struct {
    Camera camera;
    float4 background; /* radiance of escaped rays */
    SceneParams scene;
    uint width;
    uint height;
    uint seed;
    uint max_depth;
    uint sample_index;   /* sample index of the window's first sample */
    uint aov;            /* AOV_* for render_aov */
    uint flags;          /* RENDER_* */
    uint window_start;   /* pixel of the window's first sample (see PATH_STATE_FIELDS) */
    uint window_size;    /* samples in the window */
    float shutter_open;  /* camera.shutter: each camera path draws its time uniformly in */
    float shutter_close; /* [open, close] (PT_FEATURE(MOTION)); equal: no motion blur */
    /* Film and outputs (issue 19): adaptive sampling and the indirect clamp. */
    uint window_pixels;  /* pixels a window's samples cycle over (see PATH_STATE_FIELDS): width *
                          * height, or under RENDER_ADAPTIVE the length of active_pixels */
    float clamp_indirect; /* RENDER_CLAMP_INDIRECT: the most any channel of one indirect
                           * contribution may carry (shade_surface.cl, clamp_indirect) */
    uint pixel_offset;   /* the first pixel of the block being rendered (dist/work_units.h:
                          * a unit's tile is pixels pixel_offset .. + window_pixels - 1); 0
                          * under RENDER_ADAPTIVE, whose active_pixels name whole-film pixels */
    uint pad0, pad1; /* to a multiple of 16 bytes */
} RenderParams;

#define RENDER_NO_NEE 1u
#define RENDER_SHADOW_QUEUE 2u /* shadow rays appended to a queue (else: a flag per active slot) */
#define RENDER_ADAPTIVE 4u     /* window sample k traces pixel active_pixels[...] (window_pixel) */
#define RENDER_CLAMP_INDIRECT 8u /* contributions of 2+ bounces are clamped (clamp_indirect) */
#define RENDER_SOBOL 16u       /* the Sobol sampler (cl/core/sobol.cl), else independent numbers */
#define RENDER_BLACK_HOLES 32u /* the scene has black holes: ray_origin's w is `travelled` */

/* The samplers (render.sampler, --sampler): SAMPLER_DEFAULT (0) is "not given", and resolves to
 * SAMPLER_SOBOL (wavefront_init). X(NAME, "word"). */
#define SAMPLERS(X) X(SOBOL, "sobol") X(INDEPENDENT, "independent")
#define PT_SAMPLER_ENUM(name, word) SAMPLER_##name,
enum { SAMPLER_DEFAULT, SAMPLERS(PT_SAMPLER_ENUM) SAMPLER_COUNT };
#undef PT_SAMPLER_ENUM

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

/* ---- Black holes (JSON "black_holes", host/scene/black_holes.c; cl/stages/integrate_geodesic.cl) */

/* One Schwarzschild black hole, geometric units (G = c = 1: horizon radius 2M), and its optional
 * thin accretion disk through its centre. */
typedef struct {
    float4 centre;    /* xyz: position; w: mass M (> 0: holes of mass 0 are dropped at load) */
    float4 normal;    /* xyz: the disk's unit normal; w: influence radius (rays are straight beyond) */
    float4 tangent;   /* xyz: a unit vector in the disk plane (noise coordinates); w: 1 with a disk */
    float4 radii;     /* x: disk inner radius, y: outer, z: opacity, w: temperature at the inner
                         edge in kelvin (0: no blackbody colour, the emission as given) */
    float4 emission;  /* rgb: radiance scale; w unused */
    float4 noise;     /* x: frequency (cycles per inner radius), y: octaves (0: no noise),
                         z: swirl (radians of shear at the inner edge); w unused */
} BlackHole;

/* integrate_geodesic's step counts (a uint buffer, read by tools/bench_geodesic.c): curved rays,
 * their steps (mod 2^32), captured rays, then a histogram of steps per curved ray in bins of
 * GEODESIC_BIN_STEPS (the last bin holds everything beyond). */
#define GEODESIC_STAT_RAYS 0
#define GEODESIC_STAT_STEPS 1
#define GEODESIC_STAT_CAPTURED 2
#define GEODESIC_STAT_HISTOGRAM 4
#define GEODESIC_BINS 256
#define GEODESIC_BIN_STEPS 8
#define GEODESIC_STAT_WORDS (GEODESIC_STAT_HISTOGRAM + GEODESIC_BINS)

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
    X(float, srgb_decode)      /* each 8-bit sRGB code's linear value (host/scene/texture.h) */    \
    X(TextureInfo, textures)                                                                        \
    X(LightEntry, lights)                                                                           \
    X(AnalyticLight, analytic_lights)                                                               \
    X(float4, env_texels)      /* rgb radiance; w: pdf per unit uv area (host/scene/environment.h) */ \
    X(uint, env_cdf)           /* its sampling CDFs and guides, 2 (H + W H) (environment.h) */\
    X(Instance, instances)                                                                          \
    X(InstanceMotion, instance_motion) /* one per moving instance (at least one entry) */         \
    X(uint2, flat_prims)       /* a flat BVH's (instance, triangle) per baked triangle (else one) */ \
    X(Medium, media)           /* medium slot k is media[k - 1] (shared/medium.h) */              \
    X(uint, grid_bricks)       /* the grid media's brick tables */                                 \
    X(float, grid_values)      /* their bricks' voxel values */                                    \
    X(float, grid_majorants)   /* their bricks' largest densities */

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

/* Structure of arrays. The host renders a window of window_size samples at a time: window sample k
 * traces pixel (window_start + k) % window_pixels, sample index sample_index + (window_start + k) /
 * window_pixels (window_pixels = width * height; under RENDER_ADAPTIVE the pixel is
 * active_pixels[(window_start + k) % window_pixels], the pixels adaptive sampling still samples,
 * which all hold sample_index samples when the window starts). A pool of path slots (often fewer than the window's samples) traces them: a slot
 * whose path ends is refilled with the window's next sample (generate_camera_rays), so the pool
 * stays full until the window runs dry. PATH_STATE_FIELDS are per slot, SAMPLE_STATE_FIELDS per
 * window sample. The host's buffers, the clSetKernelArg loop and the kernels' parameter lists all
 * expand from these lists. A path on its pinhole camera ray has no ray_origin or throughput stored
 * (path_state.cl camera_state_implied): read those two through path_ray_origin and
 * path_throughput. */
#define PATH_STATE_FIELDS(X)                                                                       \
    X(float4, ray_origin)          /* xyz; w: travelled or eta scale (ray_origin_pack) */          \
    X(float4, ray_direction)       /* xyz; w: pdf_w (ray_direction_pack) */                        \
    X(float4, throughput)          /* rgb path weight; w: medium (throughput_pack) */              \
    X(float4, hit)                 /* t, u, v, prim (hit_pack) */                                  \
    X(float4, shadow_origin)       /* xyz; w: tmax (shadow_origin_pack) */                         \
    X(float4, shadow_direction)    /* xyz; w: bounce (shadow_direction_pack) */                    \
    X(float4, shadow_contribution) /* rgb added if unoccluded; w: waits (..._pack) */             \
    X(uint, hit_instance)          /* the instance hit (PT_FEATURE(INSTANCES); else unused) */     \
    X(float, path_time)            /* shutter fraction s in [0, 1) (PT_FEATURE(MOTION), else 0) */ \
    X(uint, sample_id)             /* the window sample k the slot traces */                       \
    X(uint, path_depth)            /* depth of the ray to trace (1: camera ray); 0: free slot */ \
    X(float, since_vertex)         /* PT_FEATURE(MEDIA), medium_state_crossed: distance from */     \
                                   /* the last scattering vertex to ray_origin */
#define SAMPLE_STATE_FIELDS(X)                                                                     \
    X(float4, radiance)            /* rgb gathered so far by sample k's path */
/* Per pixel (one entry when adaptive sampling is off): read by window_pixel. */
#define PIXEL_STATE_FIELDS(X)                                                                      \
    X(uint, active_pixels)         /* RENDER_ADAPTIVE: the pixels still sampled, ascending */

#ifdef __OPENCL_C_VERSION__
/* Each float4 lane of PATH_STATE_FIELDS packs a fourth value into w, written with its _pack and
 * read with its accessor: a slot's lane stays one 16-byte load and store (the GPU's shading is
 * bound by memory traffic), and no kernel reads a bare .w or as_uint. */

/* w: in a scene with black holes (ray_origin_bent), `travelled`, the length of the bent curve from
 * the segment's start to this origin, which intersect_closest_path adds to the hit's t
 * (integrate_geodesic.cl; 0 for every straight ray); otherwise `eta scale`, the product of eta^2
 * over the refractions the path has made (1 at the camera), which Russian roulette divides back
 * out of the throughput (shade_surface.cl survives_roulette). Scenes with black holes keep eta
 * scale 1. By the scene (RENDER_BLACK_HOLES), not only the program: a program with every feature
 * renders a scene without black holes to the bits of the scene's own program. */
inline bool ray_origin_bent(constant RenderParams *p)
{
    return PT_FEATURE(BLACK_HOLES) && (p->flags & RENDER_BLACK_HOLES);
}
inline float4 ray_origin_pack(float3 origin, float w) { return (float4)(origin, w); }
inline float ray_origin_travelled(float4 origin) { return origin.w; }
inline float ray_origin_eta_scale(constant RenderParams *p, float4 origin)
{
    return ray_origin_bent(p) ? 1.0f : origin.w;
}
/* A new straight segment from origin: travelled 0, or the path's eta scale. */
inline float4 ray_origin_pack_eta(constant RenderParams *p, float3 origin, float eta_scale)
{
    return ray_origin_pack(origin, ray_origin_bent(p) ? 0.0f : eta_scale);
}

/* pdf_w: the solid-angle density of the BSDF sample that chose the direction, 0 if specular (and
 * for the camera ray): emission and escaped rays weigh against light sampling with it. */
inline float4 ray_direction_pack(float3 direction, float pdf_w)
{
    return (float4)(direction, pdf_w);
}
inline float ray_direction_pdf_w(float4 direction) { return direction.w; }

/* medium: the path's medium state (medium_state below): which medium the segment runs in, and
 * how many interfaces the path has crossed. */
inline float4 throughput_pack(float3 beta, uint medium) { return (float4)(beta, as_float(medium)); }
inline uint throughput_medium(float4 throughput) { return as_uint(throughput.w); }

/* A medium state: the slot of the medium (shared/medium.h; low 16 bits, 0 = none), the count of
 * `interface` surfaces the path has passed through (bits 16-30, at most MEDIUM_CROSSING_LIMIT) and
 * whether it has passed one since its last scattering vertex (bit 31, medium_state_crossed; then
 * since_vertex holds the distance from that vertex to ray_origin, which an emitter hit's MIS
 * weight needs: light sampling saw the emitter from the vertex). A crossing is no bounce
 * (max_depth does not count it, as pbrt's volpath) but the next vertex must draw new numbers: its
 * bounce for the sampler is depth - 1 + crossings. medium_state: the state at a vertex (the bit
 * clear); medium_state_after_crossing: the state a crossing leaves. */
#define MEDIUM_CROSSING_LIMIT 32767u
#define MEDIUM_STATE_CROSSED 0x80000000u
inline uint medium_state(uint slot, uint crossings) { return slot | crossings << 16; }
inline uint medium_state_after_crossing(uint slot, uint crossings)
{
    return medium_state(slot, crossings) | MEDIUM_STATE_CROSSED;
}
inline uint medium_state_slot(uint state) { return state & 0xffffu; }
inline uint medium_state_crossings(uint state) { return (state >> 16) & 0x7fffu; }
inline bool medium_state_crossed(uint state) { return (state & MEDIUM_STATE_CROSSED) != 0u; }

/* t, u, v: distance and barycentrics; prim: the triangle, HIT_NONE for an escaped ray. */
inline float4 hit_pack(float t, float u, float v, uint prim)
{
    return (float4)(t, u, v, as_float(prim));
}
inline uint hit_prim(float4 hit) { return as_uint(hit.w); }
inline float hit_t(float4 hit) { return hit.x; }

/* tmax: the shadow ray's end (INFINITY toward a light at infinity; the test is t < tmax). */
inline float4 shadow_origin_pack(float3 origin, float tmax) { return (float4)(origin, tmax); }
inline float shadow_origin_tmax(float4 origin) { return origin.w; }

/* bounce: the bounce that queued the shadow ray, whose DIM_SHADOW_OPACITY stream decides the
 * cut-out pass-throughs along it (intersect_shadow.cl), below 2^16 (max_depth plus
 * MEDIUM_CROSSING_LIMIT); medium: the slot of the medium the ray starts in (0: none). */
inline float4 shadow_direction_pack(float3 direction, uint bounce, uint medium)
{
    return (float4)(direction, as_float(bounce | medium << 16));
}
inline uint shadow_direction_bounce(float4 direction) { return as_uint(direction.w) & 0xffffu; }
inline uint shadow_direction_medium(float4 direction) { return as_uint(direction.w) >> 16; }

/* waits: a shadow ray is queued and its contribution not yet resolved. Between a path's bounces no
 * slot waits: the pool starts zeroed (wavefront_state.c), and whatever queues a shadow ray resolves
 * it before the slot is shaded again or refilled (intersect_shadow after shade_surface in every
 * step, and the megakernels' connect after each shade), resetting waits; so only queuing writes
 * this lane, and shading a vertex that queues nothing, or starting a path, leaves it alone. */
inline float4 shadow_contribution_pack(float3 contribution, bool waits)
{
    return (float4)(contribution, waits ? 1.0f : 0.0f);
}
inline bool shadow_contribution_waits(float4 contribution) { return contribution.w != 0.0f; }
#endif

/* Wavefront counters (one uint buffer). */
#define COUNTER_NONFINITE 0   /* samples whose radiance was NaN or Inf (dropped) */
#define COUNTER_SHADOW_RAYS 1 /* shadow rays traced in the current window */
#define COUNTER_EXTENSION_RAYS 2 /* closest-hit rays traced in the current window */
#define COUNTER_COUNT 4

/* The paths of one trace_paths_packets work item (cl/stages/megakernel.cl), whose rays are traced
 * as one packet: host/render/megakernel.c launches a work item per PACKET_RAYS samples. */
#define PACKET_RAYS 8

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

/* The film's second moments (RenderSettings.moments; a buffer of its own, so that the plain film
 * and its accumulation are untouched without them): per pixel and channel the exact sum of the
 * squares of the film's fixed-point samples x (the integers accumulate_film adds, x <= 2^44), as a
 * 128-bit integer in a ulong2 (x: low word, y: high word), MOMENT_WORDS words per pixel. A square
 * is at most 2^88, so the sum cannot wrap before 2^40 samples of the largest radiance (it
 * saturates beyond); like the film it is integer addition, the same bits in any order. The
 * variance of the mean follows exactly from these and the film's sums (film_variance.cl). */
#define MOMENT_WORDS 6

#endif
