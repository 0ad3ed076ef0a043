// SPDX-License-Identifier: MIT
/* The environment map (shared/DESIGN.md "Environment"), on maps generated here: orientation and
 * rotation sense of the lat-long mapping, env_sample against the map's distribution (chi-square)
 * and a pdf that integrates to one, the white furnace through the map path, NEE + MIS against
 * BSDF-only sampling under a high-contrast map. Bad input: tests/test_environment_input.c. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <stb_image_write.h>

#include "io/image_io.h"
#include "procedural_mesh.h"
#include "scene/environment.h"
#include "support.h"

static const double PI = 3.14159265358979323846;

/* DESIGN's mapping inverted with rotation 0: the direction at the centre of texel (i, j), row 0 at
 * the top. */
static void texel_direction(int i, int j, int w, int h, double d[3])
{
    double phi = 2.0 * PI * ((i + 0.5) / w - 0.5), theta = PI * (j + 0.5) / h;
    d[0] = sin(theta) * sin(phi), d[1] = cos(theta), d[2] = -sin(theta) * cos(phi);
}

/* Six colours, one per axis: -z red, +x green, -x blue, +z yellow, +y white, -y magenta. */
static const double axes[6][3] = {{0, 0, -1}, {1, 0, 0}, {-1, 0, 0}, {0, 0, 1}, {0, 1, 0}, {0, -1, 0}};
static const float axis_colours[6][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 0}, {1, 1, 1}, {1, 0, 1}};

/* Each texel gets the colour of the axis nearest its centre direction. */
static float *axis_map(int w, int h)
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

/* scene.json with the given objects and environment (file, rotation), camera at the origin. */
static const char *write_scene(const char *dir, const char *name, const char *objects,
                               const char *env_file, float rotation, const char *camera)
{
    char text[2048];
    snprintf(text, sizeof text,
             "{\"camera\": %s, \"objects\": %s,\n"
             " \"environment\": {\"file\": \"%s\", \"scale\": 1, \"rotation\": %g}}\n",
             camera, objects, env_file, rotation);
    return test_write_file(dir, name, text);
}

/* A speck far below, out of every view: the scene needs an object. */
static const char *write_speck(const char *dir)
{
    return test_write_file(dir, "speck.obj", "v 50 -50 50\nv 50.01 -50 50\nv 50 -50 50.01\nf 1 2 3\n");
}

/* Looking along each axis from the origin, the image centre shows the colour DESIGN's mapping
 * predicts; rotation 90 turns the map like an object rotated 90 degrees counter-clockwise seen
 * from +y: what was at -z is now at -x, +x moves to -z, +z to +x, -x to +z. */
Test(environment, orientation_and_rotation_follow_design, .timeout = 120)
{
    const char *dir = test_temp_dir();
    int w = 64, h = 32;
    float *rgb = axis_map(w, h);
    char exr[512], hdr[512];
    snprintf(exr, sizeof exr, "%s/axes.exr", dir);
    snprintf(hdr, sizeof hdr, "%s/axes.hdr", dir);
    Error err = {0};
    cr_assert(image_write_exr(exr, rgb, w, h, &err), "%s", err.message);
    cr_assert(stbi_write_hdr(hdr, w, h, 3, rgb));
    free(rgb);
    write_speck(dir);
    const char *camera = "{\"eye\": [0, 0, 0], \"target\": [0, 0, -1], \"fov_y\": 4}";
    const char *objects = "[{\"obj\": \"speck.obj\"}]";
    /* view direction, up, expected axis colour at rotation 0 and at rotation 90 */
    static const struct {
        float look[3], up[3];
        int at_0, at_90;
    } views[] = {
        {{0, 0, -1}, {0, 1, 0}, 0, 1}, {{1, 0, 0}, {0, 1, 0}, 1, 3}, {{-1, 0, 0}, {0, 1, 0}, 2, 0},
        {{0, 0, 1}, {0, 1, 0}, 3, 2},  {{0, 1, 0}, {0, 0, -1}, 4, 4}, {{0, -1, 0}, {0, 0, -1}, 5, 5},
    };
    for (int rotated = 0; rotated < 2; rotated++) {
        /* The EXR reader at rotation 0, the HDR reader (stb) at 90. */
        const char *scene = write_scene(dir, rotated ? "rotated.json" : "plain.json", objects,
                                        rotated ? "axes.hdr" : "axes.exr", rotated ? 90.0f : 0.0f,
                                        camera);
        RenderFixture f;
        render_fixture_open(&f, scene, 9, 9);
        for (size_t v = 0; v < sizeof views / sizeof views[0]; v++) {
            CameraDesc *c = &f.scene.desc.camera;
            memset(c->eye, 0, sizeof c->eye);
            memcpy(c->target, views[v].look, sizeof c->target);
            memcpy(c->up, views[v].up, sizeof c->up);
            float *img = render_fixture_render(&f, (RenderSettings){.spp = 4, .max_depth = 1, .seed = 1}, NULL);
            int expected = rotated ? views[v].at_90 : views[v].at_0;
            const float *px = &img[3 * (4 * 9 + 4)];
            for (int ch = 0; ch < 3; ch++)
                cr_expect(fabsf(px[ch] - axis_colours[expected][ch]) < 1e-3f,
                          "rotation %d, looking along (%g, %g, %g): centre channel %d = %g, expected %g",
                          rotated ? 90 : 0, views[v].look[0], views[v].look[1], views[v].look[2], ch,
                          px[ch], axis_colours[expected][ch]);
            free(img);
        }
        render_fixture_close(&f);
    }
}

/* A high-contrast map: a bright sun, a black band, a noisy sky. */
static float *contrast_map(int w, int h)
{
    float *rgb = malloc((size_t)w * h * 3 * sizeof *rgb);
    uint64_t state = 7;
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++) {
            float *t = &rgb[3 * (j * w + i)];
            float base = j < h / 2 ? 0.3f + mesh_rng_float(&state) : 0.05f;
            t[0] = base, t[1] = 0.8f * base, t[2] = 1.2f * base;
            if (j == h / 2 + 2) /* a black row: never sampled */
                t[0] = t[1] = t[2] = 0.0f;
            if (i >= w / 8 && i < w / 8 + 2 && j >= h / 4 && j < h / 4 + 2)
                t[0] = 200.0f, t[1] = 180.0f, t[2] = 150.0f;
        }
    return rgb;
}

typedef struct {
    cl_mem texels, marginal, conditional;
} EnvBuffers;

static cl_uint env_args(Device *dev, cl_kernel k, const Environment *env, EnvBuffers *b)
{
    Error err = {0};
    size_t w = env->width, h = env->height;
    b->texels = device_buffer(dev, "env_texels", CL_MEM_READ_ONLY, w * h * sizeof(float4), env->texels, &err);
    b->marginal = device_buffer(dev, "env_marginal", CL_MEM_READ_ONLY, (h + 1) * sizeof(float), env->marginal, &err);
    b->conditional = device_buffer(dev, "env_conditional", CL_MEM_READ_ONLY, h * (w + 1) * sizeof(float),
                                   env->conditional, &err);
    cr_assert(!error_is_set(&err), "%s", err.message);
    cl_uint a = 0;
    KERNEL_ARG(k, a++, b->texels);
    KERNEL_ARG(k, a++, b->marginal);
    KERNEL_ARG(k, a++, b->conditional);
    KERNEL_ARG(k, a++, env->width);
    KERNEL_ARG(k, a++, env->height);
    KERNEL_ARG(k, a++, env->rotation);
    return a;
}

static void env_buffers_release(EnvBuffers *b)
{
    clReleaseMemObject(b->texels);
    clReleaseMemObject(b->marginal);
    clReleaseMemObject(b->conditional);
}

/* env_sample's directions fall in each texel in proportion to luminance x sin(row centre) (computed
 * here from the map, not from the host's tables), never in a black texel; each sample's pdf and
 * radiance equal what an escaped ray in its direction sees (env_lookup). */
Test(environment, samples_follow_luminance_times_sin_theta, .timeout = 300)
{
    int w = 32, h = 16;
    float *rgb = contrast_map(w, h);
    Environment env;
    Error err = {0};
    cr_assert(environment_build(&env, rgb, w, h, 1.0f, 37.0f, "contrast", &err), "%s", err.message);
    double *expected = malloc((size_t)w * h * sizeof *expected), total = 0.0;
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++) {
            const float *t = &rgb[3 * (j * w + i)];
            double f = (0.2126 * t[0] + 0.7152 * t[1] + 0.0722 * t[2]) * sin(PI * (j + 0.5) / h);
            expected[j * w + i] = f, total += f;
        }
    Device *dev = test_device();
    cl_kernel k = device_kernel(dev, "env_test_sample");
    EnvBuffers b;
    cl_uint a = env_args(dev, k, &env, &b);
    cl_uint items = 4096, per_item = 1024, seed = 5;
    cl_uint *counts = calloc((size_t)w * h, sizeof *counts), zero = 0;
    cl_mem counts_buf = device_buffer(dev, "counts", CL_MEM_READ_WRITE, (size_t)w * h * sizeof *counts, counts, &err);
    cl_mem mismatch_buf = device_buffer(dev, "mismatches", CL_MEM_READ_WRITE, sizeof zero, &zero, &err);
    cr_assert(!error_is_set(&err), "%s", err.message);
    KERNEL_ARG(k, a++, per_item);
    KERNEL_ARG(k, a++, seed);
    KERNEL_ARG(k, a++, counts_buf);
    KERNEL_ARG(k, a++, mismatch_buf);
    device_run(dev, k, items, 0, NULL);
    device_read(dev, counts_buf, 0, (size_t)w * h * sizeof *counts, counts);
    cl_uint mismatches;
    device_read(dev, mismatch_buf, 0, sizeof mismatches, &mismatches);
    cr_expect_eq(mismatches, 0, "%u samples whose pdf or radiance differ from env_lookup's", mismatches);

    double n = (double)items * per_item, chi = 0.0, pooled_e = 0.0, pooled_o = 0.0;
    int bins = 0;
    for (int t = 0; t < w * h; t++) {
        double e = n * expected[t] / total;
        if (e == 0.0) {
            cr_expect_eq(counts[t], 0, "texel %d is black but was sampled %u times", t, counts[t]);
        } else if (e < 20.0) {
            pooled_e += e, pooled_o += counts[t];
        } else {
            chi += (counts[t] - e) * (counts[t] - e) / e, bins++;
        }
    }
    if (pooled_e > 0.0)
        chi += (pooled_o - pooled_e) * (pooled_o - pooled_e) / pooled_e, bins++;
    /* Wilson-Hilferty quantile at p = 1e-6 (z = 4.75) for bins - 1 degrees of freedom. */
    double dof = bins - 1, q = 1.0 - 2.0 / (9.0 * dof) + 4.75 * sqrt(2.0 / (9.0 * dof));
    double limit = dof * q * q * q;
    cr_log_info("chi-square %.1f over %d bins (limit %.1f)", chi, bins, limit);
    cr_expect(chi < limit, "chi-square %.1f over %d bins, limit %.1f", chi, bins, limit);

    /* The solid-angle pdf integrates to 1: midpoint rule on a grid 8x finer than the texels. */
    cl_kernel kp = device_kernel(dev, "env_test_pdf");
    EnvBuffers bp;
    cl_uint ap = env_args(dev, kp, &env, &bp);
    cl_uint nt = 8 * (cl_uint)h, np = 8 * (cl_uint)w, nd = nt * np;
    float4 *dirs = malloc(nd * sizeof *dirs);
    float *pdf = malloc(nd * sizeof *pdf);
    for (cl_uint j = 0; j < nt; j++)
        for (cl_uint i = 0; i < np; i++) {
            double th = PI * (j + 0.5) / nt, ph = 2.0 * PI * (i + 0.5) / np;
            dirs[j * np + i] = (float4){{(float)(sin(th) * cos(ph)), (float)cos(th), (float)(sin(th) * sin(ph)), 0}};
        }
    cl_mem dirs_buf = device_buffer(dev, "dirs", CL_MEM_READ_ONLY, nd * sizeof *dirs, dirs, &err);
    cl_mem pdf_buf = device_buffer(dev, "pdf", CL_MEM_WRITE_ONLY, nd * sizeof *pdf, NULL, &err);
    cr_assert(!error_is_set(&err), "%s", err.message);
    KERNEL_ARG(kp, ap++, dirs_buf);
    KERNEL_ARG(kp, ap++, nd);
    KERNEL_ARG(kp, ap++, pdf_buf);
    device_run(dev, kp, nd, 0, NULL);
    device_read(dev, pdf_buf, 0, nd * sizeof *pdf, pdf);
    double integral = 0.0;
    for (cl_uint j = 0; j < nt; j++)
        for (cl_uint i = 0; i < np; i++)
            integral += pdf[j * np + i] * sin(PI * (j + 0.5) / nt) * (PI / nt) * (2.0 * PI / np);
    cr_expect(fabs(integral - 1.0) < 2e-3, "the pdf integrates to %.5f over the sphere", integral);

    clReleaseMemObject(counts_buf), clReleaseMemObject(mismatch_buf);
    clReleaseMemObject(dirs_buf), clReleaseMemObject(pdf_buf);
    env_buffers_release(&b), env_buffers_release(&bp);
    clReleaseKernel(k), clReleaseKernel(kp);
    test_device_release(dev);
    environment_free(&env);
    free(rgb), free(expected), free(counts), free(dirs), free(pdf);
}

/* An icosphere of radius 1 at the origin with material "ball", and optionally a floor at y = -1
 * with material "floor". */
static void write_ball_obj(const char *dir, bool floor)
{
    test_write_file(dir, "ball.mtl", "newmtl ball\nKd 0.8 0.8 0.8\nnewmtl floor\nKd 0.5 0.5 0.5\n");
    char path[512];
    snprintf(path, sizeof path, "%s/ball.obj", dir);
    FILE *f = fopen(path, "w");
    cr_assert(f);
    Mesh m = mesh_icosphere(3);
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
    mesh_free(&m);
}

/* White furnace through the map path: a constant map of 1 lights a convex sphere of albedo 0.8 to
 * exactly 0.8, as the constant background does; with NEE on, the map is sampled (noisy per sample,
 * 0.8 on average), with it off every sample is 0.8. */
Test(environment, white_furnace_with_a_constant_map, .timeout = 120)
{
    const char *dir = test_temp_dir();
    float ones[16 * 8 * 3];
    for (size_t i = 0; i < sizeof ones / sizeof ones[0]; i++)
        ones[i] = 1.0f;
    char exr[512];
    snprintf(exr, sizeof exr, "%s/ones.exr", dir);
    Error err = {0};
    cr_assert(image_write_exr(exr, ones, 16, 8, &err), "%s", err.message);
    write_ball_obj(dir, false);
    const char *scene = write_scene(dir, "scene.json", "[{\"obj\": \"ball.obj\"}]", "ones.exr", 30.0f,
                                    "{\"eye\": [0, 0, 4], \"target\": [0, 0, 0], \"fov_y\": 40}");
    RenderFixture f;
    render_fixture_open(&f, scene, 48, 48);
    cr_assert_eq(f.buffers.num_emissive, 1, "the map is the only entry of the light table");
    for (int no_nee = 0; no_nee < 2; no_nee++) {
        float *rgb = render_fixture_render(&f, (RenderSettings){.spp = 64, .max_depth = 8, .seed = 1, .no_nee = no_nee}, NULL);
        double sum = 0.0;
        int on_sphere = 0;
        for (int y = 0; y < 48; y++)
            for (int x = 0; x < 48; x++) {
                double r = hypot(x + 0.5 - 24, y + 0.5 - 24);
                const float *px = &rgb[3 * (y * 48 + x)];
                for (int c = 0; c < 3; c++) {
                    if (r < 14) {
                        sum += px[c];
                        if (no_nee)
                            cr_expect(fabsf(px[c] - 0.8f) < 1e-3f, "pixel %d,%d = %f, expected 0.8", x, y, px[c]);
                    } else if (r > 19) {
                        cr_expect(fabsf(px[c] - 1.0f) < 1e-5f, "sky pixel %d,%d = %f, expected 1", x, y, px[c]);
                    }
                }
                on_sphere += r < 14;
            }
        double mean = sum / (3.0 * on_sphere);
        cr_expect(fabs(mean - 0.8) < 2e-3, "no_nee %d: the sphere's mean is %.5f, expected 0.8", no_nee, mean);
        free(rgb);
    }
    render_fixture_close(&f);
}

/* Block means of a 32 x 32 image (8 x 8 blocks of 4 x 4 pixels) per channel. */
#define SIDE 32
#define BLOCK 8
#define NB ((SIDE / BLOCK) * (SIDE / BLOCK) * 3)
static void block_means(const float *rgb, double out[NB])
{
    memset(out, 0, NB * sizeof *out);
    for (int y = 0; y < SIDE; y++)
        for (int x = 0; x < SIDE; x++)
            for (int c = 0; c < 3; c++)
                out[((y / BLOCK) * (SIDE / BLOCK) + x / BLOCK) * 3 + c] += rgb[3 * (y * SIDE + x) + c] / (BLOCK * BLOCK);
}

/* A diffuse sphere on a floor under a map with a small bright sun: NEE + MIS (the map sampled,
 * escaped rays weighted) and BSDF-only sampling converge to the same image. Each block's mean is
 * compared with the spread of that mean over independent seeds. `objects` is the scene's object
 * list (the ball and floor, plus anything else). */
static void check_nee_against_bsdf_sampling(const char *dir, const char *objects)
{
    int w = 64, h = 32;
    float *rgb = contrast_map(w, h);
    char hdr[512];
    snprintf(hdr, sizeof hdr, "%s/sky.hdr", dir);
    cr_assert(stbi_write_hdr(hdr, w, h, 3, rgb));
    free(rgb);
    write_ball_obj(dir, true);
    const char *scene = write_scene(dir, "scene.json", objects, "sky.hdr", 20.0f,
                                    "{\"eye\": [0, 1, 4], \"target\": [0, -0.3, 0], \"fov_y\": 45}");
    RenderFixture f;
    render_fixture_open(&f, scene, SIDE, SIDE);
    enum { SEEDS = 8 };
    static double mean[2][SEEDS][NB];
    for (int no_nee = 0; no_nee < 2; no_nee++)
        for (int s = 0; s < SEEDS; s++) {
            RenderSettings rs = {.spp = no_nee ? 2048 : 256, .max_depth = 4, .seed = 11 + 7 * s + no_nee, .no_nee = no_nee};
            float *img = render_fixture_render(&f, rs, NULL);
            block_means(img, mean[no_nee][s]);
            free(img);
        }
    double worst = 0.0, total[2] = {0, 0};
    for (int b = 0; b < NB; b++) {
        double m[2], var[2];
        for (int k = 0; k < 2; k++) {
            m[k] = var[k] = 0.0;
            for (int s = 0; s < SEEDS; s++)
                m[k] += mean[k][s][b] / SEEDS;
            for (int s = 0; s < SEEDS; s++)
                var[k] += (mean[k][s][b] - m[k]) * (mean[k][s][b] - m[k]) / (SEEDS - 1) / SEEDS;
            total[k] += m[k];
        }
        /* A floor on the standard error: blocks of pure sky have no noise at all. */
        double z = fabs(m[0] - m[1]) / sqrt(var[0] + var[1] + 1e-5 * m[1] * m[1] + 1e-12);
        worst = fmax(worst, z);
        if (z > 3.0)
            cr_log_info("block %d channel %d: NEE %.4f +- %.4f, BSDF-only %.4f +- %.4f (z = %.1f)", b / 3, b % 3, m[0], sqrt(var[0]), m[1], sqrt(var[1]), z);
        cr_expect(z < 5.0, "block %d channel %d: NEE %.4f, BSDF-only %.4f (z = %.1f)", b / 3, b % 3, m[0], m[1], z);
    }
    cr_log_info("worst block z %.2f; image means NEE %.4f, BSDF-only %.4f", worst, total[0] / NB, total[1] / NB);
    cr_expect(fabs(total[0] - total[1]) < 0.01 * total[1], "image means NEE %.4f, BSDF-only %.4f",
              total[0] / NB, total[1] / NB);
    render_fixture_close(&f);
}

Test(environment, nee_with_mis_agrees_with_bsdf_sampling, .timeout = 300)
{
    check_nee_against_bsdf_sampling(test_temp_dir(), "[{\"obj\": \"ball.obj\"}]");
}

/* The same with a small lamp (two emissive triangles facing down) above the ball: triangles and
 * the map share one light table, so each one's MIS weight (emission_seen, environment_seen) must
 * use its share of the table's power. */
Test(environment, nee_with_mis_agrees_with_a_lamp_in_the_same_light_table, .timeout = 300)
{
    const char *dir = test_temp_dir();
    test_write_file(dir, "lamp.mtl", "newmtl lamp\nKd 0 0 0\nKe 20 18 15\n");
    test_write_file(dir, "lamp.obj",
                    "mtllib lamp.mtl\nusemtl lamp\nv -0.3 2.5 -0.3\nv 0.3 2.5 -0.3\nv 0.3 2.5 0.3\n"
                    "v -0.3 2.5 0.3\nf 1 2 3\nf 1 3 4\n");
    check_nee_against_bsdf_sampling(dir, "[{\"obj\": \"ball.obj\"}, {\"obj\": \"lamp.obj\"}]");
}
