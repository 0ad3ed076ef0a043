// SPDX-License-Identifier: MIT
/* Grid media from NanoVDB files through the scene format (host/scene/media_json.c, media_load.c;
 * the reader is io/volume_nvdb.cc): the grid by name or the file's first float grid, the grid's
 * own index-to-world map then the medium's transform, and a grid the file does not hold (or of
 * another value type) refused in one line naming media.NAME.grid. Files from tests/nvdb_fixture.cc
 * (NanoVDB's own writer). */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "nvdb_fixture.h"
#include "scene/scene.h"
#include "support.h"

static const char *dir;

static const char *write_scene(const char *media)
{
    char text[4096];
    snprintf(text, sizeof text,
             "{\"camera\": {\"eye\": [0, 0, 9], \"target\": [0, 0, 0]}, \"media\": {%s}, "
             "\"objects\": [{\"obj\": \"tri.obj\"}]}",
             media);
    test_write_file(dir, "tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    return test_write_file(dir, "scene.json", text);
}

static void setup(void)
{
    dir = test_temp_dir();
    char path[512];
    snprintf(path, sizeof path, "%s/mixed.nvdb", dir);
    cr_assert(nvdb_fixture_write_mixed(path)); /* "temperature" (double), "density", "flame" */
    snprintf(path, sizeof path, "%s/sphere.nvdb", dir);
    static const double centre[3] = {0, 0, 0}, origin[3] = {0, 0, 0};
    cr_assert(nvdb_fixture_write_sphere(path, "density", 2.0f, centre, 0.25, origin));
}

TestSuite(media_scene_nvdb, .init = setup);

Test(media_scene_nvdb, grid_by_name_and_the_first_float_grid)
{
    Scene s;
    Error err = {0};
    cr_assert(scene_load(write_scene("\"a\": {\"type\": \"grid\", \"file\": \"mixed.nvdb\", "
                                     "\"grid\": \"flame\"}, \"b\": {\"type\": \"grid\", \"file\": "
                                     "\"mixed.nvdb\"}, \"c\": {\"type\": \"grid\", \"file\": "
                                     "\"mixed.nvdb\", \"grid\": \"density\"}"),
                         &s, &err),
              "%s", err.message);
    cr_assert_eq(s.data.num_media, 3);
    const Medium *flame = &s.data.media[0], *first = &s.data.media[1], *density = &s.data.media[2];
    cr_expect_eq(flame->type, MEDIUM_GRID);
    /* "flame" is one active voxel of 2.5 (nvdb_fixture.cc): the named grid, not the first. */
    cr_expect_eq(flame->sigma_s.s[3], 2.5f, "flame's largest density");
    cr_expect(flame->res_x == 1 && flame->res_y == 1 && flame->res_z == 1, "flame: one voxel");
    /* No name: the first float grid, "density" (the double "temperature" before it is skipped). */
    cr_expect_eq(first->sigma_s.s[3], density->sigma_s.s[3], "the first float grid is density");
    cr_expect(first->res_x == density->res_x && first->res_y == density->res_y &&
                  first->res_z == density->res_z, "the first float grid is density");
    cr_expect_neq(first->sigma_s.s[3], 2.5f, "not flame");
    scene_free(&s);
}

Test(media_scene_nvdb, the_grids_own_map_then_the_transform)
{
    Scene s;
    Error err = {0};
    cr_assert(scene_load(write_scene("\"s\": {\"type\": \"grid\", \"file\": \"sphere.nvdb\", "
                                     "\"transform\": [{\"translate\": [1, 0, 0]}]}"),
                         &s, &err),
              "%s", err.message);
    /* The file's voxels are 0.25 apart (4 index units per world unit); the transform moves the
     * grid by +1 in x, so world x 1 is where the file's x 0 was. */
    const Medium *m = &s.data.media[0];
    float a = m->to_index[0].s[0] * 1.0f + m->to_index[0].s[3];
    float b = m->to_index[0].s[0] * 2.0f + m->to_index[0].s[3];
    cr_expect(fabsf((b - a) - 4.0f) < 1e-4f, "4 voxels per world unit: %g", b - a);
    Scene plain;
    cr_assert(scene_load(write_scene("\"s\": {\"type\": \"grid\", \"file\": \"sphere.nvdb\"}"),
                         &plain, &err),
              "%s", err.message);
    const Medium *p = &plain.data.media[0];
    float c = p->to_index[0].s[0] * 0.0f + p->to_index[0].s[3];
    cr_expect(fabsf(a - c) < 1e-4f, "the transform moved the grid by 1 in x (%g against %g)", a, c);
    scene_free(&plain);
    scene_free(&s);
}

Test(media_scene_nvdb, a_grid_not_in_the_file_names_the_grid_key)
{
    Scene s;
    Error err = {0};
    cr_assert(!scene_load(write_scene("\"smoke\": {\"type\": \"grid\", \"file\": \"mixed.nvdb\", "
                                      "\"grid\": \"soot\"}"),
                          &s, &err));
    cr_expect(strstr(err.message, "media.smoke.grid: ") && strstr(err.message, "soot"), "%s",
              err.message);
    cr_expect(!strchr(err.message, '\n'));
    err = (Error){0};
    cr_assert(!scene_load(write_scene("\"smoke\": {\"type\": \"grid\", \"file\": \"mixed.nvdb\", "
                                      "\"grid\": \"temperature\"}"),
                          &s, &err));
    cr_expect(strstr(err.message, "media.smoke.grid: "), "a double grid: %s", err.message);
}

Test(media_scene_nvdb, a_corrupt_file_names_the_file_key)
{
    Scene s;
    Error err = {0};
    test_write_file(dir, "bad.nvdb", "NanoVDB0 but nothing more");
    cr_assert(!scene_load(write_scene("\"smoke\": {\"type\": \"grid\", \"file\": \"bad.nvdb\"}"),
                          &s, &err));
    cr_expect(strstr(err.message, "media.smoke.file: ") && strstr(err.message, "bad.nvdb"), "%s",
              err.message);
}
