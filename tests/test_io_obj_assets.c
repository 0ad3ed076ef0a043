// SPDX-License-Identifier: MIT
/* OBJ loading of the public assets (host/io/obj_loader.cc): every asset imports with counts that
 * match an independent scan of its lines, faces are triangulated from their own corners with the
 * right area and material, and the known meshes have their known triangle counts. */
#include <criterion/criterion.h>
#include <ctype.h>
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/obj_loader.h"
#include "support.h"

/* ---- independent line scan of an OBJ ---------------------------------------------------- */

typedef struct {
    size_t first, corners;   /* into LineCounts.positions */
    size_t distinct_corners; /* fewer than corners when a position repeats (degenerate face) */
    char mtl[128];           /* the usemtl in force, "" before any */
} LineFace;

typedef struct {
    size_t v, vt, vn, f;
    size_t triangles; /* sum over faces of corners - 2 */
    LineFace *faces;
    long *positions; /* 0-based position index of every face corner */
    size_t num_positions, capacity_positions;
} LineCounts;

/* The keyword at the start of a line (after blanks), copied into word. */
static const char *first_word(const char *line, char *word, size_t size)
{
    while (*line == ' ' || *line == '\t')
        line++;
    size_t n = 0;
    while (line[n] && !isspace((unsigned char)line[n]) && n + 1 < size) {
        word[n] = line[n];
        n++;
    }
    word[n] = '\0';
    return line + n;
}

static void scan_face(LineCounts *c, const char *rest, const char *mtl)
{
    LineFace face = {.first = c->num_positions};
    snprintf(face.mtl, sizeof face.mtl, "%s", mtl);
    for (const char *p = rest; *p;) {
        char *end;
        long index = strtol(p, &end, 10);
        if (end == p)
            break;
        if (c->num_positions == c->capacity_positions) {
            c->capacity_positions = 2 * c->capacity_positions + 64;
            c->positions = realloc(c->positions, c->capacity_positions * sizeof *c->positions);
        }
        long resolved = index > 0 ? index - 1 : (long)c->v + index;
        bool repeated = false;
        for (size_t k = face.first; k < c->num_positions; k++)
            repeated = repeated || c->positions[k] == resolved;
        face.distinct_corners += !repeated;
        c->positions[c->num_positions++] = resolved;
        face.corners++;
        p = end;
        while (*p && !isspace((unsigned char)*p))
            p++;
    }
    if ((c->f & (c->f - 1)) == 0) /* grow at powers of two */
        c->faces = realloc(c->faces, 2 * (c->f + 1) * sizeof *c->faces);
    c->faces[c->f++] = face;
    c->triangles += face.corners >= 3 ? face.corners - 2 : 0;
}

static LineCounts count_lines(const char *path)
{
    LineCounts c = {0};
    FILE *file = fopen(path, "r");
    cr_assert(file, "cannot open %s", path);
    char current_mtl[128] = "";
    static char line[1 << 16];
    while (fgets(line, sizeof line, file)) {
        char word[32];
        const char *rest = first_word(line, word, sizeof word);
        if (strcmp(word, "v") == 0)
            c.v++;
        else if (strcmp(word, "vt") == 0)
            c.vt++;
        else if (strcmp(word, "vn") == 0)
            c.vn++;
        else if (strcmp(word, "usemtl") == 0)
            sscanf(rest, " %127s", current_mtl);
        else if (strcmp(word, "f") == 0)
            scan_face(&c, rest, current_mtl);
    }
    fclose(file);
    return c;
}

static void free_counts(LineCounts *c)
{
    free(c->faces);
    free(c->positions);
}

/* True when every corner of the triangle is a corner of the face. */
static bool triangle_in_face(const LineCounts *c, const LineFace *face, const int32_t *corners)
{
    for (int k = 0; k < 3; k++) {
        bool found = false;
        for (size_t i = 0; i < face->corners; i++)
            found = found || corners[3 * k] == c->positions[face->first + i];
        if (!found)
            return false;
    }
    return true;
}

/* Loads quietly; fails the test with the error message if it does not load. */
static void load_ok(const char *path, Mesh *mesh)
{
    Error err = {0};
    warnings_set_quiet(true);
    cr_assert(obj_load(path, mesh, &err), "%s: %s", path, err.message);
}

/* Every OBJ under the assets folder (two levels deep), sorted. */
static size_t list_asset_objs(char paths[][768], size_t max)
{
    size_t count = 0;
    DIR *top = opendir(ASSETS_DIR);
    cr_assert(top);
    struct dirent *folder;
    while ((folder = readdir(top))) {
        if (folder->d_name[0] == '.')
            continue;
        char dir_path[512];
        snprintf(dir_path, sizeof dir_path, "%s/%s", ASSETS_DIR, folder->d_name);
        DIR *dir = opendir(dir_path);
        if (!dir)
            continue;
        struct dirent *entry;
        while ((entry = readdir(dir)) && count < max) {
            size_t n = strlen(entry->d_name);
            if (n > 4 && strcmp(entry->d_name + n - 4, ".obj") == 0)
                snprintf(paths[count++], 768, "%s/%s", dir_path, entry->d_name);
        }
        closedir(dir);
    }
    closedir(top);
    return count;
}

/* ---- assets ------------------------------------------------------------------------------ */

/* Indices in range, and the triangle's material is the file's usemtl for its face (or the
 * default when no material of that name exists). */
static void expect_triangle_ok(const Mesh *mesh, size_t triangle, const char *usemtl,
                               const char *path)
{
    const int32_t *c = mesh->corners + 9 * triangle;
    for (int k = 0; k < 3; k++) {
        cr_assert(c[3 * k] >= 0 && (size_t)c[3 * k] < mesh->num_positions);
        cr_assert(c[3 * k + 1] >= -1 && c[3 * k + 1] < (int32_t)mesh->num_texcoords);
        cr_assert(c[3 * k + 2] >= -1 && c[3 * k + 2] < (int32_t)mesh->num_normals);
    }
    int32_t id = mesh->material_ids[triangle];
    cr_assert(id >= -1 && id < (int32_t)mesh->num_materials);
    if (id >= 0) {
        cr_expect_str_eq(mesh->materials[id].name, usemtl, "%s triangle %zu", path, triangle);
        return;
    }
    for (size_t m = 0; m < mesh->num_materials; m++)
        cr_expect_str_neq(mesh->materials[m].name, usemtl,
                          "%s triangle %zu has the default material but %s exists", path, triangle,
                          usemtl);
}

Test(obj_assets, every_obj_matches_an_independent_line_count)
{
    REQUIRE_ASSETS();
    static char paths[64][768];
    size_t count = list_asset_objs(paths, 64);
    cr_assert_geq(count, 15, "found only %zu OBJ files", count);
    for (size_t i = 0; i < count; i++) {
        Mesh mesh;
        load_ok(paths[i], &mesh);
        LineCounts lines = count_lines(paths[i]);
        cr_expect_eq(mesh.num_positions, lines.v, "%s: v", paths[i]);
        cr_expect_eq(mesh.num_texcoords, lines.vt, "%s: vt", paths[i]);
        cr_expect_eq(mesh.num_normals, lines.vn, "%s: vn", paths[i]);
        cr_expect_eq(mesh.num_faces, lines.f, "%s: f", paths[i]);
        /* Walk the faces in file order: a face gives corners - 2 triangles made of its own
         * corners; one that repeats a corner gives fewer (no zero-area triangles). */
        size_t triangle = 0, expected_triangles = 0;
        for (size_t face = 0; face < lines.f; face++) {
            const LineFace *f = &lines.faces[face];
            size_t given = 0;
            while (given + 2 < f->corners && triangle < mesh.num_triangles &&
                   triangle_in_face(&lines, f, mesh.corners + 9 * triangle)) {
                expect_triangle_ok(&mesh, triangle, f->mtl, paths[i]);
                given++;
                triangle++;
            }
            /* A repeated corner (holodeck has 4 quads like "a b b c") leaves distinct - 2. */
            cr_assert_eq(given, f->distinct_corners - 2,
                         "%s: face %zu gave %zu triangles for %zu corners", paths[i], face, given,
                         f->corners);
            expected_triangles += given;
        }
        cr_expect_eq(mesh.num_triangles, expected_triangles, "%s: triangles", paths[i]);
        free_counts(&lines);
        mesh_free(&mesh);
    }
}

Test(obj_assets, known_triangle_counts)
{
    REQUIRE_ASSETS();
    static const struct {
        const char *path;
        size_t triangles;
    } known[] = {
        {ASSETS_DIR "/cornell-box/CornellBox-Original.obj", 36},
        {ASSETS_DIR "/stanford-dragon/dragon.obj", 100000},
        {ASSETS_DIR "/skull/skull.obj", 100002},
        {ASSETS_DIR "/stanford-bunny/stanford-bunny.obj", 69451},
        {ASSETS_DIR "/spot/spot_control_mesh.obj", 372},
    };
    for (size_t i = 0; i < sizeof known / sizeof known[0]; i++) {
        Mesh mesh;
        load_ok(known[i].path, &mesh);
        cr_expect_eq(mesh.num_triangles, known[i].triangles, "%s: %zu triangles", known[i].path,
                     mesh.num_triangles);
        mesh_free(&mesh);
    }
}

Test(obj_assets, dragon_without_its_mtl_warns_and_uses_the_default_material)
{
    REQUIRE_ASSETS();
    int before = warning_count();
    Mesh mesh;
    load_ok(ASSETS_DIR "/stanford-dragon/dragon.obj", &mesh);
    cr_expect_gt(warning_count(), before, "no warning for the missing dragon.mtl");
    cr_expect_eq(mesh.num_materials, 0);
    for (size_t t = 0; t < mesh.num_triangles; t++)
        cr_assert_eq(mesh.material_ids[t], -1, "triangle %zu", t);
    mesh_free(&mesh);
}

/* Vector area (cross product / 2) of a polygon's triangles vs its Newell vector / 2: equal for
 * any triangulation with consistent orientation, planar or not. */
Test(obj_assets, spot_control_mesh_faces_keep_their_newell_area)
{
    REQUIRE_ASSETS();
    const char *path = ASSETS_DIR "/spot/spot_control_mesh.obj";
    Mesh mesh;
    load_ok(path, &mesh);
    FILE *file = fopen(path, "r");
    cr_assert(file);
    static float v[4096][3];
    size_t nv = 0, face = 0, triangle = 0, pentagons = 0;
    char line[1024];
    while (fgets(line, sizeof line, file)) {
        if (line[0] == 'v' && line[1] == ' ') {
            cr_assert(nv < 4096);
            sscanf(line + 2, "%f %f %f", &v[nv][0], &v[nv][1], &v[nv][2]);
            nv++;
            continue;
        }
        if (line[0] != 'f' || line[1] != ' ')
            continue;
        int corners[16];
        size_t n = 0;
        for (char *token = strtok(line + 2, " \t\r\n"); token && n < 16;
             token = strtok(NULL, " \t\r\n"))
            corners[n++] = atoi(token) - 1; /* v/vt: the position comes first */
        pentagons += n == 5;
        double newell[3] = {0, 0, 0};
        for (size_t i = 0; i < n; i++) {
            const float *a = v[corners[i]], *b = v[corners[(i + 1) % n]];
            newell[0] += ((double)a[1] - b[1]) * ((double)a[2] + b[2]);
            newell[1] += ((double)a[2] - b[2]) * ((double)a[0] + b[0]);
            newell[2] += ((double)a[0] - b[0]) * ((double)a[1] + b[1]);
        }
        double sum[3] = {0, 0, 0};
        for (size_t t = 0; t + 2 < n; t++, triangle++) {
            cr_assert_lt(triangle, mesh.num_triangles);
            const int32_t *c = mesh.corners + 9 * triangle;
            const float *a = mesh.positions + 3 * c[0], *b = mesh.positions + 3 * c[3],
                        *d = mesh.positions + 3 * c[6];
            double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
            double e2[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
            sum[0] += e1[1] * e2[2] - e1[2] * e2[1];
            sum[1] += e1[2] * e2[0] - e1[0] * e2[2];
            sum[2] += e1[0] * e2[1] - e1[1] * e2[0];
            for (int k = 0; k < 3; k++) { /* the triangle uses this face's corners only */
                bool found = false;
                for (size_t i = 0; i < n; i++)
                    found = found || c[3 * k] == corners[i];
                cr_expect(found, "face %zu: triangle corner %d is not a face corner", face,
                          c[3 * k]);
            }
        }
        double norm = sqrt(newell[0] * newell[0] + newell[1] * newell[1] + newell[2] * newell[2]);
        for (int k = 0; k < 3; k++)
            cr_expect(fabs(sum[k] - newell[k]) <= 1e-4 * norm,
                      "face %zu (%zu corners) axis %d: %g vs %g", face, n, k, sum[k], newell[k]);
        face++;
    }
    fclose(file);
    cr_expect_eq(face, mesh.num_faces);
    cr_expect_eq(triangle, mesh.num_triangles);
    cr_expect_eq(pentagons, 16, "the control mesh has 16 pentagons");
    mesh_free(&mesh);
}
