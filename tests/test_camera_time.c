// SPDX-License-Identifier: MIT
/* The shutter time of camera paths (generate_camera_rays, cl/core/camera.cl camera_time): with a
 * shutter interval each path draws its fraction s uniformly in [0, 1) (chi-square over 16 bins)
 * from its own random dimension: the camera rays are the same bits as without motion blur, and s
 * does not follow the sub-pixel jitter (correlation, and a chi-square over a 4 x 4 grid of s and
 * jitter). Without an interval every path's s is 0. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "support.h"

#define SIDE 64u
#define SPP 4u
#define SAMPLES (SIDE * SIDE * SPP)
/* Chi-square quantile at p = 1e-6 for 15 degrees of freedom (Wilson-Hilferty): the RNG is
 * deterministic, so this only says how unlikely a failure of a uniform, independent draw is. */
#define CHI_SQUARE_15 57.0

typedef struct {
    cl_float4 *directions;
    float *times;
} CameraPaths;

/* Runs generate_camera_rays over SIDE x SIDE pixels, SPP samples each, with the shutter given. */
static CameraPaths generate(Device *dev, float open, float close)
{
    RenderParams p;
    memset(&p, 0, sizeof p);
    p.camera.eye = (cl_float4){{0, 0, 0, 0}};
    p.camera.right = (cl_float4){{1, 0, 0, 1}};
    p.camera.up = (cl_float4){{0, 1, 0, 0.5f}};
    p.camera.forward = (cl_float4){{0, 0, -1, 1}};
    p.width = p.height = SIDE;
    p.seed = 11;
    p.max_depth = 4;
    p.window_size = SAMPLES;
    p.window_pixels = SIDE * SIDE;
    p.shutter_open = open;
    p.shutter_close = close;
    Error err = {0};
    cl_mem params = device_buffer(dev, "params", CL_MEM_READ_ONLY, sizeof p, &p, &err);
    cl_kernel k = device_kernel(dev, "generate_camera_rays");
    cl_uint arg = 0;
    KERNEL_ARG(k, arg++, params);
    cl_mem ray_direction = NULL, path_time = NULL;
    cl_mem state[32];
    int num_state = 0;
    /* Every path-state buffer in the kernel's order (shared.h PATH_STATE_FIELDS). */
#define STATE_BUFFER(type, name)                                                                   \
    state[num_state] = device_buffer(dev, #name, CL_MEM_READ_WRITE, SAMPLES * sizeof(type), NULL,  \
                                     &err);                                                        \
    if (strcmp(#name, "ray_direction") == 0)                                                       \
        ray_direction = state[num_state];                                                          \
    if (strcmp(#name, "path_time") == 0)                                                           \
        path_time = state[num_state];                                                              \
    KERNEL_ARG(k, arg++, state[num_state]);                                                        \
    num_state++;
    PATH_STATE_FIELDS(STATE_BUFFER)
    SAMPLE_STATE_FIELDS(STATE_BUFFER)
    PIXEL_STATE_FIELDS(STATE_BUFFER)
#undef STATE_BUFFER
    cl_mem active = device_buffer(dev, "active", CL_MEM_READ_WRITE, SAMPLES * sizeof(cl_uint), NULL,
                                  &err);
    cl_mem free_slots = device_buffer(dev, "free_slots", CL_MEM_READ_ONLY, sizeof(cl_uint), NULL,
                                      &err);
    cr_assert(!error_is_set(&err), "%s", err.message);
    cr_assert(ray_direction && path_time);
    cl_uint n_live = 0, first_sample = 0, n_new = SAMPLES, fresh = 1;
    KERNEL_ARGS(k, arg, KARG(active), KARG(free_slots), KARG(n_live), KARG(first_sample),
                KARG(n_new), KARG(fresh));
    /* A path_time the kernel leaves alone shows up as this. */
    float poison = -1.0f;
    CL_CHECK(clEnqueueFillBuffer(dev->queue, path_time, &poison, sizeof poison, 0,
                                 SAMPLES * sizeof(float), 0, NULL, NULL));
    device_run(dev, k, SAMPLES, 0, NULL);
    CameraPaths out = {malloc(SAMPLES * sizeof(cl_float4)), malloc(SAMPLES * sizeof(float))};
    cr_assert(out.directions && out.times);
    device_read(dev, ray_direction, 0, SAMPLES * sizeof(cl_float4), out.directions);
    device_read(dev, path_time, 0, SAMPLES * sizeof(float), out.times);
    for (int i = 0; i < num_state; i++)
        clReleaseMemObject(state[i]);
    clReleaseMemObject(active);
    clReleaseMemObject(free_slots);
    clReleaseMemObject(params);
    clReleaseKernel(k);
    return out;
}

/* The sub-pixel jitter of sample k from its direction (the camera looks down -z, tan(fov/2) 0.5,
 * aspect 1; camera.cl camera_ray). */
static void jitter_of(const cl_float4 *d, uint32_t k, double *jx, double *jy)
{
    uint32_t pixel = k % (SIDE * SIDE);
    double sx = d->s[0] / -d->s[2] / 0.5, sy = d->s[1] / -d->s[2] / 0.5;
    *jx = (sx + 1.0) * SIDE / 2.0 - (pixel % SIDE);
    *jy = (1.0 - sy) * SIDE / 2.0 - (pixel / SIDE);
}

static double correlation(const double *a, const double *b, uint32_t n)
{
    double ma = 0, mb = 0, sab = 0, saa = 0, sbb = 0;
    for (uint32_t i = 0; i < n; i++)
        ma += a[i] / n, mb += b[i] / n;
    for (uint32_t i = 0; i < n; i++) {
        sab += (a[i] - ma) * (b[i] - mb);
        saa += (a[i] - ma) * (a[i] - ma);
        sbb += (b[i] - mb) * (b[i] - mb);
    }
    return sab / sqrt(saa * sbb);
}

Test(camera_time, shutter_time_is_uniform_and_independent, .timeout = 300)
{
    Device *dev = test_device();
    CameraPaths still = generate(dev, 0.0f, 0.0f);
    CameraPaths blur = generate(dev, 2.0f, 3.0f);
    for (uint32_t k = 0; k < SAMPLES; k++)
        cr_assert_eq(still.times[k], 0.0f, "sample %u: time %g without a shutter interval", k,
                     still.times[k]);
    cr_expect(memcmp(still.directions, blur.directions, SAMPLES * sizeof(cl_float4)) == 0,
              "motion blur changes the camera rays");

    double *t = malloc(SAMPLES * sizeof *t), *jx = malloc(SAMPLES * sizeof *jx),
           *jy = malloc(SAMPLES * sizeof *jy);
    cr_assert(t && jx && jy);
    double bins[16] = {0}, grid[4][4] = {{0}};
    for (uint32_t k = 0; k < SAMPLES; k++) {
        t[k] = blur.times[k];
        cr_assert(t[k] >= 0.0 && t[k] < 1.0, "sample %u: time %g outside [0, 1)", k, t[k]);
        jitter_of(&blur.directions[k], k, &jx[k], &jy[k]);
        cr_assert(jx[k] > -1e-3 && jx[k] < 1.001 && jy[k] > -1e-3 && jy[k] < 1.001,
                  "sample %u: jitter (%g, %g) recovered outside the pixel", k, jx[k], jy[k]);
        bins[(int)(t[k] * 16)]++;
        int gx = (int)fmin(fmax(jx[k] * 4, 0), 3);
        grid[(int)(t[k] * 4)][gx]++;
    }
    double chi_t = 0.0, chi_grid = 0.0, e16 = SAMPLES / 16.0;
    for (int b = 0; b < 16; b++)
        chi_t += (bins[b] - e16) * (bins[b] - e16) / e16;
    for (int a = 0; a < 4; a++)
        for (int b = 0; b < 4; b++)
            chi_grid += (grid[a][b] - e16) * (grid[a][b] - e16) / e16;
    double limit = 5.0 / sqrt((double)SAMPLES);
    double rx = correlation(t, jx, SAMPLES), ry = correlation(t, jy, SAMPLES);
    cr_log_info("time: chi-square %.1f (16 bins), %.1f (4 x 4 with jitter x); correlation with "
                "jitter %.4f, %.4f", chi_t, chi_grid, rx, ry);
    cr_expect(chi_t < CHI_SQUARE_15, "time not uniform: chi-square %.1f over 16 bins", chi_t);
    cr_expect(chi_grid < CHI_SQUARE_15, "time follows jitter x: chi-square %.1f over 4 x 4", chi_grid);
    cr_expect(fabs(rx) < limit && fabs(ry) < limit, "time correlates with the jitter: %.4f, %.4f",
              rx, ry);
    free(t), free(jx), free(jy);
    free(still.directions), free(still.times), free(blur.directions), free(blur.times);
    test_device_release(dev);
}
