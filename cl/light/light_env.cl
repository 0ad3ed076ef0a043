/* SPDX-License-Identifier: MIT */
/* light_env.cl: the environment map (host/scene/environment.h): what an escaped ray sees and its
 * importance sampling. Mapping (shared/DESIGN.md "Environment"): direction d, +y up,
 * u = 0.5 + (atan2(d.x, -d.z) + theta) / 2 pi, v = acos(d.y) / pi, v = 0 the image's top row; texel
 * (i, j) covers [i/W, (i+1)/W) x [j/H, (j+1)/H) and its value sits at its centre.
 *
 * Radiance is the bilinear interpolation of the four texel centres around the direction (wrapping
 * in u, clamped in v), everywhere: escaped rays and next-event estimation see the same function.
 * Sampling is piecewise constant per texel cell (a row by inverting the rows' CDF with u2, a texel
 * by inverting its row's CDF with u1, then a point in the cell from what is left of u1 and u2: a
 * monotone map, so a stratified (u1, u2) stays stratified over the map, which an alias table does
 * not do), with each texel's weight how far the largest luminance of the 3 x 3 texels around it
 * (the only texels bilinear filtering reads inside its cell) rises above that maximum's mean over
 * the sphere, x sin(theta of its row) (MIS compensation, host/scene/environment.c): the density is
 * > 0 wherever the bilinear radiance rises above the mean (except at the two poles, a set of
 * measure zero); below it the BSDF's samples alone carry the light, with MIS weight 1. env_pdf_w
 * is exactly the density env_sample draws from, so NEE divides by the true pdf of its samples and
 * the MIS weights of both strategies sum to 1 for every direction: NEE + MIS and BSDF-only
 * sampling are both unbiased for the bilinear radiance (NEE alone would not be; pt never uses it
 * alone). */

typedef struct {
    const global float4 *texels;      /* rgb radiance, w: pdf per unit uv area */
    const global uint *cdf;           /* the CDFs, then their guides (environment.h) */
    uint width, height;
    float rotation;                   /* theta as a fraction of a turn */
} EnvMap;

inline EnvMap env_map(constant RenderParams *p, const SceneView *scene)
{
    EnvMap env = {scene->env_texels, scene->env_cdf, p->scene.env_width, p->scene.env_height,
                  p->scene.env_rotation};
    return env;
}

/* Map coordinates (u, v) in [0, 1) of direction d (unit length). */
inline float2 env_uv(const EnvMap *env, float3 d)
{
    float u = 0.5f + atan2(d.x, -d.z) * (0.5f * M_1_PI_F) + env->rotation;
    u -= floor(u);
    return (float2)(u, acos(clamp(d.y, -1.0f, 1.0f)) * M_1_PI_F);
}

/* The index of the texel whose cell holds (u, v). */
inline uint env_texel_at(const EnvMap *env, float2 uv)
{
    uint i = min((uint)(uv.x * (float)env->width), env->width - 1u);
    uint j = min((uint)(uv.y * (float)env->height), env->height - 1u);
    return j * env->width + i;
}

/* The texel index of direction d (unit length). */
inline uint env_texel_of(const EnvMap *env, float3 d) { return env_texel_at(env, env_uv(env, d)); }

/* Solid-angle pdf of direction d from the texel's uv pdf: the map covers 2 pi x pi radians, and a
 * uv cell at polar angle t spans sin(t) of its area in solid angle. */
inline float env_pdf_w(float pdf_uv, float sin_theta)
{
    return sin_theta > 0.0f ? pdf_uv / (2.0f * M_PI_F * M_PI_F * sin_theta) : 0.0f;
}

/* Bilinear radiance at map coordinates (u, v) in [0, 1): texel centres at ((i + 0.5) / W,
 * (j + 0.5) / H), wrapping across u = 0 and clamped at the poles' rows. */
inline float3 env_bilinear(const EnvMap *env, float u, float v)
{
    float x = u * (float)env->width - 0.5f, y = v * (float)env->height - 0.5f;
    float fx0 = floor(x), fy0 = floor(y);
    float fx = x - fx0, fy = y - fy0;
    int w = (int)env->width, h = (int)env->height;
    int i0 = (int)fx0, j0 = (int)fy0;
    int i1 = i0 + 1 >= w ? i0 + 1 - w : i0 + 1;
    i0 = i0 < 0 ? i0 + w : i0;
    int j1 = min(j0 + 1, h - 1);
    j0 = max(j0, 0);
    const global float4 *t = env->texels;
    float3 top = (1.0f - fx) * xyz(t[j0 * w + i0]) + fx * xyz(t[j0 * w + i1]);
    float3 bottom = (1.0f - fx) * xyz(t[j1 * w + i0]) + fx * xyz(t[j1 * w + i1]);
    return (1.0f - fy) * top + fy * bottom;
}

/* Radiance seen along d (bilinear); *pdf_w: env_sample's solid-angle density of d. */
inline float3 env_lookup(const EnvMap *env, float3 d, float *pdf_w)
{
    float2 uv = env_uv(env, d);
    float sin_theta = sqrt(fmax(0.0f, 1.0f - d.y * d.y));
    *pdf_w = env_pdf_w(env->texels[env_texel_at(env, uv)].w, sin_theta);
    return env_bilinear(env, uv.x, uv.y);
}

typedef struct {
    float3 direction;
    float3 radiance;
    float pdf_w;
} EnvSample;

/* The interval of a 32-bit fixed-point CDF of n entries (cdf[0] = 0, the end 2^32 implied) that
 * holds x: the largest k with cdf[k] <= x (so cdf[k] <= x < its end: an interval of width 0 is
 * never found), searched between the guide's entries for x's bucket (environment.c build_guide):
 * one or two steps on average, up to log2 of the bucket's entries where many narrow intervals
 * share it (a sun on a dim sky); *rest gets where x lies in the interval, in [0, 1). */
inline uint cdf_invert(const global uint *cdf, const global uint *guide, uint n, uint x, float *rest)
{
    uint b = mul_hi(x, n);
    uint lo = guide[b], hi = b + 1u < n ? guide[b + 1u] + 1u : n; /* cdf[lo] <= x < cdf[hi] */
    while (hi - lo > 1u) {
        uint mid = (lo + hi) >> 1;
        if (cdf[mid] <= x)
            lo = mid;
        else
            hi = mid;
    }
    ulong end = lo + 1u < n ? (ulong)cdf[lo + 1u] : 4294967296ul;
    *rest = fmin((float)(x - cdf[lo]) / (float)(end - (ulong)cdf[lo]), 0x1.fffffep-1f);
    return lo;
}

/* A direction in proportion to each texel's weight (how far the 3 x 3 neighbourhood's largest
 * luminance rises above its mean, x sin(theta) of the row): the row from the rows' CDF by the 32
 * bits v_bits, the texel from that row's CDF by u_bits, the point in its uv cell from what is
 * left of each (texels[].w is the probability of each texel x W x H, from the same integers). */
inline EnvSample env_sample(const EnvMap *env, uint u_bits, uint v_bits)
{
    float u1, u2;
    const global uint *guide = env->cdf + env->height + env->width * env->height;
    uint j = cdf_invert(env->cdf, guide, env->height, v_bits, &u2);
    uint i = cdf_invert(env->cdf + env->height + j * env->width, guide + env->height + j * env->width,
                        env->width, u_bits, &u1);
    float u = ((float)i + u1) / (float)env->width, v = ((float)j + u2) / (float)env->height;
    /* phi = 2 pi (u - 1/2 - rotation), theta = pi v. */
    float2 phi = cos_sin_turns(u - 0.5f - env->rotation), theta = cos_sin_turns(0.5f * v);
    EnvSample s;
    s.direction = (float3)(theta.y * phi.y, theta.x, -theta.y * phi.x);
    /* Radiance and pdf as an escaped ray in this direction sees them: a direction on a texel edge
     * may round into the neighbour, and both strategies must weigh the same function. */
    s.radiance = env_lookup(env, s.direction, &s.pdf_w);
    return s;
}
