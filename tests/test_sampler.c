// SPDX-License-Identifier: MIT
/* The Sobol sampler (cl/core/sobol.cl, rng.cl's RNG_SOBOL keys): the stratification it promises,
 * the faster convergence it is for, and that it converges to the independent sampler's image. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "support.h"

#define NET_POINTS 4096u /* 2^12 */

static void sobol_points(Device *dev, cl_kernel kernel, cl_mem out, cl_uint pixel, cl_uint seed,
                         cl_uint tuple, cl_uint first, cl_uint use_pair, cl_uint *points)
{
    cl_uint count = NET_POINTS;
    KERNEL_ARGS(kernel, 0, KARG(pixel), KARG(seed), KARG(tuple), KARG(first), KARG(count),
                KARG(use_pair), KARG(out));
    device_run(dev, kernel, NET_POINTS, 0, NULL);
    device_read(dev, out, 0, NET_POINTS * 2 * sizeof(cl_uint), points);
}

/* The top `bits` bits of x (0 for bits = 0, where x >> 32 would be undefined). */
static uint32_t top_bits(uint32_t x, unsigned bits) { return bits ? x >> (32u - bits) : 0u; }

/* Whether points[0 .. 2^k - 1] form a (0, k, 2)-net in base 2: for every split a + b = k, each
 * of the 2^a x 2^b elementary intervals holds exactly one point. */
static bool is_net(const cl_uint *points, unsigned k, unsigned *bad_a)
{
    static unsigned char seen[1u << 12];
    for (unsigned a = 0; a <= k; a++) {
        memset(seen, 0, (size_t)1 << k);
        for (uint32_t i = 0; i < (1u << k); i++) {
            uint32_t cell = top_bits(points[2 * i], a) << (k - a) | top_bits(points[2 * i + 1], k - a);
            if (seen[cell]++) {
                *bad_a = a;
                return false;
            }
        }
    }
    return true;
}

/* Every aligned block of 2^k samples of a pixel (the first 2^k among them: any prefix is a union
 * of such blocks, one per binary digit of its length) is a (0, k, 2)-net, for every tuple, pixel
 * and seed: what keeps adaptive sampling's and resumed renders' partial counts stratified. */
Test(sampler, sobol_aligned_blocks_are_nets, .timeout = 600)
{
    static const cl_uint pixels[] = {0u, 1u, 4099u, 262143u};
    static const cl_uint seeds[] = {0u, 7u};
    static const cl_uint tuples[] = {0u, 1u, 4u, 5u, 6u, 13u, 500u};
    Device *dev = test_device();
    Error err = {0};
    cl_mem out = device_buffer(dev, "points", CL_MEM_WRITE_ONLY, NET_POINTS * 2 * sizeof(cl_uint), NULL, &err);
    cr_assert(!error_is_set(&err), "%s", err.message);
    cl_kernel kernel = device_kernel(dev, "rng_test_sobol_tuple");
    static cl_uint points[2 * NET_POINTS], scalar[2 * NET_POINTS];
    for (size_t p = 0; p < sizeof pixels / sizeof *pixels; p++)
        for (size_t s = 0; s < sizeof seeds / sizeof *seeds; s++)
            for (size_t t = 0; t < sizeof tuples / sizeof *tuples; t++)
                for (cl_uint first = 0; first <= 2 * NET_POINTS; first += 2 * NET_POINTS) {
                    sobol_points(dev, kernel, out, pixels[p], seeds[s], tuples[t], first, 1u, points);
                    sobol_points(dev, kernel, out, pixels[p], seeds[s], tuples[t], first, 0u, scalar);
                    cr_assert(!memcmp(points, scalar, sizeof points),
                              "pixel %u tuple %u: rng_bits2 and rng_bits disagree", pixels[p], tuples[t]);
                    for (unsigned k = 0; k <= 12; k++)
                        for (uint32_t block = 0; block < NET_POINTS >> k; block++) {
                            unsigned a = 0;
                            cr_assert(is_net(points + 2 * (block << k), k, &a),
                                      "pixel %u seed %u tuple %u: samples %u .. %u are no (0, %u, 2)-net "
                                      "(two points in one 2^-%u x 2^-%u interval)",
                                      pixels[p], seeds[s], tuples[t], first + (block << k),
                                      first + ((block + 1) << k) - 1, k, a, k - a);
                        }
                }
    clReleaseKernel(kernel);
    clReleaseMemObject(out);
    test_device_release(dev);
}
