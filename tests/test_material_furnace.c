// SPDX-License-Identifier: MIT
/* The white furnace at the render level (issue 16): a closed sphere under a uniform sky of 1, made
 * of a Fresnel-1 rough conductor or a rough dielectric, can only lose light. A path's weight is a
 * product of sample weights that are each <= 1 for these lobes (F G1 for the conductor; for glass
 * the 1/eta^2 of entering cancels the eta^2 of leaving), so the sphere's mean stays <= 1 (and a
 * conductor's every pixel, up to Russian roulette's 1/0.95); a lobe that creates energy (a pdf too small, a missing G1, an
 * eta^2 on the wrong side) puts the sphere above 1. The energy single-scattering GGX loses at
 * roughness 1 is logged (README "How materials render"). */
#include <criterion/criterion.h>
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>

#include "sphere_obj.h"
#include "support.h"

#define SIZE 40

static const char *write_scene(const char *dir, const char *material)
{
    static char path[512];
    char file[512];
    snprintf(file, sizeof file, "%s/sphere.obj", dir);
    FILE *f = fopen(file, "w");
    cr_assert(f);
    write_sphere_obj(f, (float[3]){0, 0, 0}, 1.0f, 32, 64, false);
    fclose(f);
    snprintf(path, sizeof path, "%s/scene.json", dir);
    f = fopen(path, "w");
    cr_assert(f);
    fprintf(f, "{\"camera\": {\"eye\": [0, 0, 4], \"target\": [0, 0, 0], \"fov_y\": 40},\n"
               " \"materials\": {\"m\": %s},\n"
               " \"objects\": [{\"obj\": \"sphere.obj\", \"material\": \"m\", \"smooth\": true}],\n"
               " \"background\": [1, 1, 1]}\n", material);
    fclose(f);
    return path;
}

/* Renders the sphere of `material` and returns the mean over pixels well inside its silhouette;
 * fails when any such pixel (averaged over its samples) or the mean exceeds 1 beyond roulette. */
static double furnace_mean(const char *material, bool samples_at_most_one)
{
    RenderFixture f;
    render_fixture_open(&f, write_scene(test_temp_dir(), material), SIZE, SIZE);
    float *rgb = render_fixture_render(&f, (RenderSettings){.spp = 64, .max_depth = 64, .seed = 2}, NULL);
    double sum = 0.0, worst = 0.0;
    int n = 0;
    for (int y = 0; y < SIZE; y++)
        for (int x = 0; x < SIZE; x++) {
            /* The sphere's radius is about 13.8 pixels at this camera. */
            if (hypot(x + 0.5 - SIZE / 2.0, y + 0.5 - SIZE / 2.0) > 11.0)
                continue;
            for (int c = 0; c < 3; c++) {
                double v = rgb[3 * (y * SIZE + x) + c];
                sum += v, n++;
                worst = fmax(worst, v);
            }
        }
    free(rgb);
    render_fixture_close(&f);
    cr_assert(n > 300);
    /* A conductor's samples are each <= 1 / 0.95 (roulette divides by at most 0.95 what is <= 1).
     * Glass's are not: roulette renormalises a path inside the glass (weight 1/eta^2) to about 1,
     * and leaving multiplies by eta^2; only the mean is bounded there. */
    if (samples_at_most_one)
        cr_expect(worst <= 1.0 / 0.95 + 1e-4, "%s: a pixel reaches %f", material, worst);
    double mean = sum / n;
    cr_expect(mean <= 1.0 + 2e-3, "%s: the sphere averages %f > 1", material, mean);
    cr_log_info("%s: furnace mean %.4f", material, mean);
    return mean;
}

Test(material_furnace, rough_conductor_with_fresnel_one_never_gains, .timeout = 240)
{
    double smooth = furnace_mean("{\"type\": \"conductor\", \"roughness\": 0}", true);
    cr_expect(fabs(smooth - 1.0) < 1e-3, "a perfect Fresnel-1 mirror keeps everything: %f", smooth);
    furnace_mean("{\"type\": \"conductor\", \"roughness\": 0.3}", true);
    double rough = furnace_mean("{\"type\": \"conductor\", \"roughness\": 1}", true);
    /* Single scattering loses a sizeable share at roughness 1 (no compensation): the sphere's
     * visible disc averages 0.34 (PoCL, logged); above 0.9 would mean the loss went missing. */
    cr_expect(rough < 0.9 && rough > 0.2, "roughness 1 keeps %f", rough);
}

Test(material_furnace, rough_dielectric_never_gains, .timeout = 240)
{
    furnace_mean("{\"type\": \"dielectric\", \"ior\": 1.5, \"roughness\": 0.3}", false);
    furnace_mean("{\"type\": \"dielectric\", \"ior\": 1.5, \"roughness\": 1}", false);
    double smooth = furnace_mean("{\"type\": \"dielectric\", \"ior\": 1.5, \"roughness\": 0}", false);
    /* Smooth glass loses only what max_depth 64 and roulette cut (nothing, in expectation). */
    cr_expect(smooth > 0.98, "smooth glass keeps %f", smooth);
}
