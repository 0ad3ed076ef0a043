// SPDX-License-Identifier: MIT
/* The fast cos and sin that sampling uses instead of the general ones (cl/core/sampling.cl):
 * cos_sin_turns against the C library's double-precision cos and sin over several turns, both
 * signs and every quadrant boundary, and the concentric disc map against its definition
 * (r cos phi, r sin phi with phi = pi/4 b/a, or pi/2 - pi/4 a/b), in double. A wrong quadrant
 * rotation, a lost sign or a polynomial coefficient off in its third digit fails by far more than
 * the 2e-7 allowed (a few float ulps at magnitude 1). */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>

#include "support.h"

#define COUNT (1u << 16)
#define TOLERANCE 2e-7
#define PI 3.14159265358979323846

static void run(Device *dev, const char *name, const float *in, size_t in_floats, float *out)
{
    Error err = {0};
    cl_mem a = device_buffer(dev, "in", CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                             in_floats * sizeof(float), (void *)in, &err);
    cl_mem b = device_buffer(dev, "out", CL_MEM_WRITE_ONLY, 2 * COUNT * sizeof(float), NULL, &err);
    cr_assert(!error_is_set(&err), "%s", err.message);
    cl_kernel kernel = device_kernel(dev, name);
    cl_uint count = COUNT, arg = 0;
    KERNEL_ARG(kernel, arg++, a);
    KERNEL_ARG(kernel, arg++, count);
    KERNEL_ARG(kernel, arg++, b);
    device_run(dev, kernel, COUNT, 0, NULL);
    device_read(dev, b, 0, 2 * COUNT * sizeof(float), out);
    clReleaseKernel(kernel);
    clReleaseMemObject(a);
    clReleaseMemObject(b);
}

Test(sampling_trig, cos_sin_turns_matches_libm)
{
    Device *dev = test_device();
    float *turns = malloc(COUNT * sizeof *turns), *out = malloc(2 * COUNT * sizeof *out);
    cr_assert(turns && out);
    for (uint32_t i = 0; i < COUNT; i++) {
        /* Quarter-turn boundaries and their float neighbours first, then a sweep of [-2, 2). */
        if (i < 96) {
            float q = (float)((int)(i / 3) - 16) * 0.25f;
            turns[i] = i % 3 == 0 ? q : nextafterf(q, i % 3 == 1 ? -INFINITY : INFINITY);
        } else {
            turns[i] = -2.0f + 4.0f * (float)i / COUNT;
        }
    }
    run(dev, "sampling_test_cos_sin_turns", turns, COUNT, out);
    double worst = 0.0;
    uint32_t worst_i = 0;
    for (uint32_t i = 0; i < COUNT; i++) {
        double angle = 2.0 * PI * (double)turns[i];
        double e = fmax(fabs(out[2 * i] - cos(angle)), fabs(out[2 * i + 1] - sin(angle)));
        if (e > worst)
            worst = e, worst_i = i;
    }
    cr_expect_leq(worst, TOLERANCE, "cos_sin_turns(%.9g) = (%.9g, %.9g), libm (%.9g, %.9g)",
                  turns[worst_i], out[2 * worst_i], out[2 * worst_i + 1],
                  cos(2.0 * PI * turns[worst_i]), sin(2.0 * PI * turns[worst_i]));
    free(turns);
    free(out);
    test_device_release(dev);
}

Test(sampling_trig, concentric_disk_matches_its_definition)
{
    Device *dev = test_device();
    float *u = malloc(2 * COUNT * sizeof *u), *out = malloc(2 * COUNT * sizeof *out);
    cr_assert(u && out);
    srand(3);
    for (uint32_t i = 0; i < 2 * COUNT; i++)
        u[i] = (float)(rand() >> 7) / (float)(RAND_MAX >> 7) * 0.999999f;
    u[0] = u[1] = 0.5f; /* the centre */
    run(dev, "sampling_test_disk", u, 2 * COUNT, out);
    double worst = 0.0;
    uint32_t worst_i = 0;
    for (uint32_t i = 0; i < COUNT; i++) {
        double a = 2.0 * u[2 * i] - 1.0, b = 2.0 * u[2 * i + 1] - 1.0, x = 0.0, y = 0.0;
        if (a != 0.0 || b != 0.0) {
            double r = fabs(a) > fabs(b) ? a : b;
            double phi = fabs(a) > fabs(b) ? PI / 4 * (b / a) : PI / 2 - PI / 4 * (a / b);
            x = r * cos(phi), y = r * sin(phi);
        }
        double e = fmax(fabs(out[2 * i] - x), fabs(out[2 * i + 1] - y));
        if (e > worst)
            worst = e, worst_i = i;
    }
    cr_expect_leq(worst, TOLERANCE, "sample_disk_concentric(%.9g, %.9g) = (%.9g, %.9g)",
                  u[2 * worst_i], u[2 * worst_i + 1], out[2 * worst_i], out[2 * worst_i + 1]);
    free(u);
    free(out);
    test_device_release(dev);
}
