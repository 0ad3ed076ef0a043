// SPDX-License-Identifier: MIT
/* Hostile input to the v2 readers (issue 42) that a generated file cannot carry by itself: a FIFO
 * named by a glTF buffer or image URI (opening one to see whether it exists waited for a writer
 * forever), URIs leaving the file's folder (refused unless --allow-outside-paths), and JSON
 * nested 100,000 deep in a pt scene (one clear line, not cJSON's "malformed" at its limit). The
 * glTF memory-error cases are files: tools/gltf_hostile_cases.py, run by test_io_gltf. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "base/fs.h"
#include "io/gltf_loader.h"
#include "scene/scene.h"
#include "scene/scene_data.h"
#include "support.h"

static const char *generate(void)
{
    const char *dir = test_temp_dir();
    char command[2048];
    snprintf(command, sizeof command, "python3 tools/make_gltf_tests.py '%s' >/dev/null", dir);
    cr_assert_eq(system(command), 0, "%s failed", command);
    return dir;
}

/* features.gltf with its first `from` replaced by `to`, written as dir/name. */
static const char *features_with(const char *dir, const char *name, const char *from, const char *to)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/features.gltf", dir);
    size_t size;
    char *text = test_read_file(path, &size);
    char *at = strstr(text, from);
    cr_assert(at, "features.gltf has no %s", from);
    size_t out_size = size + strlen(to) + 1;
    char *out = malloc(out_size);
    snprintf(out, out_size, "%.*s%s%s", (int)(at - text), text, to, at + strlen(from));
    const char *written = test_write_file(dir, name, out);
    free(text);
    free(out);
    return written;
}

static void expect_refused(const char *path, const char *needle)
{
    Scene s;
    Error err = {0};
    cr_assert_not(scene_load(path, &s, &err), "%s loaded", path);
    cr_expect(strstr(err.message, needle) && !strchr(err.message, '\n'),
              "\"%s\" should name \"%s\" on one line", err.message, needle);
}

Test(hostile_readers, gltf_fifo_uris_are_refused_without_waiting, .timeout = 120)
{
    const char *dir = generate();
    char fifo[1024];
    snprintf(fifo, sizeof fifo, "%s/pipe.bin", dir);
    cr_assert_eq(mkfifo(fifo, 0600), 0);
    expect_refused(features_with(dir, "fifo_buffer.gltf", "\"features.bin\"", "\"pipe.bin\""),
                   "buffers[0].uri \"");
    /* A FIFO image used by a material: the texture reader refuses it by name. */
    const char *image = features_with(dir, "fifo_image.gltf", "\"asset\": {",
                                      "\"images\": [{\"uri\": \"pipe.bin\"}], \"textures\": "
                                      "[{\"source\": 0}], \"asset\": {");
    char *text = test_read_file(image, NULL);
    char *pbr = strstr(text, "\"pbrMetallicRoughness\": {");
    cr_assert(pbr);
    pbr += strlen("\"pbrMetallicRoughness\": {");
    char *used = malloc(strlen(text) + 64);
    sprintf(used, "%.*s\"baseColorTexture\": {\"index\": 0}, %s", (int)(pbr - text), text, pbr);
    expect_refused(test_write_file(dir, "fifo_texture.gltf", used), "pipe.bin");
    free(used);
    free(text);
}

Test(hostile_readers, gltf_uris_stay_in_the_folder_unless_allowed, .timeout = 120)
{
    const char *dir = generate();
    const char *slash = strrchr(dir, '/');
    char escaping[1200];
    snprintf(escaping, sizeof escaping, "\"../%s/features.bin\"", slash + 1);
    const char *path = features_with(dir, "outside.gltf", "\"features.bin\"", escaping);
    expect_refused(path, "buffers[0].uri \"../");
    fs_set_allow_outside_paths(true);
    Scene s;
    Error err = {0};
    bool ok = scene_load(path, &s, &err);
    fs_set_allow_outside_paths(false);
    cr_assert(ok, "with --allow-outside-paths: %s", err.message);
    scene_free(&s);
}

Test(hostile_readers, json_scene_nested_too_deep_is_one_clear_line)
{
    const char *dir = test_temp_dir();
    size_t depth = 100000, size = 2 * depth + 64;
    char *text = malloc(size);
    int n = sprintf(text, "{\"version\": 2, \"x\": ");
    memset(text + n, '[', depth);
    memset(text + n + depth, ']', depth);
    strcpy(text + n + 2 * depth, "}");
    const char *path = test_write_file(dir, "deep.json", text);
    free(text);
    expect_refused(path, "deep.json:1: JSON nested more than 1000 levels deep");
}

/* 10^5 nodes placing one mesh, and 10^5 primitives in one mesh, load (they took minutes: every
 * object grew the scene's arrays by its own size, O(n^2) bytes copied), and the arrays grow
 * geometrically: at most ~log2(n) reallocations, counted, not timed. */
static void load_many(const char *kind, Scene *s)
{
    const char *dir = test_temp_dir();
    char command[2048], path[1024];
    snprintf(path, sizeof path, "%s/many_%s.glb", dir, kind);
    snprintf(command, sizeof command, "python3 tools/gltf_hostile_cases.py %s 100000 '%s'", kind, path);
    cr_assert_eq(system(command), 0, "%s failed", command);
    Error err = {0};
    cr_assert(scene_load(path, s, &err), "%s", err.message);
}

Test(hostile_readers, gltf_with_1e5_nodes_or_primitives_loads, .timeout = 600)
{
    Scene s;
    load_many("nodes", &s);
    cr_expect_eq(s.data.num_instances, 100000);
    scene_free(&s);
    load_many("primitives", &s);
    cr_expect_eq(s.data.num_triangles, 100000);
    scene_free(&s);
}

Test(hostile_readers, scene_arrays_grow_geometrically)
{
    SceneData data;
    scene_data_init(&data);
    int grew[3] = {0, 0, 0};
    float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    int32_t corners[9] = {0, -1, -1, 1, -1, -1, 2, -1, -1}, material = -1;
    Mesh mesh = {.positions = positions, .num_positions = 3, .corners = corners,
                 .material_ids = &material, .num_triangles = 1, .num_faces = 1};
    for (int i = 0; i < 100000; i++) {
        size_t before[3] = {data.vertex_capacity, data.mesh_capacity, data.instance_capacity};
        uint32_t first_triangle = data.num_triangles, first_vertex = data.num_vertices;
        Error err = {0};
        SceneInstance inst = {.mesh = data.num_meshes, .object = i, .to_world = affine_identity()};
        cr_assert(scene_data_append_mesh(&data, &mesh, "tri", &err) &&
                  scene_data_add_mesh(&data, first_triangle, first_vertex, &err) &&
                  scene_data_add_instance(&data, &inst, &err), "%s", err.message);
        size_t after[3] = {data.vertex_capacity, data.mesh_capacity, data.instance_capacity};
        for (int k = 0; k < 3; k++)
            grew[k] += after[k] != before[k];
    }
    for (int k = 0; k < 3; k++)
        cr_expect_leq(grew[k], 40, "array %d reallocated %d times for 100000 objects", k, grew[k]);
    cr_expect_geq(data.triangle_capacity, data.num_triangles);
    scene_data_free(&data);
}

/* A POINTS or LINES primitive is skipped (one warning) and the triangles render: the quad of
 * the features file (meshes[1], 2 triangles, placed once) as LINES leaves 2 triangles fewer. */
Test(hostile_readers, gltf_lines_primitive_is_skipped_not_refused, .timeout = 120)
{
    const char *dir = generate();
    Scene all, lines;
    Error err = {0};
    char path[1024];
    snprintf(path, sizeof path, "%s/features.gltf", dir);
    cr_assert(scene_load(path, &all, &err), "%s", err.message);
    const char *skipped = features_with(dir, "lines.gltf", "\"indices\": 5,",
                                        "\"mode\": 1, \"indices\": 5,");
    cr_assert(scene_load(skipped, &lines, &err), "%s", err.message);
    cr_expect_eq(lines.data.num_triangles + 2, all.data.num_triangles);
    scene_free(&all);
    scene_free(&lines);
}

/* The warnings of scene_load(path) (stderr captured), or NULL when it fails. */
static char *load_warnings(const char *dir, const char *path)
{
    char log[1024];
    snprintf(log, sizeof log, "%s/stderr.txt", dir);
    fflush(stderr);
    int saved = dup(2), fd = open(log, O_WRONLY | O_CREAT | O_TRUNC, 0600);
    cr_assert(saved >= 0 && fd >= 0);
    dup2(fd, 2);
    close(fd);
    Scene s;
    Error err = {0};
    bool ok = scene_load(path, &s, &err);
    fflush(stderr);
    dup2(saved, 2);
    close(saved);
    cr_assert(ok, "%s", err.message);
    scene_free(&s);
    return test_read_file(log, NULL);
}

static int count(const char *text, const char *needle)
{
    int n = 0;
    for (const char *at = text; (at = strstr(at, needle)); at++)
        n++;
    return n;
}

/* Skins, morph targets, animations and orthographic cameras: one warning each (none --quiet). */
Test(hostile_readers, gltf_dropped_features_warn_once_each, .timeout = 120)
{
    const char *dir = generate();
    const char *path = features_with(dir, "dropped.gltf", "\"asset\": {",
                                     "\"skins\": [{\"joints\": [0]}, {\"joints\": [1]}], "
                                     "\"animations\": [{\"channels\": [], \"samplers\": []}], "
                                     "\"asset\": {");
    char *text = test_read_file(path, NULL);
    char *more = malloc(strlen(text) + 256);
    char *cams = strstr(text, "\"cameras\": [");
    cr_assert(cams);
    cams += strlen("\"cameras\": [");
    sprintf(more, "%.*s{\"type\": \"orthographic\", \"orthographic\": {\"xmag\": 1, \"ymag\": 1, "
            "\"znear\": 0.1, \"zfar\": 10}}, %s", (int)(cams - text), text, cams);
    char *weights = strstr(more, "\"primitives\": [");
    cr_assert(weights);
    const char *insert = "\"weights\": [0.5], ";
    memmove(weights + strlen(insert), weights, strlen(weights) + 1);
    memcpy(weights, insert, strlen(insert));
    path = test_write_file(dir, "dropped.gltf", more);
    free(more);
    free(text);
    char *warnings = load_warnings(dir, path);
    const char *features[] = {"skins: pt ignores 2 skins", "morph targets: pt ignores those of 1 mesh",
                              "animations: pt ignores 1 animation", "cameras: pt ignores 1 orthographic"};
    for (int i = 0; i < 4; i++)
        cr_expect_eq(count(warnings, features[i]), 1, "\"%s\" once in:\n%s", features[i], warnings);
    free(warnings);
    gltf_loader_set_quiet(true);
    warnings = load_warnings(dir, path);
    gltf_loader_set_quiet(false);
    cr_expect_eq(count(warnings, "pt ignores"), 0, "--quiet:\n%s", warnings);
    free(warnings);
}
