// SPDX-License-Identifier: MIT
/* OBJ/MTL loading (host/io/obj_loader.cc, host/io/obj_lines.c): every public asset imports with counts
 * that match an independent scan of its lines, faces are triangulated with the right area and
 * material, and each kind of bad input gives its own error naming the file and the line. */
#include <criterion/criterion.h>
#include <ctype.h>
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "io/obj_lines.h"
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
static void load_ok(const char *path, ObjMesh *mesh)
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
static void expect_triangle_ok(const ObjMesh *mesh, size_t triangle, const char *usemtl,
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
        ObjMesh mesh;
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
        obj_free(&mesh);
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
        ObjMesh mesh;
        load_ok(known[i].path, &mesh);
        cr_expect_eq(mesh.num_triangles, known[i].triangles, "%s: %zu triangles", known[i].path,
                     mesh.num_triangles);
        obj_free(&mesh);
    }
}

Test(obj_assets, dragon_without_its_mtl_warns_and_uses_the_default_material)
{
    REQUIRE_ASSETS();
    int before = warning_count();
    ObjMesh mesh;
    load_ok(ASSETS_DIR "/stanford-dragon/dragon.obj", &mesh);
    cr_expect_gt(warning_count(), before, "no warning for the missing dragon.mtl");
    cr_expect_eq(mesh.num_materials, 0);
    for (size_t t = 0; t < mesh.num_triangles; t++)
        cr_assert_eq(mesh.material_ids[t], -1, "triangle %zu", t);
    obj_free(&mesh);
}

/* Vector area (cross product / 2) of a polygon's triangles vs its Newell vector / 2: equal for
 * any triangulation with consistent orientation, planar or not. */
Test(obj_assets, spot_control_mesh_faces_keep_their_newell_area)
{
    REQUIRE_ASSETS();
    const char *path = ASSETS_DIR "/spot/spot_control_mesh.obj";
    ObjMesh mesh;
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
    obj_free(&mesh);
}

Test(obj_assets, mtl_fields_and_texture_paths)
{
    REQUIRE_ASSETS();
    ObjMesh mesh;
    load_ok(ASSETS_DIR "/cornell-box/CornellBox-Original.obj", &mesh);
    int light = -1;
    for (size_t m = 0; m < mesh.num_materials; m++)
        if (strcmp(mesh.materials[m].name, "light") == 0)
            light = (int)m;
    cr_assert_geq(light, 0);
    const ObjMaterial *l = &mesh.materials[light];
    cr_expect(l->ke[0] == 17 && l->ke[1] == 12 && l->ke[2] == 4, "Ke %g %g %g", l->ke[0], l->ke[1],
              l->ke[2]);
    cr_expect(l->kd[0] == 0.78f && l->illum == 2);
    size_t light_triangles = 0;
    for (size_t t = 0; t < mesh.num_triangles; t++)
        light_triangles += mesh.material_ids[t] == light;
    cr_expect_eq(light_triangles, 2, "the light quad gives 2 triangles");
    obj_free(&mesh);

    load_ok(ASSETS_DIR "/scrub-pine/scrubPine.obj", &mesh);
    cr_assert_eq(mesh.num_materials, 2);
    for (size_t m = 0; m < 2; m++) {
        FILE *texture = fopen(mesh.materials[m].map_kd, "rb");
        cr_expect(texture, "map_Kd %s does not resolve to a file", mesh.materials[m].map_kd);
        if (texture)
            fclose(texture);
        const char *folder = ASSETS_DIR "/scrub-pine/";
        cr_expect(strncmp(mesh.materials[m].map_kd, folder, strlen(folder)) == 0, "%s",
                  mesh.materials[m].map_kd);
    }
    obj_free(&mesh);

    /* holodeck: map_Ke carries "-mm 0 0.4"; its map_Kd still resolves. */
    load_ok(ASSETS_DIR "/holodeck/holodeck.obj", &mesh);
    bool screens = false;
    for (size_t m = 0; m < mesh.num_materials; m++) {
        screens = screens || strcmp(mesh.materials[m].name, "screens") == 0;
        if (strcmp(mesh.materials[m].name, "holodeckwirefrane") == 0)
            cr_expect_str_eq(mesh.materials[m].map_kd, ASSETS_DIR "/holodeck/wall.png");
    }
    cr_expect(screens);
    obj_free(&mesh);
}

/* ---- small files written by the tests ---------------------------------------------------- */

static const char *write_file(const char *dir, const char *name, const char *text)
{
    static char paths[8][512];
    static int slot;
    char *path = paths[slot++ % 8];
    snprintf(path, 512, "%s/%s", dir, name);
    FILE *file = fopen(path, "wb");
    cr_assert(file, "cannot write %s", path);
    fputs(text, file);
    fclose(file);
    return path;
}

/* Loading must fail with this code, naming the file and the line (0: no line to check). */
static void expect_error(const char *text, ErrorCode code, int line, const char *mentions)
{
    const char *dir = test_temp_dir();
    const char *path = write_file(dir, "bad.obj", text);
    ObjMesh mesh;
    Error err = {0};
    warnings_set_quiet(true);
    bool loaded = obj_load(path, &mesh, &err);
    cr_assert_not(loaded, "loaded:\n%s", text);
    cr_expect_eq(err.code, code, "%s instead of %s for:\n%s\nmessage: %s",
                 error_code_name(err.code), error_code_name(code), text, err.message);
    cr_expect(strstr(err.message, "bad.obj") != NULL, "message without file name: %s", err.message);
    if (line > 0) {
        char at_line[32];
        snprintf(at_line, sizeof at_line, ":%d:", line);
        cr_expect_eq(err.line, line, "line %d instead of %d: %s", err.line, line, err.message);
        cr_expect(strstr(err.message, at_line) != NULL, "message without %s: %s", at_line,
                  err.message);
    }
    if (mentions)
        cr_expect(strstr(err.message, mentions) != NULL, "message without '%s': %s", mentions,
                  err.message);
    cr_expect(strchr(err.message, '\n') == NULL, "message is not one line: %s", err.message);
    cr_expect_null(mesh.corners);
    remove(path);
    rmdir(dir);
}

#define TRIANGLE_V "v 0 0 0\nv 1 0 0\nv 0 1 0\n"

Test(obj_errors, missing_file)
{
    ObjMesh mesh;
    Error err = {0};
    cr_assert_not(obj_load("/nonexistent/folder/bad.obj", &mesh, &err));
    cr_expect_eq(err.code, ERR_FILE_MISSING);
    cr_expect(strstr(err.message, "/nonexistent/folder/bad.obj: no such file") != NULL, "%s",
              err.message);
}

Test(obj_errors, face_index_out_of_range)
{
    expect_error("# three vertices\n" TRIANGLE_V "f 1 2 99\n", ERR_OBJ_INDEX, 5, "99");
    expect_error(TRIANGLE_V "f 1 2 3\nf 0 1 2\n", ERR_OBJ_INDEX, 5, "index 0");
    expect_error(TRIANGLE_V "f -1 -2 -4\n", ERR_OBJ_INDEX, 4, "-4");
    expect_error("f -1 -2 -3\n" TRIANGLE_V, ERR_OBJ_INDEX, 1, "-1");
    expect_error(TRIANGLE_V "vt 0 0\nf 1/1 2/5 3/1\n", ERR_OBJ_INDEX, 5, "texcoord index 5");
    expect_error(TRIANGLE_V "vt 0 0\nf 1/1 2/-2 3/1\n", ERR_OBJ_INDEX, 5, "-2");
    expect_error(TRIANGLE_V "vn 0 0 1\nf 1//1 2//1 3//2\n", ERR_OBJ_INDEX, 5, "normal index 2");
    expect_error(TRIANGLE_V "vn 0 0 1\nf 1/1/1 2/1/1 3/1/1\n", ERR_OBJ_INDEX, 5, "texcoord");
}

Test(obj_errors, line_numbers_count_crlf_and_cr_line_ends)
{
    expect_error("v 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\n\r\nf 1 2 7\r\n", ERR_OBJ_INDEX, 5, "7");
    expect_error("v 0 0 0\rv 1 0 0\rv 0 1 0\rf 1 2 3\rf 1 2 8\r", ERR_OBJ_INDEX, 5, "8");
}

Test(obj_errors, non_finite_vertices)
{
    expect_error(TRIANGLE_V "v nan 0 0\nf 1 2 3\n", ERR_OBJ_NONFINITE, 4, "nan");
    expect_error("v 0 0 0\nv inf 0 0\n", ERR_OBJ_NONFINITE, 2, "inf");
    expect_error("v 0 -Infinity 0\n", ERR_OBJ_NONFINITE, 1, NULL);
    expect_error(TRIANGLE_V "v 1e99 0 0\n", ERR_OBJ_NONFINITE, 4, "1e99");
    expect_error(TRIANGLE_V "vn 0 0 NaN\n", ERR_OBJ_NONFINITE, 4, NULL);
    expect_error(TRIANGLE_V "vt 0.5 1e40\n", ERR_OBJ_NONFINITE, 4, NULL);
}

Test(obj_errors, malformed_records)
{
    expect_error(TRIANGLE_V "v abc 0 0\n", ERR_OBJ_PARSE, 4, "abc");
    expect_error("v 0 0\n", ERR_OBJ_PARSE, 1, NULL);
    expect_error(TRIANGLE_V "f 1 2 x\n", ERR_OBJ_PARSE, 4, "'x'");
    expect_error(TRIANGLE_V "f 1/ 2/ 3/\n", ERR_OBJ_PARSE, 4, NULL);
    /* tinyobjloader itself rejects a line record with index 0; the message keeps its line. */
    expect_error(TRIANGLE_V "\nl 0 1\n", ERR_OBJ_PARSE, 5, NULL);
}

Test(obj_errors, face_with_too_many_corners)
{
    static char text[32768];
    size_t used = 0;
    for (int i = 0; i < 300; i++)
        used += (size_t)snprintf(text + used, sizeof text - used, "v %d %d 0\n", i % 17, i / 17);
    used += (size_t)snprintf(text + used, sizeof text - used, "f");
    for (int i = 1; i <= 300; i++)
        used += (size_t)snprintf(text + used, sizeof text - used, " %d", i);
    snprintf(text + used, sizeof text - used, "\n");
    expect_error(text, ERR_TOO_LARGE, 301, "300");
}

/* ---- accepted quirks and details ---------------------------------------------------------- */

static void load_text(const char *text, ObjMesh *mesh, const char **path_out)
{
    const char *dir = test_temp_dir();
    const char *path = write_file(dir, "ok.obj", text);
    if (path_out)
        *path_out = path;
    load_ok(path, mesh);
    remove(path);
    rmdir(dir);
}

Test(obj_details, corners_carry_position_texcoord_normal_or_minus_one)
{
    ObjMesh mesh;
    load_text(TRIANGLE_V "vt 0 0\nvt 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\nf 3/2 2/1 1/2\nf -3 -2 -1\n",
              &mesh, NULL);
    cr_assert_eq(mesh.num_triangles, 3);
    const int32_t expected[3][9] = {{0, -1, 0, 1, -1, 0, 2, -1, 0},
                                    {2, 1, -1, 1, 0, -1, 0, 1, -1},
                                    {0, -1, -1, 1, -1, -1, 2, -1, -1}};
    for (int t = 0; t < 3; t++)
        for (int k = 0; k < 9; k++)
            cr_expect_eq(mesh.corners[9 * t + k], expected[t][k], "triangle %d value %d", t, k);
    obj_free(&mesh);
}

Test(obj_details, concave_ngon_face_is_ear_clipped)
{
    /* An L-shaped hexagon, reflex corner last: a fan from corner 0 would flip a triangle. */
    ObjMesh mesh;
    load_text("v 0 3 0\nv 0 0 0\nv 3 0 0\nv 3 1 0\nv 1 1 0\nv 1 3 0\nf 1 2 3 4 5 6\n", &mesh, NULL);
    cr_assert_eq(mesh.num_faces, 1);
    cr_assert_eq(mesh.num_triangles, 4);
    double total = 0;
    for (size_t t = 0; t < 4; t++) {
        const int32_t *c = mesh.corners + 9 * t;
        const float *a = mesh.positions + 3 * c[0], *b = mesh.positions + 3 * c[3],
                    *d = mesh.positions + 3 * c[6];
        double z = ((double)b[0] - a[0]) * ((double)d[1] - a[1]) -
                   ((double)b[1] - a[1]) * ((double)d[0] - a[0]);
        cr_expect_gt(z, 0, "triangle %zu is flipped or degenerate", t);
        total += z / 2;
    }
    cr_expect_float_eq(total, 5.0, 1e-6, "L-shape area 5, got %g", total);
    obj_free(&mesh);
}

Test(obj_details, positive_indices_may_refer_forward)
{
    /* tinyobjloader resolves positive indices after the whole file is read. */
    ObjMesh mesh;
    load_text("f 1 2 3\n" TRIANGLE_V, &mesh, NULL);
    cr_expect_eq(mesh.num_triangles, 1);
    obj_free(&mesh);
}

Test(obj_details, short_face_is_skipped_with_a_warning)
{
    int before = warning_count();
    ObjMesh mesh;
    load_text(TRIANGLE_V "f 1 2\nf 1 2 3\n", &mesh, NULL);
    cr_expect_gt(warning_count(), before);
    cr_expect_eq(mesh.num_faces, 1);
    cr_expect_eq(mesh.num_triangles, 1);
    obj_free(&mesh);
}

Test(obj_details, mtl_values_defaults_and_warnings)
{
    const char *dir = test_temp_dir();
    write_file(dir, "m.mtl",
               "newmtl glass\n  Kd 0.1 0.2 0.3\n  Ks 0.4 0.5 0.6\n  Ke 1 2 3\n  Tf 0.7 0.8 0.9\n"
               "  Ni 1.5\n  d 0.25\n  illum 7\n  map_Kd -mm 0 0.4 tex.png\n"
               "newmtl plain\n  Kd 1 1 1\n");
    const char *path = write_file(dir, "m.obj",
                                  "mtllib m.mtl\n" TRIANGLE_V "usemtl glass\nf 1 2 3\n"
                                  "usemtl plain\nf 1 2 3\nusemtl nosuch\nf 1 2 3\n");
    int before = warning_count();
    ObjMesh mesh;
    load_ok(path, &mesh);
    cr_expect_eq(warning_count(), before + 1, "one warning, for usemtl nosuch");
    cr_assert_eq(mesh.num_materials, 2);
    const ObjMaterial *glass = &mesh.materials[0], *plain = &mesh.materials[1];
    cr_expect_str_eq(glass->name, "glass");
    cr_expect(glass->kd[2] == 0.3f && glass->ks[1] == 0.5f && glass->ke[2] == 3.0f);
    cr_expect(glass->tf[0] == 0.7f && glass->ni == 1.5f && glass->d == 0.25f && glass->illum == 7);
    char texture[600];
    snprintf(texture, sizeof texture, "%s/tex.png", dir);
    cr_expect_str_eq(glass->map_kd, texture);
    cr_expect(plain->illum == -1 && plain->tf[0] == 1 && plain->ni == 1 && plain->d == 1,
              "absent illum -1, Tf 1, Ni 1, d 1");
    cr_expect_str_eq(plain->map_kd, "");
    cr_assert_eq(mesh.num_triangles, 3);
    cr_expect_eq(mesh.material_ids[0], 0);
    cr_expect_eq(mesh.material_ids[1], 1);
    cr_expect_eq(mesh.material_ids[2], -1);
    obj_free(&mesh);
    remove(path);
    remove(write_file(dir, "m.mtl", ""));
    rmdir(dir);
}

Test(obj_details, missing_mtl_is_a_warning_naming_it)
{
    const char *dir = test_temp_dir();
    const char *path =
        write_file(dir, "m.obj", "mtllib absent.mtl\n" TRIANGLE_V "usemtl red\nf 1 2 3\n");
    /* Catch what warn() prints: stderr goes to a file while loading. */
    char log_path[600];
    snprintf(log_path, sizeof log_path, "%s/stderr.txt", dir);
    fflush(stderr);
    int saved = dup(fileno(stderr));
    FILE *log = fopen(log_path, "w");
    cr_assert(log && saved >= 0);
    dup2(fileno(log), fileno(stderr));
    warnings_set_quiet(false);
    int before = warning_count();
    ObjMesh mesh;
    Error err = {0};
    bool loaded = obj_load(path, &mesh, &err);
    fflush(stderr);
    dup2(saved, fileno(stderr));
    close(saved);
    fclose(log);
    cr_assert(loaded, "%s", err.message);
    cr_expect_gt(warning_count(), before);
    char *printed = test_read_file(log_path, NULL);
    cr_assert(printed);
    cr_expect(strstr(printed, "absent.mtl") != NULL, "warnings do not name the MTL:\n%s", printed);
    for (char *line = printed; (line = strstr(line, "pt: warning: ")) != NULL; line++)
        cr_expect(strncmp(line + 13, path, strlen(path)) == 0 || strstr(line, "absent.mtl"),
                  "warning names neither the OBJ nor the MTL: %.80s", line);
    free(printed);
    cr_expect_eq(mesh.num_materials, 0);
    cr_expect_eq(mesh.material_ids[0], -1);
    obj_free(&mesh);
    remove(path);
    remove(log_path);
    rmdir(dir);
}

Test(obj_lines, find_record_counts_like_tinyobjloader)
{
    const char text[] =
        "# c\nv 0 0 0\n  v 1 0 0\r\nvt 0 0\rv 2 0 0\nf 1 2\nf 1 2 3\nvn 0 0 1\n\tf 3 2 1\n";
    size_t size = sizeof text - 1;
    cr_expect_eq(obj_lines_find_record(text, size, "v", 0), 2);
    cr_expect_eq(obj_lines_find_record(text, size, "v", 1), 3);
    cr_expect_eq(obj_lines_find_record(text, size, "v", 2), 5);
    cr_expect_eq(obj_lines_find_record(text, size, "v", 3), 0);
    cr_expect_eq(obj_lines_find_record(text, size, "vt", 0), 4);
    cr_expect_eq(obj_lines_find_record(text, size, "vn", 0), 8);
    cr_expect_eq(obj_lines_find_record(text, size, "f", 0), 7, "the 2-corner face is not counted");
    cr_expect_eq(obj_lines_find_record(text, size, "f", 1), 9);
}

/* Never crash: byte-mutated copies of a small OBJ either load with every index in range and every
 * position finite, or fail with a one-line message naming the file. */
Test(obj_errors, mutated_files_load_or_fail_cleanly)
{
    static const char original[] = "mtllib none.mtl\n# box\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                                   "vt 0 0\nvt 1 0\nvn 0 0 1\nusemtl a\nf 1/1/1 2/2/1 3/1/1 4/2/1\n"
                                   "f -4 -3 -2\nf 1//1 3//1 4//1\n";
    static const char alphabet[] = "0123456789 -+/.\n\r\tvfenai#e";
    const char *dir = test_temp_dir();
    uint32_t state = 7;
    warnings_set_quiet(true);
    for (int trial = 0; trial < 400; trial++) {
        char text[sizeof original];
        memcpy(text, original, sizeof original);
        for (int m = 0; m < 1 + trial % 4; m++) {
            state = state * 1664525u + 1013904223u;
            size_t at = (state >> 8) % (sizeof original - 1);
            state = state * 1664525u + 1013904223u;
            text[at] = alphabet[(state >> 8) % (sizeof alphabet - 1)];
        }
        const char *path = write_file(dir, "mutant.obj", text);
        ObjMesh mesh;
        Error err = {0};
        if (!obj_load(path, &mesh, &err)) {
            cr_expect_neq(err.code, ERR_NONE);
            cr_expect(strstr(err.message, "mutant.obj") && !strchr(err.message, '\n'),
                      "trial %d: %s", trial, err.message);
            continue;
        }
        for (size_t i = 0; i < 3 * mesh.num_positions; i++)
            cr_assert(isfinite(mesh.positions[i]), "trial %d:\n%s", trial, text);
        for (size_t t = 0; t < mesh.num_triangles; t++)
            for (int k = 0; k < 3; k++) {
                const int32_t *c = mesh.corners + 9 * t + 3 * k;
                cr_assert(c[0] >= 0 && (size_t)c[0] < mesh.num_positions, "trial %d", trial);
                cr_assert(c[1] >= -1 && c[1] < (int32_t)mesh.num_texcoords, "trial %d", trial);
                cr_assert(c[2] >= -1 && c[2] < (int32_t)mesh.num_normals, "trial %d", trial);
            }
        obj_free(&mesh);
    }
    remove(write_file(dir, "mutant.obj", ""));
    rmdir(dir);
}
