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

static double luminance(const float4 *c) { return 0.2126 * c->s[0] + 0.7152 * c->s[1] + 0.0722 * c->s[2]; }

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
    double *row_weight = malloc(h * sizeof *row_weight);
    if (!env->texels || !env->marginal || !env->conditional || !row_weight) {
        free(row_weight);
        environment_free(env);
        error_set(err, ERR_TOO_LARGE, name, 0, "%s: out of memory for a %dx%d environment map", name,
                  width, height);
        return false;
    }
    const double pi = 3.14159265358979323846;
    size_t clamped = 0;
    double total = 0.0, solid_angle_sum = 0.0;
    for (size_t j = 0; j < h; j++) {
        /* Texels are weighted by sin(theta) of their row centre: a row's cells shrink toward the
         * poles. The conditional CDF accumulates in double so zero texels stay zero-width. */
        double sin_c = sin(pi * ((double)j + 0.5) / (double)h);
        double row_solid_angle = 2.0 * pi / (double)w *
                                 (cos(pi * (double)j / (double)h) - cos(pi * (double)(j + 1) / (double)h));
        double row = 0.0;
        float *cdf = env->conditional + j * (w + 1);
        cdf[0] = 0.0f;
        for (size_t i = 0; i < w; i++) {
            float4 *t = &env->texels[j * w + i];
            for (int c = 0; c < 3; c++) {
                float v = rgb[3 * (j * w + i) + c];
                if (!(v >= 0.0f) || !isfinite(v))
                    clamped++, v = 0.0f;
                t->s[c] = v * scale;
            }
            double lum = luminance(t);
            t->s[3] = (float)(lum * sin_c); /* the weight for now; the pdf below */
            row += lum * sin_c;
            solid_angle_sum += lum * row_solid_angle;
            cdf[i + 1] = (float)row;
        }
        for (size_t i = 1; i <= w; i++)
            cdf[i] = row > 0.0 ? (float)((double)cdf[i] / row) : (float)i / (float)w;
        cdf[w] = 1.0f;
        row_weight[j] = row;
        total += row;
    }
    if (clamped)
        warn("%s: %zu negative or non-finite texel values clamped to 0", name, clamped);
    if (!(total > 0.0) || !isfinite(total)) {
        free(row_weight);
        environment_free(env);
        error_set(err, ERR_TEXTURE, name, 0,
                  "%s: the environment map has zero total power (every texel black): it cannot light",
                  name);
        return false;
    }
    double running = 0.0;
    env->marginal[0] = 0.0f;
    for (size_t j = 0; j < h; j++) {
        running += row_weight[j];
        env->marginal[j + 1] = (float)(running / total);
    }
    env->marginal[h] = 1.0f;
    /* pdf per unit (u, v) area: weight / mean weight. */
    double to_pdf = (double)n / total;
    for (size_t k = 0; k < n; k++)
        env->texels[k].s[3] = (float)(env->texels[k].s[3] * to_pdf);
    free(row_weight);
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
