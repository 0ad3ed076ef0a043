// SPDX-License-Identifier: MIT
/* environment.c: reading the environment map and building its sampling distribution (a marginal
 * CDF over the rows and a conditional one per row, in 32-bit fixed point). */
#include "scene/environment.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <stb_image.h>

#include "base/fs.h"
#include "base/parallel_for.h"
#include "io/image_checks.h"
#include "io/image_io.h"
#include "io/input_file.h"

/* 8192 x 4096 is the largest map the issue asks for; twice that in texels is still refused before
 * decoding anything. */
#define ENVIRONMENT_MAX_TEXELS ((uint64_t)1 << 26)

static float luminance(const float4 *c) { return 0.2126f * c->s[0] + 0.7152f * c->s[1] + 0.0722f * c->s[2]; }

/* The passes over the texels run in parallel by rows (base/parallel_for.h): each row writes only
 * its own texels and per-row sums, which are added in row order afterwards, so the tables are the
 * same bits on any number of cores. */
#define ROWS_PER_THREAD 16
#define CDF_ONE 4294967296.0 /* 2^32: the fixed point's 1 */

typedef struct {
    const float *rgb;       /* the decoded image, 3 floats per texel */
    float4 *texels;
    uint32_t *cdf;          /* Environment.cdf: h row entries, then w per row; then the guides */
    float *weight;          /* per texel: the 3 x 3 maximum (scratch) */
    size_t w, h;
    float scale;
    double *row_sum;        /* per row: luminance sum (convert) or weight sum (weights) */
    size_t *row_clamped;    /* per row: texel values clamped to 0 */
    double mean_weight;     /* compensate_rows: the weights' mean over the sphere */
} EnvPass;

/* texels = clamp(rgb) x scale, w = luminance. */
static void convert_rows(void *ctx, size_t begin, size_t end)
{
    EnvPass *e = ctx;
    for (size_t j = begin; j < end; j++) {
        double row = 0.0;
        size_t clamped = 0;
        for (size_t i = 0; i < e->w; i++) {
            float4 *t = &e->texels[j * e->w + i];
            for (int c = 0; c < 3; c++) {
                float v = e->rgb[3 * (j * e->w + i) + c];
                if (!(v >= 0.0f) || !isfinite(v))
                    clamped++, v = 0.0f;
                t->s[c] = v * e->scale;
            }
            t->s[3] = luminance(t);
            row += t->s[3];
        }
        e->row_sum[j] = row, e->row_clamped[j] = clamped;
    }
}

/* A texel's sampling weight starts as the largest luminance of the 3 x 3 texels around it
 * (wrapping in u, clamped in v): bilinear filtering inside a texel's cell reads only those texels,
 * so it is > 0 wherever the displayed radiance is (see cl/light/light_env.cl); compensate_rows
 * then takes the mean off, and build_tables multiplies by sin(theta of the row centre). This pass
 * puts the 3 x 3 maximum in weight[] and each row's sum of them in row_sum. */
static void weight_rows(void *ctx, size_t begin, size_t end)
{
    EnvPass *e = ctx;
    size_t w = e->w;
    for (size_t j = begin; j < end; j++) {
        const float4 *rows[3] = {e->texels + (j > 0 ? j - 1 : j) * w, e->texels + j * w,
                                 e->texels + (j + 1 < e->h ? j + 1 : j) * w};
        double row = 0.0;
        for (size_t i = 0; i < w; i++) {
            size_t left = i == 0 ? w - 1 : i - 1, right = i + 1 == w ? 0 : i + 1;
            float m = 0.0f;
            for (int r = 0; r < 3; r++)
                m = fmaxf(m, fmaxf(fmaxf(rows[r][left].s[3], rows[r][i].s[3]), rows[r][right].s[3]));
            e->weight[j * w + i] = m;
            row += (double)m;
        }
        e->row_sum[j] = row;
    }
}

/* MIS compensation (Karlik, Sik, Vevoda, Skrivan and Krivanek 2019, "MIS compensation: optimizing
 * sampling techniques in multiple importance sampling"; pbrt-v4's image light): next-event
 * estimation draws texels in proportion to how far their weight rises above the map's mean, not to
 * the weight itself. Every escaped BSDF ray is weighed against light sampling by MIS, and the BSDF
 * already samples the even part of the sky well, so light samples spent there were wasted: they go
 * to the sun and the bright windows instead. A texel at or below the mean gets weight 0 (its
 * directions reach NEE + MIS through the BSDF's samples alone, whose MIS weight is then 1, so the
 * sum stays unbiased: every strategy's pdf is the density it draws from). The mean is over the
 * sphere (each texel's weight x sin theta of its row, as its solid angle). A map whose weights are
 * all equal keeps them: nothing rises above its mean. */
static void compensate_rows(void *ctx, size_t begin, size_t end)
{
    EnvPass *e = ctx;
    for (size_t j = begin; j < end; j++) {
        double row = 0.0;
        for (size_t i = 0; i < e->w; i++) {
            float *wt = &e->weight[j * e->w + i];
            double above = (double)*wt - e->mean_weight; /* in double: a float mean could round up */
            *wt = above > 0.0 ? (float)above : 0.0f;
            row += (double)*wt;
        }
        e->row_sum[j] = row;
    }
}

/* The mean over the sphere of the texels' weights (before the rows' sin theta): their sum per row
 * (row_sum) x sin theta of the row, over W x the sum of the rows' sin theta. */
static double mean_weight(const EnvPass *e)
{
    const double pi = 3.14159265358979323846;
    double sum = 0.0, area = 0.0;
    for (size_t j = 0; j < e->h; j++) {
        double s = sin(pi * ((double)j + 0.5) / (double)e->h);
        sum += e->row_sum[j] * s;
        area += (double)e->w * s;
    }
    return sum / area;
}

/* Fixed point of the cumulative sum `below` of a total `total`: round(2^32 below / total), at most
 * 2^32 - 1 (the end of the last interval, 2^32, is implied). Monotone in `below`, so the
 * intervals never overlap; an interval of width 0 is never drawn. Zero-weight entries at the end
 * (a black ground's last rows, a row's last black texels) are the exception: the clamp leaves the
 * last of them [2^32 - 1, 2^32), drawn once in 2^32, with its pdf from the same integers and a
 * radiance of 0, so nothing is biased. */
static uint32_t fixed_cdf(double below, double total)
{
    double f = floor(below / total * CDF_ONE + 0.5);
    return f >= CDF_ONE - 1.0 ? UINT32_MAX : (uint32_t)f;
}

/* The width of interval k of a fixed-point CDF of n entries (the last one ends at 2^32). */
static double cdf_width(const uint32_t *cdf, size_t n, size_t k)
{
    return (k + 1 < n ? (double)cdf[k + 1] : CDF_ONE) - (double)cdf[k];
}

/* Each row's conditional CDF over its texels' weights (a row of weight 0 gets all zeros: its
 * marginal interval has width 0, it is never drawn). */
static void conditional_rows(void *ctx, size_t begin, size_t end)
{
    EnvPass *e = ctx;
    for (size_t j = begin; j < end; j++) {
        uint32_t *row = e->cdf + e->h + j * e->w;
        const float *wt = e->weight + j * e->w;
        double below = 0.0;
        for (size_t i = 0; i < e->w; i++) {
            row[i] = e->row_sum[j] > 0.0 ? fixed_cdf(below, e->row_sum[j]) : 0u;
            below += (double)wt[i];
        }
    }
}

/* The guide of a fixed-point CDF of n entries: guide[b] is the interval that holds the start of
 * bucket b of n equal buckets of the 32-bit range (the bucket is mul_hi(x, n), its start
 * ceil(b 2^32 / n)), so an x of bucket b lies in an interval from guide[b] to guide[b + 1]: the
 * kernel's search (cdf_invert) takes one or two steps instead of log2 n. */
static void build_guide(const uint32_t *cdf, uint32_t *guide, size_t n)
{
    size_t k = 0;
    for (size_t b = 0; b < n; b++) {
        uint64_t start = (((uint64_t)b << 32) + n - 1) / n;
        while (k + 1 < n && cdf[k + 1] <= start)
            k++;
        guide[b] = (uint32_t)k;
    }
}

/* Per row, once both CDFs are written: texels[].w = W x H x the probability env_sample draws the
 * texel with (the product of its row's and its own interval widths / 2^64, from the stored
 * integers, so the pdf of the MIS weights is exactly the density of the samples), and the row's
 * guide. */
static void finish_rows(void *ctx, size_t begin, size_t end)
{
    EnvPass *e = ctx;
    double n = (double)e->w * (double)e->h;
    for (size_t j = begin; j < end; j++) {
        double row = cdf_width(e->cdf, e->h, j) / CDF_ONE;
        const uint32_t *cond = e->cdf + e->h + j * e->w;
        for (size_t i = 0; i < e->w; i++)
            e->texels[j * e->w + i].s[3] = (float)(n * row * (cdf_width(cond, e->w, i) / CDF_ONE));
        build_guide(cond, e->cdf + 2 * e->h + e->w * e->h + j * e->w, e->w);
    }
}

/* The sampling tables: each texel's weight (its 3 x 3 maximum less their mean, x sin theta of its
 * row), the marginal CDF of the rows' weights, each row's conditional CDF, and texels[].w, the pdf
 * per unit uv area. Inverting two CDFs (not an alias table, which pt used before) keeps a
 * stratified (u1, u2) stratified over the map: the low-discrepancy sampler's points stay spread
 * over the texels.
 * Returns the total weight (0: the map is black). e->row_sum: h doubles of scratch. */
static double build_tables(EnvPass *e)
{
    const double pi = 3.14159265358979323846;
    size_t h = e->h;
    parallel_for(h, ROWS_PER_THREAD, weight_rows, e);
    e->mean_weight = mean_weight(e);
    parallel_for(h, ROWS_PER_THREAD, compensate_rows, e);
    double compensated = 0.0;
    for (size_t j = 0; j < h; j++)
        compensated += e->row_sum[j];
    if (!(compensated > 0.0))
        parallel_for(h, ROWS_PER_THREAD, weight_rows, e); /* every weight equal: keep them */
    parallel_for(h, ROWS_PER_THREAD, conditional_rows, e);
    double total = 0.0; /* row_sum becomes each row's weight: x sin theta of its centre */
    for (size_t j = 0; j < h; j++)
        total += e->row_sum[j] *= sin(pi * ((double)j + 0.5) / (double)h);
    if (!(total > 0.0) || !isfinite(total))
        return 0.0;
    double below = 0.0;
    for (size_t j = 0; j < h; j++) {
        e->cdf[j] = fixed_cdf(below, total);
        below += e->row_sum[j];
    }
    build_guide(e->cdf, e->cdf + h + e->w * h, h);
    parallel_for(h, ROWS_PER_THREAD, finish_rows, e);
    return total;
}

bool environment_build(Environment *env, const float *rgb, int width, int height, float scale,
                       float rotation_degrees, const char *name, Error *err)
{
    memset(env, 0, sizeof *env);
    if (!(scale >= 0.0f) || !isfinite(scale)) {
        error_set(err, ERR_JSON_VALUE, name, 0, "%s: environment scale %g must be >= 0", name, scale);
        return false;
    }
    if (width <= 0 || height <= 0 || (uint64_t)width * (uint64_t)height > ENVIRONMENT_MAX_TEXELS) {
        error_set(err, ERR_TOO_LARGE, name, 0, "%s: environment map size %dx%d is not in 1..2^26 texels",
                  name, width, height);
        return false;
    }
    size_t w = (size_t)width, h = (size_t)height, n = w * h;
    env->texels = malloc(n * sizeof *env->texels);
    env->cdf = malloc(2 * (h + n) * sizeof *env->cdf); /* environment_cdf_count */
    float *weight = malloc(n * sizeof *weight);
    double *row_sum = malloc(h * sizeof *row_sum);
    size_t *row_clamped = malloc(h * sizeof *row_clamped);
    if (!env->texels || !env->cdf || !weight || !row_sum || !row_clamped) {
        free(weight), free(row_sum), free(row_clamped);
        environment_free(env);
        error_set(err, ERR_TOO_LARGE, name, 0, "%s: out of memory for a %dx%d environment map", name,
                  width, height);
        return false;
    }
    const double pi = 3.14159265358979323846;
    EnvPass pass = {.rgb = rgb, .texels = env->texels, .cdf = env->cdf, .weight = weight, .w = w,
                    .h = h, .scale = scale, .row_sum = row_sum, .row_clamped = row_clamped};
    parallel_for(h, ROWS_PER_THREAD, convert_rows, &pass);
    size_t clamped = 0;
    double solid_angle_sum = 0.0;
    for (size_t j = 0; j < h; j++) {
        double row_solid_angle = 2.0 * pi / (double)w *
                                 (cos(pi * (double)j / (double)h) - cos(pi * (double)(j + 1) / (double)h));
        solid_angle_sum += row_sum[j] * row_solid_angle;
        clamped += row_clamped[j];
    }
    if (clamped)
        warn("%s: %zu negative or non-finite texel values clamped to 0", name, clamped);
    double total = build_tables(&pass);
    free(weight), free(row_sum), free(row_clamped);
    if (!(total > 0.0)) {
        environment_free(env);
        error_set(err, ERR_TEXTURE, name, 0,
                  "%s: the environment map has zero total power (every texel black): it cannot light",
                  name);
        return false;
    }
    env->width = (uint32_t)width;
    env->height = (uint32_t)height;
    env->rotation = (float)(fmod((double)rotation_degrees, 360.0) / 360.0);
    env->mean_luminance = solid_angle_sum / (4.0 * pi);
    return true;
}

/* A Radiance .hdr through stb_image (float rgb, row 0 at the top). */
static bool read_hdr(const char *path, float **rgb, int *width, int *height, Error *err)
{
    char *file = NULL;
    size_t size = 0;
    if (!input_file_read(path, "an environment map", INPUT_LIMIT_TEXTURE, &file, &size, err))
        return false;
    const stbi_uc *bytes = (const stbi_uc *)file;
    int length = size > INT_MAX ? INT_MAX : (int)size, channels = 0;
    const char *problem = NULL;
    *rgb = NULL;
    if (!stbi_is_hdr_from_memory(bytes, length) ||
        !stbi_info_from_memory(bytes, length, width, height, &channels)) {
        error_set(err, ERR_TEXTURE, path, 0, "%s: not a Radiance HDR image", path);
    } else if (*width <= 0 || *height <= 0 ||
               (uint64_t)*width * (uint64_t)*height > ENVIRONMENT_MAX_TEXELS) {
        error_set(err, ERR_TOO_LARGE, path, 0, "%s: declared size %dx%d is over the limit of 2^26 texels",
                  path, *width, *height);
    } else if ((problem = image_check_hdr(bytes, size, *width, *height))) {
        error_set(err, ERR_TEXTURE, path, 0, "%s: corrupt HDR image: %s", path, problem);
    } else if (!(*rgb = stbi_loadf_from_memory(bytes, length, width, height, &channels, 3))) {
        error_set(err, ERR_TEXTURE, path, 0, "%s: cannot decode HDR image: %s", path,
                  stbi_failure_reason());
    }
    free(file);
    return *rgb != NULL;
}

bool environment_load(Environment *env, const char *path, float scale, float rotation_degrees,
                      Error *err)
{
    memset(env, 0, sizeof *env);
    float *rgb = NULL;
    int width = 0, height = 0;
    bool ok;
    if (fs_has_suffix(path, ".exr") || fs_has_suffix(path, ".EXR")) {
        ok = image_read_exr(path, &rgb, &width, &height, err);
    } else if (fs_has_suffix(path, ".hdr") || fs_has_suffix(path, ".HDR")) {
        ok = read_hdr(path, &rgb, &width, &height, err);
    } else {
        error_set(err, ERR_TEXTURE, path, 0,
                  "%s: unknown environment map type (expected .hdr or .exr)", path);
        return false;
    }
    ok = ok && environment_build(env, rgb, width, height, scale, rotation_degrees, path, err);
    free(rgb); /* stbi_image_free is free() here: stb uses the default allocator */
    return ok;
}

void environment_free(Environment *env)
{
    free(env->texels);
    free(env->cdf);
    memset(env, 0, sizeof *env);
}
