// SPDX-License-Identifier: MIT
/* environment.c: reading the environment map and building its sampling distribution. */
#include "scene/environment.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <stb_image.h>

#include "base/fs.h"
#include "io/image_checks.h"
#include "io/image_io.h"
#include "io/input_file.h"

/* 8192 x 4096 is the largest map the issue asks for; twice that in texels is still refused before
 * decoding anything. */
#define ENVIRONMENT_MAX_TEXELS ((uint64_t)1 << 26)

static float luminance(const float4 *c) { return 0.2126f * c->s[0] + 0.7152f * c->s[1] + 0.0722f * c->s[2]; }

/* out[i] = the largest of lum[i - 1], lum[i], lum[i + 1], wrapping around the row (u = 0 meets
 * u = 1). lum is the row's texels; their w holds the luminance while the tables are built. */
static void row_max3(const float4 *row, size_t w, float *out)
{
    for (size_t i = 0; i < w; i++) {
        float left = row[i == 0 ? w - 1 : i - 1].s[3], right = row[i + 1 == w ? 0 : i + 1].s[3];
        out[i] = fmaxf(fmaxf(left, row[i].s[3]), right);
    }
}

/* The sampling tables. A texel's weight is the largest luminance of the 3 x 3 texels around it
 * (wrapping in u, clamped in v) x sin(theta of its row centre): bilinear filtering inside a texel's
 * cell reads only those texels, so the weight is > 0 wherever the displayed radiance is (see
 * cl/light/light_env.cl). Weights accumulate in double so zero texels stay zero-width. texels[].w
 * holds the luminance on entry and the pdf per unit uv area on return: the product of the float
 * CDF steps of the texel's row and column, exactly the density env_sample draws from. Returns the
 * total weight (0: the map is black). rows: 3 * w scratch floats, row_weight: h doubles. */
static double build_tables(Environment *env, size_t w, size_t h, float *rows, double *row_weight)
{
    const double pi = 3.14159265358979323846;
    float *above = rows, *here = rows + w, *below = rows + 2 * w;
    row_max3(env->texels, w, here);
    memcpy(above, here, w * sizeof *here);
    double total = 0.0;
    env->marginal[0] = 0.0f;
    for (size_t j = 0; j < h; j++) {
        if (j + 1 < h)
            row_max3(env->texels + (j + 1) * w, w, below);
        else
            memcpy(below, here, w * sizeof *here);
        double sin_c = sin(pi * ((double)j + 0.5) / (double)h), row = 0.0;
        float *cdf = env->conditional + j * (w + 1);
        cdf[0] = 0.0f;
        for (size_t i = 0; i < w; i++) {
            row += (double)fmaxf(fmaxf(above[i], here[i]), below[i]);
            cdf[i + 1] = (float)row;
        }
        for (size_t i = 1; i <= w; i++)
            cdf[i] = row > 0.0 ? (float)((double)cdf[i] / row) : (float)i / (float)w;
        cdf[w] = 1.0f;
        row_weight[j] = row * sin_c;
        total += row_weight[j];
        float *spare = above; /* roll: this row is the next one's row above */
        above = here, here = below, below = spare;
    }
    if (!(total > 0.0) || !isfinite(total))
        return 0.0;
    double running = 0.0;
    for (size_t j = 0; j < h; j++) {
        running += row_weight[j];
        env->marginal[j + 1] = (float)(running / total);
    }
    env->marginal[h] = 1.0f;
    double cells = (double)w * (double)h;
    for (size_t j = 0; j < h; j++) {
        double row_p = (double)env->marginal[j + 1] - (double)env->marginal[j];
        const float *cdf = env->conditional + j * (w + 1);
        for (size_t i = 0; i < w; i++)
            env->texels[j * w + i].s[3] = (float)(row_p * ((double)cdf[i + 1] - (double)cdf[i]) * cells);
    }
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
    env->marginal = malloc((h + 1) * sizeof *env->marginal);
    env->conditional = malloc(h * (w + 1) * sizeof *env->conditional);
    float *rows = malloc(3 * w * sizeof *rows);
    double *row_weight = malloc(h * sizeof *row_weight);
    if (!env->texels || !env->marginal || !env->conditional || !rows || !row_weight) {
        free(rows), free(row_weight);
        environment_free(env);
        error_set(err, ERR_TOO_LARGE, name, 0, "%s: out of memory for a %dx%d environment map", name,
                  width, height);
        return false;
    }
    const double pi = 3.14159265358979323846;
    size_t clamped = 0;
    double solid_angle_sum = 0.0;
    for (size_t j = 0; j < h; j++) {
        double row_solid_angle = 2.0 * pi / (double)w *
                                 (cos(pi * (double)j / (double)h) - cos(pi * (double)(j + 1) / (double)h));
        double row = 0.0;
        for (size_t i = 0; i < w; i++) {
            float4 *t = &env->texels[j * w + i];
            for (int c = 0; c < 3; c++) {
                float v = rgb[3 * (j * w + i) + c];
                if (!(v >= 0.0f) || !isfinite(v))
                    clamped++, v = 0.0f;
                t->s[c] = v * scale;
            }
            t->s[3] = luminance(t);
            row += t->s[3];
        }
        solid_angle_sum += row * row_solid_angle;
    }
    if (clamped)
        warn("%s: %zu negative or non-finite texel values clamped to 0", name, clamped);
    double total = build_tables(env, w, h, rows, row_weight);
    free(rows), free(row_weight);
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
    free(env->marginal);
    free(env->conditional);
    memset(env, 0, sizeof *env);
}
