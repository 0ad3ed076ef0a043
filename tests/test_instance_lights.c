// SPDX-License-Identifier: MIT
/* The light table over instances (host/scene/lights.c): one entry per (instance, emissive
 * triangle of its mesh), in instance order, weighted by the triangle's world area through the
 * instance (a mirrored one too; a moving one at shutter open) times its luminance; the pdfs sum to
 * 1 and the alias table draws each entry with its pdf. One-level scenes (one identity instance)
 * keep the table they had before instances. */
#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "instance_scene.h"
#include "scene/lights.h"
#include "support.h"

static Affine rotated(const double axis[3], double degrees)
{
    Affine r;
    cr_assert(affine_rotate(axis, degrees, &r));
    return r;
}

/* Three lamps: turned and moved (area kept), scaled non-uniformly and turned, mirrored and
 * scaled. */
static void three_lamps(LampInstance lamps[3])
{
    const double axis[3] = {1, 2, 3}, y[3] = {0, 1, 0};
    Affine r1 = rotated(axis, 30), r2 = rotated(y, 70);
    Affine t1 = affine_translate(5, 1, -2), s2 = affine_scale(2, 1.5, 0.5);
    Affine t3 = affine_translate(-4, 0, 0), m3 = affine_scale(-1.5, 1, 1);
    Affine a2 = affine_mul(&r2, &s2);
    lamps[0] = (LampInstance){.transform = affine_mul(&t1, &r1)};
    lamps[1] = (LampInstance){.transform = affine_mul(&t1, &a2)};
    lamps[2] = (LampInstance){.transform = affine_mul(&t3, &m3)};
}

/* How often the alias table (Vose: keep entry i with prob, else take its alias) draws each entry. */
static void alias_probabilities(const LightTable *t, double *out)
{
    for (uint32_t i = 0; i < t->count; i++)
        out[i] = 0.0;
    for (uint32_t i = 0; i < t->count; i++) {
        out[i] += t->entries[i].prob / t->count;
        out[t->entries[i].alias] += (1.0 - t->entries[i].prob) / t->count;
    }
}

Test(instance_lights, entries_follow_world_area_over_instances)
{
    LampInstance lamps[3];
    three_lamps(lamps);
    SceneData d;
    instance_scene_build(&d, lamps, 3);
    LightTable table;
    light_table_build(&table, &d);

    /* The ground emits nothing: lamps 1..3, each with its bright then its dim triangle. */
    cr_assert_eq(table.count, 6, "one entry per (lamp instance, emissive triangle)");
    double expected[6], total = 0.0;
    for (uint32_t e = 0; e < 6; e++) {
        uint32_t instance = 1 + e / 2, tri = e % 2 ? LAMP_DIM : LAMP_BRIGHT;
        cr_expect_eq(table.entries[e].instance, instance, "entry %u: instance %u, expected %u", e,
                     table.entries[e].instance, instance);
        cr_expect_eq(table.entries[e].triangle, tri, "entry %u: triangle %u, expected %u", e,
                     table.entries[e].triangle, tri);
        expected[e] = ref_area(tri, &lamps[instance - 1].transform) * (tri == LAMP_DIM ? 0.5 : 2.0);
        total += expected[e];
    }
    /* The mirrored lamp (det < 0) has positive, scaled areas like any other. */
    cr_expect_float_eq(ref_area(LAMP_BRIGHT, &lamps[2].transform), 1.5 * 0.5, 1e-9);
    cr_expect_float_eq(table.total_power, total, 1e-5 * total, "total power %g, expected %g",
                       table.total_power, total);
    double sum = 0.0, drawn[6];
    alias_probabilities(&table, drawn);
    for (uint32_t e = 0; e < 6; e++) {
        double want = expected[e] / total;
        sum += table.entries[e].pdf;
        cr_expect_float_eq(table.entries[e].pdf, want, 1e-6, "entry %u: pdf %.7f, expected %.7f", e,
                           table.entries[e].pdf, want);
        cr_expect_float_eq(drawn[e], want, 1e-6, "entry %u: drawn with %.7f, expected %.7f", e,
                           drawn[e], want);
    }
    cr_expect_float_eq(sum, 1.0, 1e-6, "the pdfs sum to %.8f", sum);
    /* The scale makes the lamps' powers differ: an area-blind table fails the checks above. */
    cr_assert(fabs(expected[2] - expected[0]) > 0.1 * expected[0]);
    light_table_free(&table);
    scene_data_free(&d);
}

/* A moving lamp's entries are weighed at shutter open (Instance.to_world; the kernels correct
 * the MIS pdf of hits at other times, cl/light/light_sample.cl emitter_area_ratio). */
Test(instance_lights, moving_instance_weighs_its_open_transform)
{
    LampInstance lamps[2] = {
        {.transform = affine_identity()},
        {.transform = affine_scale(3, 3, 3), .moving = true, .end = affine_scale(1, 1, 1)},
    };
    SceneData d;
    instance_scene_build(&d, lamps, 2);
    LightTable table;
    light_table_build(&table, &d);
    cr_assert_eq(table.count, 4);
    /* Bright: area 0.5 x 2; 9 times that for the moving lamp at open. */
    cr_expect_float_eq(table.entries[2].pdf / table.entries[0].pdf, 9.0, 1e-5,
                       "moving lamp's weight ratio %g, expected 9 (its area at open)",
                       table.entries[2].pdf / table.entries[0].pdf);
    light_table_free(&table);
    scene_data_free(&d);
}

/* A mesh that no instance uses emits nothing; one used twice emits twice. */
Test(instance_lights, every_instance_of_a_mesh_counts)
{
    LampInstance lamps[2] = {{.transform = affine_identity()},
                             {.transform = affine_translate(0, 5, 0)}};
    SceneData d;
    instance_scene_build(&d, lamps, 2);
    LightTable table;
    light_table_build(&table, &d);
    cr_expect_eq(table.count, 4);
    cr_expect_float_eq(table.entries[0].pdf, table.entries[2].pdf, 1e-7);
    light_table_free(&table);
    /* Only the ground left: no light. */
    d.num_instances = 1;
    light_table_build(&table, &d);
    cr_expect_eq(table.count, 0);
    cr_expect_null(table.entries);
    light_table_free(&table);
    scene_data_free(&d);
}

/* One identity instance over everything (what scene_data_finish gives a one-level scene) and a
 * SceneData without instances build the same table, bit for bit, as before instances existed:
 * entries in emissive_triangles order, instance 0. */
Test(instance_lights, one_level_scene_keeps_its_table)
{
    SceneData d;
    instance_scene_build(&d, NULL, 0);
    /* One mesh of everything, one identity instance: a one-level scene. */
    d.num_meshes = 0, d.num_instances = 0;
    Error err = {0};
    cr_assert(scene_data_add_mesh(&d, 0, 0, &err));
    SceneInstance whole = {.mesh = 0, .object = -1, .to_world = affine_identity()};
    cr_assert(scene_data_add_instance(&d, &whole, &err));
    scene_data_finish_instances(&d);
    cr_assert(!d.two_level);
    LightTable one_level;
    light_table_build(&one_level, &d);
    uint32_t n = d.num_instances;
    d.num_instances = 0;
    LightTable bare;
    light_table_build(&bare, &d);
    d.num_instances = n;
    cr_assert_eq(one_level.count, 2);
    cr_assert_eq(bare.count, 2);
    cr_expect(memcmp(one_level.entries, bare.entries, 2 * sizeof(LightEntry)) == 0);
    cr_expect_eq(one_level.total_power, bare.total_power);
    cr_expect_eq(one_level.entries[0].triangle, LAMP_BRIGHT);
    cr_expect_eq(one_level.entries[1].triangle, LAMP_DIM);
    cr_expect_eq(one_level.entries[0].instance, 0);
    cr_expect_eq(one_level.entries[0].pdf, (float)(1.0 / 1.5));
    light_table_free(&one_level);
    light_table_free(&bare);
    scene_data_free(&d);
}
