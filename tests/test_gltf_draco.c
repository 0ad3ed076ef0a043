// SPDX-License-Identifier: MIT
/* glTF KHR_draco_mesh_compression (io/gltf_draco.cc) against its uncompressed twin, both written
 * by tests/draco_fixture.cc with libdraco's encoder: every decoded vertex lies within the
 * quantisation step of its twin's (positions 14 bits, normals 12, uvs 14), the triangles are the
 * same, the images agree within what the quantisation moves; EXT_meshopt_compression is refused
 * by name; corrupt Draco data is one line naming the primitive. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "draco_fixture.h"
#include "io/gltf_loader.h"
#include "support.h"

#define AROUND 48

static void load(const char *dir, const char *name, GltfFile *f)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    Error err = {0};
    cr_assert(gltf_load(path, f, &err), "%s", err.message);
    cr_assert_eq(f->num_primitives, 1);
}

/* The twin's vertex nearest to decoded vertex i, position and uv together (the seam has two
 * vertices at one position). */
static size_t twin_of(const Mesh *plain, const Mesh *draco, size_t i)
{
    size_t best = 0;
    double best_d = INFINITY;
    for (size_t k = 0; k < plain->num_positions; k++) {
        double d = 0;
        for (int c = 0; c < 3; c++) {
            double e = plain->positions[3 * k + c] - draco->positions[3 * i + c];
            d += e * e;
        }
        for (int c = 0; c < 2; c++) {
            double e = plain->texcoords[2 * k + c] - draco->texcoords[2 * i + c];
            d += e * e;
        }
        if (d < best_d)
            best_d = d, best = k;
    }
    return best;
}

static int compare_triangles(const void *a, const void *b)
{
    const size_t *x = a, *y = b;
    for (int k = 0; k < 3; k++)
        if (x[k] != y[k])
            return x[k] < y[k] ? -1 : 1;
    return 0;
}

/* The triangles as sorted twin-vertex triples, rotated to start at their smallest index. */
static size_t *triangle_set(const Mesh *m, const size_t *map)
{
    size_t *t = malloc(m->num_triangles * 3 * sizeof *t);
    cr_assert(t);
    for (size_t i = 0; i < m->num_triangles; i++) {
        size_t v[3];
        for (int k = 0; k < 3; k++)
            v[k] = map ? map[m->corners[9 * i + 3 * k]] : (size_t)m->corners[9 * i + 3 * k];
        int r = v[0] <= v[1] && v[0] <= v[2] ? 0 : v[1] <= v[2] ? 1 : 2;
        for (int k = 0; k < 3; k++)
            t[3 * i + k] = v[(r + k) % 3];
    }
    qsort(t, m->num_triangles, 3 * sizeof *t, compare_triangles);
    return t;
}

Test(gltf_draco, decodes_to_its_twin_within_quantisation, .timeout = 60)
{
    const char *dir = test_temp_dir();
    cr_assert(draco_fixture_write(dir, AROUND, 14));
    GltfFile plain_file, draco_file;
    load(dir, "plain.gltf", &plain_file);
    load(dir, "draco.gltf", &draco_file);
    const Mesh *plain = &plain_file.primitives[0].mesh, *draco = &draco_file.primitives[0].mesh;
    cr_assert_eq(draco->num_triangles, plain->num_triangles);
    cr_assert(draco->num_normals == draco->num_positions && draco->num_texcoords == draco->num_positions,
              "normals and uvs decoded");
    size_t *map = malloc(draco->num_positions * sizeof *map);
    cr_assert(map);
    /* Quantisation to b bits over the range 2: steps of 2 / (2^b - 1), errors up to half. */
    const double pos_tol = 1.0 / ((1 << 14) - 1) * 1.01, uv_tol = 0.5 / ((1 << 14) - 1) * 1.01;
    double worst_pos = 0, worst_nrm = 0, worst_uv = 0;
    for (size_t i = 0; i < draco->num_positions; i++) {
        size_t k = map[i] = twin_of(plain, draco, i);
        for (int c = 0; c < 3; c++) {
            worst_pos = fmax(worst_pos, fabs(plain->positions[3 * k + c] - draco->positions[3 * i + c]));
            worst_nrm = fmax(worst_nrm, fabs(plain->normals[3 * k + c] - draco->normals[3 * i + c]));
        }
        for (int c = 0; c < 2; c++)
            worst_uv = fmax(worst_uv, fabs(plain->texcoords[2 * k + c] - draco->texcoords[2 * i + c]));
    }
    cr_expect_leq(worst_pos, pos_tol, "positions off by %g (step/2 %g)", worst_pos, pos_tol);
    cr_expect_leq(worst_uv, uv_tol, "uvs off by %g (step/2 %g)", worst_uv, uv_tol);
    cr_expect_leq(worst_nrm, 2e-3, "normals off by %g (12-bit octahedral)", worst_nrm);
    size_t *a = triangle_set(plain, NULL), *b = triangle_set(draco, map);
    cr_expect(memcmp(a, b, plain->num_triangles * 3 * sizeof *a) == 0,
              "the decoded triangles are the twin's, with the same winding");
    free(a), free(b), free(map);
    gltf_free(&plain_file);
    gltf_free(&draco_file);
}

Test(gltf_draco, renders_like_its_twin, .timeout = 300)
{
    const char *dir = test_temp_dir();
    cr_assert(draco_fixture_write(dir, AROUND, 14));
    char scene[2048];
    const char *names[2] = {"plain.gltf", "draco.gltf"};
    float *rgb[2];
    for (int i = 0; i < 2; i++) {
        snprintf(scene, sizeof scene,
                 "{\"camera\": {\"eye\": [0.4, 0.6, 3], \"target\": [0, 0, 0], \"fov_y\": 45},\n"
                 " \"objects\": [{\"gltf\": \"%s\", \"smooth\": true}],\n"
                 " \"lights\": [{\"type\": \"point\", \"position\": [2, 3, 2], \"intensity\": [20, 20, 20]}]}\n",
                 names[i]);
        RenderFixture f;
        render_fixture_open(&f, test_write_file(dir, i ? "d.json" : "p.json", scene), 32, 32);
        rgb[i] = render_fixture_render(&f, (RenderSettings){.spp = 4, .max_depth = 2, .seed = 3}, NULL);
        render_fixture_close(&f);
    }
    double diff = 0, sum = 0;
    for (int k = 0; k < 32 * 32 * 3; k++)
        diff += fabs(rgb[0][k] - rgb[1][k]), sum += rgb[0][k];
    cr_expect_gt(sum, 1.0, "the sphere is lit");
    /* Point light, max_depth 2: direct light only, so the images differ only where quantised
     * normals and positions shade differently: well under 1 %. */
    cr_expect_lt(diff / sum, 0.01, "the Draco image differs by %.4f of the twin's", diff / sum);
    free(rgb[0]), free(rgb[1]);
}

Test(gltf_draco, meshopt_refused_by_name_and_corrupt_data_in_one_line, .timeout = 60)
{
    const char *dir = test_temp_dir();
    const char *meshopt = test_write_file(dir, "meshopt.gltf",
        "{\"asset\": {\"version\": \"2.0\"}, \"extensionsUsed\": [\"EXT_meshopt_compression\"],"
        " \"extensionsRequired\": [\"EXT_meshopt_compression\"], \"meshes\": []}");
    GltfFile f;
    Error err = {0};
    cr_expect_not(gltf_load(meshopt, &f, &err));
    cr_expect(strstr(err.message, "meshopt.gltf") && strstr(err.message, "EXT_meshopt_compression"),
              "message: %s", err.message);
    cr_assert(draco_fixture_write(dir, 8, 14));
    char path[1024];
    snprintf(path, sizeof path, "%s/draco.bin", dir);
    FILE *bin = fopen(path, "r+b");
    cr_assert(bin);
    fseek(bin, 0, SEEK_END);
    long size = ftell(bin);
    fseek(bin, 0, SEEK_SET);
    for (long i = 0; i < size; i++)
        fputc(0xA5, bin); /* not Draco */
    fclose(bin);
    snprintf(path, sizeof path, "%s/draco.gltf", dir);
    err = (Error){0};
    cr_expect_not(gltf_load(path, &f, &err));
    cr_expect(strstr(err.message, "draco.gltf") &&
                  strstr(err.message, "meshes[0].primitives[0].extensions.KHR_draco_mesh_compression") &&
                  !strchr(err.message, '\n'),
              "message: %s", err.message);
}
