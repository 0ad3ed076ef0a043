/* SPDX-License-Identifier: MIT */
/* environment_maps.h: what the environment tests (tests/test_environment*.c) share: maps generated
 * in memory (axis colours, a high-contrast sky, one bright texel), scene files around them, and the
 * device buffers env_test.cl's kernels read. Header-only, like procedural_mesh.h. */
#ifndef PT_TEST_ENVIRONMENT_MAPS_H
#define PT_TEST_ENVIRONMENT_MAPS_H

#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "procedural_mesh.h"
#include "scene/environment.h"
#include "support.h"

#define ENV_PI 3.14159265358979323846

/* DESIGN's mapping inverted with rotation 0: the direction at the centre of texel (i, j), row 0 at
 * the top. */
static inline void texel_direction(int i, int j, int w, int h, double d[3])
{
    double phi = 2.0 * ENV_PI * ((i + 0.5) / w - 0.5), theta = ENV_PI * (j + 0.5) / h;
    d[0] = sin(theta) * sin(phi), d[1] = cos(theta), d[2] = -sin(theta) * cos(phi);
}

/* Six colours, one per axis: -z red, +x green, -x blue, +z yellow, +y white, -y magenta. */
static const double axes[6][3] = {{0, 0, -1}, {1, 0, 0}, {-1, 0, 0}, {0, 0, 1}, {0, 1, 0}, {0, -1, 0}};
static const float axis_colours[6][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 0}, {1, 1, 1}, {1, 0, 1}};

/* Each texel gets the colour of the axis nearest its centre direction. */
static inline float *axis_map(int w, int h)
{
    float *rgb = malloc((size_t)w * h * 3 * sizeof *rgb);
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++) {
            double d[3];
            texel_direction(i, j, w, h, d);
            int best = 0;
            for (int a = 1; a < 6; a++)
                if (d[0] * axes[a][0] + d[1] * axes[a][1] + d[2] * axes[a][2] >
                    d[0] * axes[best][0] + d[1] * axes[best][1] + d[2] * axes[best][2])
                    best = a;
            memcpy(&rgb[3 * (j * w + i)], axis_colours[best], sizeof axis_colours[best]);
        }
    return rgb;
}

/* A high-contrast map: a bright sun, a black band, a noisy sky. */
static inline float *contrast_map(int w, int h)
{
    float *rgb = malloc((size_t)w * h * 3 * sizeof *rgb);
    uint64_t state = 7;
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++) {
            float *t = &rgb[3 * (j * w + i)];
            float base = j < h / 2 ? 0.3f + mesh_rng_float(&state) : 0.05f;
            t[0] = base, t[1] = 0.8f * base, t[2] = 1.2f * base;
            if (j == h / 2 + 2) /* a black row */
                t[0] = t[1] = t[2] = 0.0f;
            if (i >= w / 8 && i < w / 8 + 2 && j >= h / 4 && j < h / 4 + 2)
                t[0] = 200.0f, t[1] = 180.0f, t[2] = 150.0f;
        }
    return rgb;
}

/* Black but for one bright texel at (bi, bj): bilinear filtering spreads it over the cells around
 * it, which the sampler must cover. */
static inline float *one_texel_map(int w, int h, int bi, int bj)
{
    float *rgb = calloc((size_t)w * h * 3, sizeof *rgb);
    float *t = &rgb[3 * (bj * w + bi)];
    t[0] = 50.0f, t[1] = 40.0f, t[2] = 30.0f;
    return rgb;
}

/* scene.json with the given objects and environment (file, rotation). */
static inline const char *write_scene(const char *dir, const char *name, const char *objects,
                                      const char *env_file, float rotation, const char *camera)
{
    char text[8192];
    snprintf(text, sizeof text,
             "{\"camera\": %s, \"objects\": %s,\n"
             " \"environment\": {\"file\": \"%s\", \"scale\": 1, \"rotation\": %g}}\n",
             camera, objects, env_file, rotation);
    return test_write_file(dir, name, text);
}

/* An icosphere of radius 1 at the origin with material "ball", and optionally a floor at y = -1
 * with material "floor". */
static inline void write_ball_obj(const char *dir, bool floor)
{
    test_write_file(dir, "ball.mtl", "newmtl ball\nKd 0.8 0.8 0.8\nnewmtl floor\nKd 0.5 0.5 0.5\n");
    char path[512];
    snprintf(path, sizeof path, "%s/ball.obj", dir);
    FILE *f = fopen(path, "w");
    cr_assert(f);
    TestMesh m = mesh_icosphere(3);
    fprintf(f, "mtllib ball.mtl\nusemtl ball\n");
    for (uint32_t v = 0; v < m.num_positions; v++)
        fprintf(f, "v %.7f %.7f %.7f\n", m.positions[v].s[0], m.positions[v].s[1], m.positions[v].s[2]);
    for (uint32_t t = 0; t < m.num_triangles; t++)
        fprintf(f, "f %u %u %u\n", m.triangles[t].v.s[0] + 1, m.triangles[t].v.s[1] + 1, m.triangles[t].v.s[2] + 1);
    if (floor) {
        uint32_t o = m.num_positions;
        fprintf(f, "usemtl floor\nv -4 -1 -4\nv 4 -1 -4\nv 4 -1 4\nv -4 -1 4\nf %u %u %u\nf %u %u %u\n",
                o + 1, o + 3, o + 2, o + 1, o + 4, o + 3);
    }
    fclose(f);
    test_mesh_free(&m);
}

typedef struct {
    cl_mem texels, cdf;
} EnvBuffers;

/* The map's buffers as the first arguments of an env_test.cl kernel (ENV_TEST_PARAMS); returns
 * the next argument index. */
static inline cl_uint env_args(Device *dev, cl_kernel k, const Environment *env, EnvBuffers *b)
{
    Error err = {0};
    size_t n = (size_t)env->width * env->height;
    b->texels = device_buffer(dev, "env_texels", CL_MEM_READ_ONLY, n * sizeof(float4), env->texels, &err);
    b->cdf = device_buffer(dev, "env_cdf", CL_MEM_READ_ONLY, environment_cdf_count(env) * sizeof(uint32_t), env->cdf,
                           &err);
    cr_assert(!error_is_set(&err), "%s", err.message);
    cl_uint a = 0;
    KERNEL_ARG(k, a++, b->texels);
    KERNEL_ARG(k, a++, b->cdf);
    KERNEL_ARG(k, a++, env->width);
    KERNEL_ARG(k, a++, env->height);
    KERNEL_ARG(k, a++, env->rotation);
    return a;
}

static inline void env_buffers_release(EnvBuffers *b)
{
    clReleaseMemObject(b->texels);
    clReleaseMemObject(b->cdf);
}

#endif
