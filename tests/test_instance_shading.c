// SPDX-License-Identifier: MIT
/* Shading with instances (kernels built with FEATURE_INSTANCES and FEATURE_MOTION):
 * surface_at puts a hit on a transformed, a mirrored and a moving instance where the host's
 * double-precision maths does, with normals through the inverse transpose (a mirrored instance's
 * front is where those point, DESIGN "Objects"); light samples of instanced emitters land on the
 * world triangle with the density entry pdf / world area at the path's time, and the pdf that
 * emission_seen weighs a BSDF ray's hit of the same point with is that same density, also for an
 * emitter whose scale changes over the shutter (the table weighed it at shutter open). Last, the
 * camera's shutter time: uniform in [0, 1), from its own random dimension (the rays do not
 * change, and the time does not follow the jitter). */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "instance_scene.h"
#include "scene/lights.h"
#include "support.h"

/* The test device with this file's kernels, built for instances and motion. */
static Device *instance_device(void)
{
    Device *dev = calloc(1, sizeof *dev);
    Error err = {0};
    const char *spec = getenv("PT_TEST_DEVICE");
    cr_assert(device_open(dev, spec ? spec : "cpu", &err), "device_open: %s", err.message);
    char *source = test_read_file("tests/cl/instance_shading_test.cl", NULL);
    cr_assert(source, "tests/cl/instance_shading_test.cl: run the tests from the repository root");
    bool built = device_build(dev, PROGRAM_FEATURES_ALL, source, "tests/cl/instance_shading_test.cl",
                              &err);
    free(source);
    cr_assert(built, "device_build: %s", err.message);
    return dev;
}

/* Ground; lamp 1 turned, scaled non-uniformly and moved; lamp 2 mirrored (det < 0), turned and
 * moved; lamp 3 moving: scale 3 at open, 1 and turned at close (its emitters' area changes). */
static void lamps(LampInstance out[3])
{
    const double axis[3] = {1, 2, 3}, z[3] = {0, 0, 1}, x[3] = {1, 0, 0};
    Affine r1, r2, r3;
    cr_assert(affine_rotate(axis, 30, &r1) && affine_rotate(z, 20, &r2) && affine_rotate(x, 40, &r3));
    Affine s1 = affine_scale(2, 1.5, 0.5), t1 = affine_translate(5, 1, -2);
    Affine m2 = affine_scale(-1.5, 1, 1), t2 = affine_translate(-4, 0, 0);
    Affine a1 = affine_mul(&r1, &s1), a2 = affine_mul(&r2, &m2);
    Affine s3 = affine_scale(3, 3, 3), t3 = affine_translate(0, 4, 0), t3e = affine_translate(1, 4, 0);
    out[0] = (LampInstance){.transform = affine_mul(&t1, &a1)};
    out[1] = (LampInstance){.transform = affine_mul(&t2, &a2)};
    out[2] = (LampInstance){.transform = affine_mul(&t3, &s3), .moving = true,
                            .end = affine_mul(&t3e, &r3)};
}

/* Instance i's transform at shutter fraction s, as the host composes it. */
static Affine instance_at_time(const SceneData *d, uint32_t i, double s)
{
    const SceneInstance *inst = &d->instances[i];
    if (!inst->moving)
        return inst->to_world;
    Trs trs = trs_interpolate(&inst->motion[0], &inst->motion[1], s);
    return trs_compose(&trs);
}

typedef struct {
    Device *dev;
    SceneData data;
    SceneBvh bvh;
    SceneBuffers buffers;
} InstanceFixture;

static void fixture_open(InstanceFixture *f)
{
    LampInstance l[3];
    lamps(l);
    instance_scene_build(&f->data, l, 3);
    f->dev = instance_device();
    /* The kernels here read the scene's arrays, never the BVH: one level is enough. */
    scene_accel_build(&f->bvh, &f->data, f->dev, BVH_ONE_LEVEL);
    Error err = {0};
    cr_assert(scene_buffers_upload(f->dev, &f->data, &f->bvh, &f->buffers, &err), "%s", err.message);
}

static void fixture_close(InstanceFixture *f)
{
    scene_buffers_release(&f->buffers);
    scene_bvh_free(&f->bvh);
    scene_data_free(&f->data);
    test_device_release(f->dev);
}

static void expect_close3(const float *got, const double *want, double tol, const char *what,
                          uint32_t instance, uint32_t tri, double s)
{
    double err = 0.0;
    for (int k = 0; k < 3; k++)
        err = fmax(err, fabs(got[k] - want[k]));
    cr_expect(err <= tol,
              "%s of instance %u triangle %u at s = %.2f: (%.6f %.6f %.6f), expected (%.6f %.6f "
              "%.6f)",
              what, instance, tri, s, got[0], got[1], got[2], want[0], want[1], want[2]);
}

Test(instance_shading, surface_at_is_in_world_space, .timeout = 300)
{
    InstanceFixture f;
    fixture_open(&f);
    const double times[2] = {0.0, 0.6};
    const float u = 0.2f, v = 0.3f;
    for (int ti = 0; ti < 2; ti++) {
        double s = times[ti];
        /* Every (instance, triangle of its mesh) pair. */
        cl_float4 queries[16];
        uint32_t qi[16], qt[16], n = 0;
        for (uint32_t i = 0; i < f.data.num_instances; i++) {
            const SceneMesh *mesh = &f.data.meshes[f.data.instances[i].mesh];
            for (uint32_t t = mesh->first_triangle; t < mesh->first_triangle + mesh->num_triangles; t++) {
                cl_uint tu = t, iu = i;
                queries[n].s[0] = u, queries[n].s[1] = v;
                memcpy(&queries[n].s[2], &tu, 4);
                memcpy(&queries[n].s[3], &iu, 4);
                qi[n] = i, qt[n++] = t;
            }
        }
        Error err = {0};
        cl_mem qbuf = device_buffer(f.dev, "queries", CL_MEM_READ_ONLY, n * sizeof(cl_float4),
                                    queries, &err);
        cl_mem obuf = device_buffer(f.dev, "out", CL_MEM_WRITE_ONLY, 4 * n * sizeof(cl_float4), NULL,
                                    &err);
        cr_assert(!error_is_set(&err), "%s", err.message);
        cl_kernel k = device_kernel(f.dev, "instance_shading_test_surface");
        cl_float time = (cl_float)s;
        cl_uint count = n;
        cl_uint arg = scene_buffers_set_args(&f.buffers, k, 0);
        KERNEL_ARGS(k, arg, KARG(qbuf), KARG(count), KARG(time), KARG(obuf));
        device_run(f.dev, k, n, 0, NULL);
        cl_float4 out[64];
        device_read(f.dev, obuf, 0, 4 * n * sizeof(cl_float4), out);
        for (uint32_t q = 0; q < n; q++) {
            uint32_t t = qt[q];
            Affine m = instance_at_time(&f.data, qi[q], s);
            double c[3][3], obj[3], world[3], e1[3], e2[3], n_obj[3], ng[3], ns[3];
            Affine id = affine_identity();
            ref_corners(t, &id, c);
            for (int k3 = 0; k3 < 3; k3++)
                obj[k3] = (1.0 - u - v) * c[0][k3] + u * c[1][k3] + v * c[2][k3];
            ref_point(&m, obj, world);
            vec_sub(c[1], c[0], e1);
            vec_sub(c[2], c[0], e2);
            vec_cross(e1, e2, n_obj);
            ref_normal(&m, n_obj, ng);
            memcpy(ns, ng, sizeof ns);
            if (instance_scene_triangles[t][3] & TRIANGLE_HAS_NORMALS) {
                double interpolated[3];
                for (int k3 = 0; k3 < 3; k3++) {
                    interpolated[k3] = 0.0;
                    const double w[3] = {1.0 - u - v, u, v};
                    for (int corner = 0; corner < 3; corner++)
                        interpolated[k3] +=
                            w[corner] * instance_scene_normals[instance_scene_triangles[t][corner]][k3];
                }
                ref_normal(&m, interpolated, ns);
            }
            expect_close3(out[4 * q].s, world, 1e-4, "position", qi[q], t, s);
            expect_close3(out[4 * q + 1].s, obj, 1e-6, "object position", qi[q], t, s);
            expect_close3(out[4 * q + 2].s, ng, 1e-5, "geometric normal", qi[q], t, s);
            expect_close3(out[4 * q + 3].s, ns, 1e-5, "shading normal", qi[q], t, s);
            if (qi[q] == 2) {
                /* The mirrored lamp: the front is opposite its world-space winding. */
                double w[3][3], we1[3], we2[3], wn[3];
                ref_corners(t, &m, w);
                vec_sub(w[1], w[0], we1);
                vec_sub(w[2], w[0], we2);
                vec_cross(we1, we2, wn);
                cr_assert(vec_dot(wn, ng) < 0.0, "the test's mirrored instance mirrors");
            }
        }
        clReleaseKernel(k);
        clReleaseMemObject(qbuf);
        clReleaseMemObject(obuf);
    }
    fixture_close(&f);
}

#define LIGHT_SAMPLES 4096u

/* The table entry of (instance, triangle). */
static const LightEntry *entry_of(const LightTable *t, uint32_t instance, uint32_t tri)
{
    for (uint32_t e = 0; e < t->count; e++)
        if (t->entries[e].instance == instance && t->entries[e].triangle == tri)
            return &t->entries[e];
    return NULL;
}

static void check_light_samples(InstanceFixture *f, double s, const double from[3])
{
    LightTable table;
    light_table_build(&table, &f->data);
    RenderParams params;
    memset(&params, 0, sizeof params);
    params.seed = 5;
    params.scene = f->buffers.params;
    Error err = {0};
    cl_mem pbuf = device_buffer(f->dev, "params", CL_MEM_READ_ONLY, sizeof params, &params, &err);
    cl_mem obuf = device_buffer(f->dev, "out", CL_MEM_WRITE_ONLY,
                                4 * LIGHT_SAMPLES * sizeof(cl_float4), NULL, &err);
    cr_assert(!error_is_set(&err), "%s", err.message);
    cl_kernel k = device_kernel(f->dev, "instance_shading_test_light");
    cl_float4 from4 = {{(float)from[0], (float)from[1], (float)from[2], 0.0f}};
    cl_float time = (cl_float)s;
    cl_uint n = LIGHT_SAMPLES;
    cl_uint arg = 0;
    KERNEL_ARG(k, arg++, pbuf);
    arg = scene_buffers_set_args(&f->buffers, k, arg);
    KERNEL_ARGS(k, arg, KARG(from4), KARG(time), KARG(n), KARG(obuf));
    device_run(f->dev, k, LIGHT_SAMPLES, 0, NULL);
    cl_float4 *out = malloc(4 * LIGHT_SAMPLES * sizeof *out);
    device_read(f->dev, obuf, 0, 4 * LIGHT_SAMPLES * sizeof *out, out);

    uint32_t front_of[4] = {0}, failures = 0;
    for (uint32_t i = 0; i < LIGHT_SAMPLES && failures < 8; i++) {
        const float *pos = out[4 * i].s, *normal = out[4 * i + 1].s, *hit = out[4 * i + 2].s;
        float pdf_w = out[4 * i].s[3], hit_pdf = out[4 * i + 2].s[3], radiance = out[4 * i + 3].s[3];
        uint32_t instance, tri = 0;
        memcpy(&instance, &out[4 * i + 1].s[3], 4);
        cr_assert(instance >= 1 && instance <= 3, "sample %u: instance %u", i, instance);
        Affine m = instance_at_time(&f->data, instance, s);
        /* Which of the lamp's emitters: the one whose world plane holds the point. */
        double best = INFINITY, want_n[3] = {0};
        const uint32_t emitters[2] = {LAMP_BRIGHT, LAMP_DIM};
        for (int e = 0; e < 2; e++) {
            double c[3][3], e1[3], e2[3], nn[3], d[3], obj_n[3];
            ref_corners(emitters[e], &m, c);
            vec_sub(c[1], c[0], e1);
            vec_sub(c[2], c[0], e2);
            vec_cross(e1, e2, nn);
            vec_normalize(nn);
            double p[3] = {pos[0], pos[1], pos[2]};
            vec_sub(p, c[0], d);
            if (fabs(vec_dot(d, nn)) < best) {
                best = fabs(vec_dot(d, nn));
                tri = emitters[e];
                Affine id = affine_identity();
                double oc[3][3], oe1[3], oe2[3];
                ref_corners(tri, &id, oc);
                vec_sub(oc[1], oc[0], oe1);
                vec_sub(oc[2], oc[0], oe2);
                vec_cross(oe1, oe2, obj_n);
                ref_normal(&m, obj_n, want_n);
            }
        }
        bool ok = best < 1e-4;
        cr_expect(ok, "sample %u (instance %u, s %.2f): off both emitters' planes by %g", i, instance,
                  s, best);
        double p[3] = {pos[0], pos[1], pos[2]}, h[3] = {hit[0], hit[1], hit[2]};
        expect_close3(normal, want_n, 1e-5, "light normal", instance, tri, s);
        expect_close3(pos, h, 1e-4, "light sample vs surface_at position", instance, tri, s);
        double to_from[3];
        vec_sub(from, p, to_from);
        double dist = sqrt(vec_dot(to_from, to_from));
        double cos_light = vec_dot(to_from, want_n) / dist;
        if (cos_light < 1e-3) {
            ok &= radiance == 0.0f && pdf_w == 0.0f;
            cr_expect(radiance == 0.0f, "sample %u: the back of instance %u triangle %u emits %g", i,
                      instance, tri, radiance);
        } else {
            front_of[instance]++;
            const LightEntry *entry = entry_of(&table, instance, tri);
            cr_assert(entry);
            double want_pdf = entry->pdf * dist * dist / (cos_light * ref_area(tri, &m));
            bool pdf_ok = fabs(pdf_w - want_pdf) <= 2e-4 * want_pdf;
            bool mis_ok = fabs(hit_pdf - pdf_w) <= 2e-4 * pdf_w;
            ok &= radiance > 0.0f && pdf_ok && mis_ok;
            cr_expect(radiance > 0.0f, "sample %u: the front of instance %u triangle %u is dark", i,
                      instance, tri);
            cr_expect(pdf_ok, "sample %u (instance %u triangle %u, s %.2f): pdf %g, expected %g", i,
                      instance, tri, s, pdf_w, want_pdf);
            cr_expect(mis_ok,
                      "sample %u (instance %u triangle %u, s %.2f): a BSDF ray's hit is weighed "
                      "with pdf %g, light sampling drew it with %g",
                      i, instance, tri, s, hit_pdf, pdf_w);
        }
        failures += !ok;
    }
    for (uint32_t i = 1; i <= 3; i++)
        cr_expect(front_of[i] > 50, "instance %u: %u samples seen from the front", i, front_of[i]);
    free(out);
    clReleaseKernel(k);
    clReleaseMemObject(pbuf);
    clReleaseMemObject(obuf);
    light_table_free(&table);
}

Test(instance_shading, light_samples_and_mis_agree_on_instances, .timeout = 300)
{
    InstanceFixture f;
    fixture_open(&f);
    const double from[3] = {0.5, 2.0, 6.0};
    check_light_samples(&f, 0.0, from);
    check_light_samples(&f, 0.6, from);
    fixture_close(&f);
}
