// SPDX-License-Identifier: MIT
/* Grid media rendered (shared/DESIGN.md "Media"; cl/medium/medium_grid.cl), from Mitsuba .vol
 * files written here, against closed forms:
 *   - transmittance: an emitter seen through a grid whose density varies across the image (4 x 4
 *     voxels, one along the view) is Le exp(-sigma_t rho(x, y) d), rho the bilinear interpolation
 *     between voxel centres, clamped to the edge voxels: the voxel-centre convention, the file's
 *     bounding box, the medium's transform, the brick walk and the majorants all show in it;
 *   - a sparse grid (most bricks empty, one dense blob far off the ray) leaves the light untouched
 *     where the ray misses the blob and dims it where it passes through;
 *   - a white furnace: a non-absorbing grid of random densities in an `interface` box disappears
 *     under a uniform sky. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "media_fixtures.h"
#include "support.h"

static const double PI = 3.14159265358979323846;

/* write_vol_file into dir. */
static void write_vol(const char *dir, const char *name, int nx, int ny, int nz,
                      const float *values, const float lo[3], const float hi[3])
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    write_vol_file(path, nx, ny, nz, values, lo, hi);
}

static float *render_scene(const char *scene, int spp, int max_depth, unsigned seed)
{
    RenderFixture f;
    render_fixture_open(&f, scene, 0, 0);
    float *rgb = render_fixture_render(
        &f, (RenderSettings){.spp = spp, .max_depth = max_depth, .seed = seed}, NULL);
    render_fixture_close(&f);
    return rgb;
}

/* A lamp (radiance 1) at z = -3 seen from (0, 0, 8) with a narrow view (half-width `half` at
 * z = 0) through the grid medium `medium` filling the box |x|, |y| <= 1, |z| <= 0.5. */
#define RES 24
static const char *lamp_scene(const char *dir, const char *medium, double half)
{
    box_obj(dir, "box.obj", -1, -1, -0.5, 1, 1, 0.5);
    test_write_file(dir, "lamp.obj", "v -9 -9 -3\nv 9 -9 -3\nv 9 9 -3\nv -9 9 -3\nf 1 2 3 4\n");
    char text[4096];
    snprintf(text, sizeof text,
             "{\"camera\": {\"eye\": [0, 0, 8], \"target\": [0, 0, 0], \"up\": [0, 1, 0], "
             "\"fov_y\": %.9g},\n \"film\": {\"width\": %d, \"height\": %d},\n"
             " \"media\": {\"smoke\": %s},\n"
             " \"materials\": {\"lamp\": {\"type\": \"diffuse\", \"albedo\": 0, \"emission\": 1},\n"
             "               \"boundary\": {\"type\": \"interface\"}},\n"
             " \"objects\": [{\"obj\": \"lamp.obj\", \"material\": \"lamp\"},\n"
             "             {\"obj\": \"box.obj\", \"material\": \"boundary\", \"interior\": \"smoke\"}]}\n",
             2.0 * atan(half / 8.0) * 180.0 / PI, RES, RES, medium);
    return test_write_file(dir, "scene.json", text);
}

/* The ray through the film point (sx, sy) in [-1, 1]^2 crosses z = 0 at (sx, sy) * half. */
static void film_point(int i, int j, int a, int b, int sub, double half, double *x, double *y)
{
    *x = (2.0 * (i + (a + 0.5) / sub) / RES - 1.0) * half;
    *y = (1.0 - 2.0 * (j + (b + 0.5) / sub) / RES) * half;
}

/* Bilinear interpolation of a 4 x 4 grid over [lo, hi]^2 with centre values v (x fastest),
 * clamped to the edge voxels. */
static double bilinear(const float *v, double x, double y, double lo, double hi)
{
    double fx = (x - lo) / (hi - lo) * 4.0 - 0.5, fy = (y - lo) / (hi - lo) * 4.0 - 0.5;
    fx = fmin(fmax(fx, 0.0), 3.0), fy = fmin(fmax(fy, 0.0), 3.0);
    int ix = (int)floor(fx), iy = (int)floor(fy);
    if (ix > 2)
        ix = 2;
    if (iy > 2)
        iy = 2;
    double tx = fx - ix, ty = fy - iy;
    double v00 = v[iy * 4 + ix], v10 = v[iy * 4 + ix + 1], v01 = v[(iy + 1) * 4 + ix],
           v11 = v[(iy + 1) * 4 + ix + 1];
    return (1 - ty) * ((1 - tx) * v00 + tx * v10) + ty * ((1 - tx) * v01 + tx * v11);
}

Test(media_grid, transmittance_follows_the_interpolated_density, .timeout = 600)
{
    const char *dir = test_temp_dir();
    /* 4 x 4 x 1 voxels over x, y in [-0.8, 0.8] (the file's bbox; z [-0.5, 0.5]): densities 0 to
     * 1.5, a different one per voxel. Outside the bbox the density is 0. */
    float v[16];
    for (int k = 0; k < 16; k++)
        v[k] = (float)((k * 7) % 16) / 10.0f;
    const float lo[3] = {-0.8f, -0.8f, -0.5f}, hi[3] = {0.8f, 0.8f, 0.5f};
    write_vol(dir, "ramp.vol", 4, 4, 1, v, lo, hi);
    /* Grey: the tracking's weight is 0 or 1 (delta tracking), so a pixel's estimate has at most a
     * Bernoulli variance (the sampler's stratification only lowers it). Chromatic tracking is
     * test_media_render's. */
    const double sigma_t[3] = {1.2, 1.2, 1.2}, scale = 1.5;
    char medium[512];
    snprintf(medium, sizeof medium,
             "{\"type\": \"grid\", \"file\": \"ramp.vol\", \"density_scale\": %g, "
             "\"sigma_t\": [%g, %g, %g], \"albedo\": 0}",
             scale, sigma_t[0], sigma_t[1], sigma_t[2]);
    double half = 1.0;
    const char *scene = lamp_scene(dir, medium, half);
    float *rgb = render_scene(scene, 256, 1, 3);
    /* Per pixel: the mean of exp(-sigma_t scale rho) over the footprint; the estimate's noise
     * (256 spp of a 0/1-ish tracking weight) bounds each pixel to a few percent: compare the mean
     * over each pixel instead against 4.5 sigma of a Bernoulli-like estimate. */
    double worst_z = 0.0;
    for (int j = 0; j < RES; j++)
        for (int i = 0; i < RES; i++)
            for (int c = 0; c < 3; c++) {
                double sum = 0.0;
                for (int a = 0; a < 6; a++)
                    for (int b = 0; b < 6; b++) {
                        double x0, y0;
                        film_point(i, j, a, b, 6, half, &x0, &y0);
                        /* The ray from the eye (0, 0, 8) through (x0, y0, 0) is at (x0, y0)
                         * (8 - z) / 8 at depth z: the optical depth along it through the slab,
                         * by the midpoint rule over z, times its length per unit z. */
                        double depth = 0.0, ds = sqrt(1.0 + (x0 * x0 + y0 * y0) / 64.0);
                        for (int k = 0; k < 64; k++) {
                            double z = -0.5 + (k + 0.5) / 64.0, f = (8.0 - z) / 8.0;
                            double x = x0 * f, y = y0 * f;
                            bool inside = fabs(x) <= 0.8 && fabs(y) <= 0.8;
                            depth += (inside ? bilinear(v, x, y, -0.8, 0.8) : 0.0) / 64.0 * ds;
                        }
                        sum += exp(-sigma_t[c] * scale * depth);
                    }
                double t = sum / 36.0, got = rgb[3 * (j * RES + i) + c];
                double sd = sqrt(fmax(t * (1.0 - t), 1e-4) / 256.0);
                worst_z = fmax(worst_z, fabs(got - t) / sd);
            }
    cr_log_info("grid transmittance: worst pixel z %.2f", worst_z);
    /* 1728 pixel-channels: 5.5 sigma is passed by chance about once in 10^4 renders. */
    cr_expect(worst_z < 5.5, "a pixel is %.2f standard deviations off the closed form", worst_z);
    free(rgb);
}

Test(media_grid, sparse_grid_dims_only_where_the_blob_is, .timeout = 600)
{
    const char *dir = test_temp_dir();
    /* 64^3 voxels over [-1, 1]^2 x [-0.5, 0.5]: zero but for a dense cube of 8^3 voxels around
     * (0.5, 0.5): most bricks empty, the walk must skip them and stop in the blob. Along z the
     * blob fills one brick, so its interpolation ramps reach into two bricks with no voxel of their
     * own (3% of the optical depth: below this test's noise; the majorants that must cover them
     * are checked exactly in test_volume_grid). */
    enum { N = 64 };
    float *v = calloc((size_t)N * N * N, sizeof *v);
    cr_assert(v);
    for (int z = 24; z < 32; z++) /* one brick exactly: its ramps spill into two empty bricks */
        for (int y = 44; y < 52; y++)
            for (int x = 44; x < 52; x++)
                v[((size_t)z * N + y) * N + x] = 4.0f;
    const float lo[3] = {-1, -1, -0.5f}, hi[3] = {1, 1, 0.5f};
    write_vol(dir, "blob.vol", N, N, N, v, lo, hi);
    free(v);
    const char *scene = lamp_scene(
        dir, "{\"type\": \"grid\", \"file\": \"blob.vol\", \"albedo\": 0, \"density_scale\": 2}", 1.0);
    float *rgb = render_scene(scene, 256, 1, 7);
    /* The blob's flat core covers x, y in (0.39, 0.61) (voxel centres 44.5 .. 51.5 of 64 over
     * [-1, 1]); along z its 8 voxels and the ramps to their neighbours add up to 8 voxels = 0.125
     * of density 8: transmittance exp(-1) there. Pixels 17, 18 across and 5, 6 down see x, y in
     * (0.42, 0.58). */
    double core = 0.0;
    for (int j = 5; j <= 6; j++)
        for (int i = 17; i <= 18; i++)
            core += rgb[3 * (j * RES + i) + 1] / 4.0;
    double far_sum = 0.0;
    int far_n = 0;
    for (int j = RES / 2; j < RES; j++) /* the bottom half: y < 0, far from the blob */
        for (int i = 0; i < RES; i++) {
            far_sum += rgb[3 * (j * RES + i) + 1];
            far_n++;
        }
    cr_log_info("sparse grid: core pixels %.4f (expected about %.4f), far pixels %.6f", core,
                exp(-1.0), far_sum / far_n);
    cr_expect(fabs(far_sum / far_n - 1.0) < 1e-6, "light away from the blob is dimmed: %.6f",
              far_sum / far_n);
    cr_expect(fabs(core - exp(-1.0)) < 0.03, "through the blob: %.4f, expected about %.4f", core,
              exp(-1.0));
    free(rgb);
}

Test(media_grid, white_furnace, .timeout = 600)
{
    const char *dir = test_temp_dir();
    enum { N = 20 };
    float v[N * N * N];
    srand(5);
    for (int k = 0; k < N * N * N; k++)
        v[k] = (float)rand() / (float)RAND_MAX * 3.0f;
    const float lo[3] = {-1, -1, -1}, hi[3] = {1, 1, 1};
    write_vol(dir, "noise.vol", N, N, N, v, lo, hi);
    box_obj(dir, "box.obj", -1, -1, -1, 1, 1, 1);
    const char *scene = test_write_file(
        dir, "scene.json",
        "{\"camera\": {\"eye\": [2.5, 2, 4], \"target\": [0, 0, 0], \"up\": [0, 1, 0], \"fov_y\": 40},\n"
        " \"film\": {\"width\": 16, \"height\": 16},\n"
        " \"media\": {\"smoke\": {\"type\": \"grid\", \"file\": \"noise.vol\", \"sigma_t\": [1, 2, 3],"
        " \"albedo\": 1, \"g\": 0.4}},\n"
        " \"materials\": {\"boundary\": {\"type\": \"interface\"}},\n"
        " \"objects\": [{\"obj\": \"box.obj\", \"material\": \"boundary\", \"interior\": \"smoke\"}],\n"
        " \"background\": [0.5, 0.5, 0.5]}\n");
    float *rgb = render_scene(scene, 256, 1000, 11);
    for (int c = 0; c < 3; c++) {
        double sum = 0.0, sum2 = 0.0;
        for (int k = 0; k < 16 * 16; k++) {
            double x = rgb[3 * k + c];
            sum += x, sum2 += x * x;
        }
        double mean = sum / 256.0, se = sqrt(fmax(sum2 / 256.0 - mean * mean, 0.0) / 256.0);
        cr_log_info("grid furnace channel %d: %.5f +- %.5f", c, mean, se);
        cr_expect(fabs(mean - 0.5) < 4.5 * se + 1e-6, "channel %d: %.5f, the sky is 0.5 (se %.5f)",
                  c, mean, se);
    }
    free(rgb);
}

/* ---- NanoVDB ---------------------------------------------------------------------------------- */

#include "nvdb_fixture.h"

/* The same 8^3 densities as a .vol over [-1, 1]^3 and as a NanoVDB grid whose map puts its voxel
 * centres where the .vol's are (voxel size 0.25, voxel ijk at -1 + 0.25 (ijk + 0.5)): the two
 * scenes render the same image (the grids go through different readers and index maps, so a rare
 * tracking decision may flip on a last-bit difference of the world-to-index transform: nearly
 * every pixel has the same bits and the means agree). */
Test(media_grid, nanovdb_renders_as_the_same_vol, .timeout = 600)
{
    const char *dir = test_temp_dir();
    enum { N = 8 };
    float v[N * N * N];
    int ijk[3 * N * N * N];
    srand(9);
    for (int z = 0, k = 0; z < N; z++)
        for (int y = 0; y < N; y++)
            for (int x = 0; x < N; x++, k++) {
                v[k] = 0.5f + 2.0f * (float)rand() / (float)RAND_MAX;
                ijk[3 * k] = x, ijk[3 * k + 1] = y, ijk[3 * k + 2] = z;
            }
    const float lo[3] = {-1, -1, -1}, hi[3] = {1, 1, 1};
    write_vol(dir, "g.vol", N, N, N, v, lo, hi);
    char nvdb[512];
    snprintf(nvdb, sizeof nvdb, "%s/g.nvdb", dir);
    const double matrix[9] = {0.25, 0, 0, 0, 0.25, 0, 0, 0, 0.25};
    const double translation[3] = {-1 + 0.125, -1 + 0.125, -1 + 0.125};
    cr_assert(nvdb_fixture_write_voxels(nvdb, "density", N * N * N, ijk, v, matrix, translation));
    box_obj(dir, "box.obj", -1.2, -1.2, -1.2, 1.2, 1.2, 1.2);
    test_write_file(dir, "lamp.obj", "v -9 -9 -3\nv 9 -9 -3\nv 9 9 -3\nv -9 9 -3\nf 1 2 3 4\n");
    float *img[2];
    for (int f = 0; f < 2; f++) {
        char text[2048];
        snprintf(text, sizeof text,
                 "{\"camera\": {\"eye\": [1, 1.5, 6], \"target\": [0, 0, 0], \"up\": [0, 1, 0], "
                 "\"fov_y\": 35},\n \"film\": {\"width\": 24, \"height\": 24},\n"
                 " \"media\": {\"smoke\": {\"type\": \"grid\", \"file\": \"%s\", \"albedo\": 0.6, "
                 "\"g\": 0.3}},\n"
                 " \"materials\": {\"lamp\": {\"type\": \"diffuse\", \"albedo\": 0, \"emission\": 1},\n"
                 "               \"boundary\": {\"type\": \"interface\"}},\n"
                 " \"objects\": [{\"obj\": \"lamp.obj\", \"material\": \"lamp\"},\n"
                 "             {\"obj\": \"box.obj\", \"material\": \"boundary\", \"interior\": \"smoke\"}],\n"
                 " \"background\": [0.2, 0.25, 0.3]}\n",
                 f ? "g.nvdb" : "g.vol");
        img[f] = render_scene(test_write_file(dir, "scene.json", text), 64, 8, 13);
    }
    size_t same = 0, n = 24 * 24 * 3;
    double mean[2] = {0, 0};
    for (size_t i = 0; i < n; i++) {
        same += memcmp(&img[0][i], &img[1][i], sizeof(float)) == 0;
        mean[0] += img[0][i] / n, mean[1] += img[1][i] / n;
    }
    cr_log_info("nanovdb vs vol: %zu of %zu values the same bits, means %.6f %.6f", same, n,
                mean[0], mean[1]);
    cr_expect(same >= n * 95 / 100, "only %zu of %zu values have the same bits", same, n);
    cr_expect(fabs(mean[0] - mean[1]) < 0.01 * mean[0], "means %.6f (vol) and %.6f (nvdb)",
              mean[0], mean[1]);
    cr_expect(mean[0] > 0.05, "the image is dark: %.4f", mean[0]);
    free(img[0]);
    free(img[1]);
}
