// SPDX-License-Identifier: MIT
/* Next-event estimation picks emitters in proportion to their power, also among very many: with
 * 2^20 emitters of eight power levels, the picks that the kernels' light_pick makes from the host's
 * alias table (host/scene/lights.c) with the path RNG pass a chi-square test against the exact
 * probabilities. The estimator divides by the exact pdf, so any deviation is bias, not noise. One
 * 24-bit uniform shared by the index (20 bits) and the alias coin (the 4 left) keeps an entry with
 * probability ceil(16 p) / 16 instead of p: up to 6% too often for the dim ones. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "scene/lights.h"
#include "support.h"

#define EMITTERS (1u << 20)
#define LEVELS 8u      /* power levels, 0.3 + 0.25 level */
#define BLOCKS 8u      /* index blocks: a group is (level, block), LEVELS * BLOCKS of them */
#define GROUPS (LEVELS * BLOCKS) /* LIGHT_PICK_TEST_GROUPS of tests/cl/light_pick_test.cl */
#define ITEMS 4096u
#define SAMPLES_PER_ITEM 4096u
/* The chi-square quantile for GROUPS - 1 = 63 degrees of freedom at p = 1e-6 (Wilson-Hilferty):
 * the deterministic RNG makes the outcome fixed, this only says how unlikely a failure of an
 * unbiased sampler would be. */
#define CHI_SQUARE_LIMIT 132.0

static uint32_t level_of(uint32_t t) { return (t * 2654435761u) >> 29; }

Test(light_pick, picks_follow_power_among_a_million_emitters, .timeout = 300)
{
    /* One shared triangle, so that power is the material's luminance times a fixed area. */
    SceneData data;
    memset(&data, 0, sizeof data);
    float4 corners[3] = {{{0, 0, 0, 0}}, {{1, 0, 0, 0}}, {{0, 1, 0, 0}}};
    Material materials[LEVELS];
    memset(materials, 0, sizeof materials);
    for (uint32_t l = 0; l < LEVELS; l++) {
        float luminance = 0.3f + 0.25f * (float)l;
        materials[l].emission = (float4){{luminance, luminance, luminance, luminance}};
    }
    data.positions = corners;
    data.num_vertices = 3;
    data.materials = materials;
    data.num_materials = LEVELS;
    data.num_triangles = data.num_emissive = EMITTERS;
    data.triangles = malloc(EMITTERS * sizeof *data.triangles);
    data.material_ids = malloc(EMITTERS * sizeof *data.material_ids);
    data.emissive_triangles = malloc(EMITTERS * sizeof *data.emissive_triangles);
    cl_uchar *group_of = malloc(EMITTERS);
    double expected[GROUPS] = {0}, total = 0.0;
    for (uint32_t t = 0; t < EMITTERS; t++) {
        data.triangles[t] = (Triangle){{{0, 1, 2, 0}}};
        data.material_ids[t] = level_of(t);
        data.emissive_triangles[t] = t;
        group_of[t] = (cl_uchar)(level_of(t) * BLOCKS + t / (EMITTERS / BLOCKS));
        double power = 0.3 + 0.25 * level_of(t);
        expected[group_of[t]] += power;
        total += power;
    }
    LightTable table;
    light_table_build(&table, &data);
    cr_assert_eq(table.count, EMITTERS);

    Device *dev = test_device();
    Error err = {0};
    cl_mem lights = device_buffer(dev, "lights", CL_MEM_READ_ONLY, EMITTERS * sizeof(LightEntry),
                                  table.entries, &err);
    cl_mem groups = device_buffer(dev, "group_of", CL_MEM_READ_ONLY, EMITTERS, group_of, &err);
    cl_uint zero[GROUPS] = {0};
    cl_mem counts = device_buffer(dev, "counts", CL_MEM_READ_WRITE, sizeof zero, zero, &err);
    cr_assert(!error_is_set(&err), "%s", err.message);
    cl_kernel kernel = device_kernel(dev, "light_pick_test_count");
    cl_uint arg = 0, num_lights = EMITTERS, samples = SAMPLES_PER_ITEM, seed = 3;
    KERNEL_ARG(kernel, arg++, lights);
    KERNEL_ARG(kernel, arg++, num_lights);
    KERNEL_ARG(kernel, arg++, groups);
    KERNEL_ARG(kernel, arg++, samples);
    KERNEL_ARG(kernel, arg++, seed);
    KERNEL_ARG(kernel, arg++, counts);
    device_run(dev, kernel, ITEMS, 0, NULL);
    cl_uint observed[GROUPS];
    device_read(dev, counts, 0, sizeof observed, observed);

    double n = (double)ITEMS * SAMPLES_PER_ITEM, chi_square = 0.0, worst = 0.0;
    uint64_t sum = 0;
    uint32_t worst_group = 0;
    for (uint32_t g = 0; g < GROUPS; g++) {
        double e = n * expected[g] / total, d = observed[g] - e;
        chi_square += d * d / e;
        sum += observed[g];
        if (fabs(d / e) > worst)
            worst = fabs(d / e), worst_group = g;
    }
    cr_assert_eq(sum, (uint64_t)n, "every draw picks one emitter");
    cr_log_info("chi-square %.1f over %u groups", chi_square, GROUPS);
    cr_expect(chi_square < CHI_SQUARE_LIMIT,
              "chi-square %.1f over %u groups (limit %.0f); worst: level %u block %u picked %.2f%% "
              "off its power share",
              chi_square, GROUPS, CHI_SQUARE_LIMIT, worst_group / BLOCKS, worst_group % BLOCKS,
              100.0 * worst);
    clReleaseKernel(kernel);
    clReleaseMemObject(lights);
    clReleaseMemObject(groups);
    clReleaseMemObject(counts);
    test_device_release(dev);
    light_table_free(&table);
    free(data.triangles);
    free(data.material_ids);
    free(data.emissive_triangles);
    free(group_of);
}
