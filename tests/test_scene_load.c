// SPDX-License-Identifier: MIT
/* Scene descriptions (host/scene/scene.c): every kind of bad JSON gives its own error naming the key (or
 * the line), good scenes parse with the documented defaults, a bare .obj and a folder with
 * scene.json load, the framed camera sees the whole object, and every public OBJ imports. */
#include <criterion/criterion.h>
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "scene/camera.h"
#include "scene/scene.h"
#include "support.h"

static char g_dir[64];

/* Writes name in a temporary folder made on first use (g_dir). */
static const char *write_file(const char *name, const char *text)
{
    if (!g_dir[0])
        snprintf(g_dir, sizeof g_dir, "%s", test_temp_dir());
    return test_write_file(g_dir, name, text);
}

/* Loads `json` as a scene file and checks the error code and that the message holds `needle`. */
static Error expect_error(const char *json, ErrorCode code, const char *needle)
{
    const char *path = write_file("bad.json", json);
    SceneDesc desc;
    Error err = {0};
    bool ok = scene_desc_load(path, &desc, &err);
    cr_expect_not(ok, "accepted: %s", json);
    if (ok)
        scene_desc_free(&desc);
    cr_expect_eq(err.code, code, "%s instead of %s for: %s (%s)", error_code_name(err.code),
                 error_code_name(code), json, err.message);
    cr_expect(strstr(err.message, needle) != NULL, "message \"%s\" lacks \"%s\"", err.message, needle);
    cr_expect(strstr(err.message, "bad.json") != NULL, "message names the file: %s", err.message);
    return err;
}

#define OBJECTS "\"objects\": [{\"obj\": \"box.obj\"}]"
#define CAMERA "\"camera\": {\"eye\": [0, 1, 4], \"target\": [0, 1, 0]}"

Test(scene, missing_file_and_folder_without_scene_json)
{
    SceneDesc desc;
    Error err = {0};
    cr_expect_not(scene_desc_load("/nonexistent/scene.json", &desc, &err));
    cr_expect_eq(err.code, ERR_FILE_MISSING);
    cr_expect(strstr(err.message, "/nonexistent/scene.json"), "%s", err.message);
    const char *folder = test_temp_dir();
    Error err2 = {0};
    cr_expect_not(scene_desc_load(folder, &desc, &err2));
    cr_expect_eq(err2.code, ERR_FILE_MISSING);
    cr_expect(strstr(err2.message, "scene.json"), "%s", err2.message);
}

Test(scene, malformed_json_reports_its_line)
{
    Error err = expect_error("{\n  " CAMERA ",\n  \"film\": {\"width\": 4x0},\n  " OBJECTS "\n}\n",
                             ERR_JSON_SYNTAX, "bad.json:3:");
    cr_expect_eq(err.line, 3);
    err = expect_error("{\n  \"background\": [0, 0, ],\n  " OBJECTS "\n}\n", ERR_JSON_SYNTAX,
                       "bad.json:2:");
    cr_expect_eq(err.line, 2);
    err = expect_error("{\n  " OBJECTS "\n}\n}\n", ERR_JSON_SYNTAX, "bad.json:4:");
    expect_error("", ERR_JSON_SYNTAX, "bad.json:1:");
    expect_error("{\n  " OBJECTS ",\n  " OBJECTS "\n}\n", ERR_JSON_SYNTAX, "objects");
}

Test(scene, unknown_keys_are_named_with_their_path)
{
    Error err = expect_error("{\n  " OBJECTS ",\n  \"camera\": {\"eye\": [0, 1, 4],\n"
                             "    \"fov\": 40, \"target\": [0, 0, 0]}\n}\n",
                             ERR_JSON_UNKNOWN_KEY, "camera.fov");
    cr_expect_eq(err.line, 4, "line of the key: %d", err.line);
    expect_error("{" OBJECTS ", \"camra\": {}}", ERR_JSON_UNKNOWN_KEY, "camra");
    expect_error("{" OBJECTS ", \"film\": {\"depth\": 3}}", ERR_JSON_UNKNOWN_KEY, "film.depth");
    expect_error("{" OBJECTS ", \"render\": {\"samples\": 3}}", ERR_JSON_UNKNOWN_KEY, "render.samples");
    expect_error("{\"objects\": [{\"obj\": \"a.obj\"}, {\"file\": \"b.obj\"}]}", ERR_JSON_UNKNOWN_KEY,
                 "objects[1].file");
    expect_error("{" OBJECTS ", \"Camera\": {}}", ERR_JSON_UNKNOWN_KEY, "Camera");
}

Test(scene, wrong_types_name_the_key)
{
    expect_error("{" OBJECTS ", \"camera\": {\"eye\": [0, 1, 4], \"target\": [0, 0, 0], \"fov_y\": \"40\"}}",
                 ERR_JSON_TYPE, "camera.fov_y");
    expect_error("{" OBJECTS ", \"camera\": {\"eye\": [0, 1], \"target\": [0, 0, 0]}}", ERR_JSON_TYPE,
                 "camera.eye");
    expect_error("{" OBJECTS ", \"camera\": {\"eye\": [0, 1, 4], \"target\": [0, \"0\", 0]}}",
                 ERR_JSON_TYPE, "camera.target");
    expect_error("{" OBJECTS ", \"camera\": [0, 1, 4]}", ERR_JSON_TYPE, "camera");
    expect_error("{" OBJECTS ", \"film\": {\"width\": 512.5}}", ERR_JSON_TYPE, "film.width");
    expect_error("{" OBJECTS ", \"render\": {\"spp\": \"64\"}}", ERR_JSON_TYPE, "render.spp");
    expect_error("{" OBJECTS ", \"render\": {\"max_depth\": true}}", ERR_JSON_TYPE, "render.max_depth");
    expect_error("{" OBJECTS ", \"background\": [1, 1]}", ERR_JSON_TYPE, "background");
    expect_error("{\"objects\": {\"obj\": \"box.obj\"}}", ERR_JSON_TYPE, "objects");
    expect_error("{\"objects\": [\"box.obj\"]}", ERR_JSON_TYPE, "objects[0]");
    expect_error("{\"objects\": [{\"obj\": 3}]}", ERR_JSON_TYPE, "objects[0].obj");
    expect_error("[1, 2, 3]", ERR_JSON_TYPE, "top level");
}

Test(scene, values_out_of_range_name_key_and_value)
{
#define CAM(extra) "{" OBJECTS ", \"camera\": {\"eye\": [0, 1, 4], \"target\": [0, 1, 0]" extra "}}"
    expect_error(CAM(", \"fov_y\": 180"), ERR_JSON_VALUE, "camera.fov_y: 180");
    expect_error(CAM(", \"fov_y\": 0"), ERR_JSON_VALUE, "camera.fov_y: 0");
    expect_error(CAM(", \"fov_y\": -20"), ERR_JSON_VALUE, "camera.fov_y: -20");
    expect_error(CAM(", \"fov_y\": 1e999"), ERR_JSON_VALUE, "camera.fov_y: inf");
    expect_error(CAM(", \"aperture\": -0.5"), ERR_JSON_VALUE, "camera.aperture: -0.5");
    expect_error(CAM(", \"focus_distance\": -1"), ERR_JSON_VALUE, "camera.focus_distance: -1");
    expect_error(CAM(", \"up\": [0, 0, -2]"), ERR_JSON_VALUE, "camera.up: [0, 0, -2]");
    expect_error(CAM(", \"up\": [0, 0, 0]"), ERR_JSON_VALUE, "camera.up");
#undef CAM
    expect_error("{" OBJECTS ", \"camera\": {\"eye\": [0, 1, 1e40], \"target\": [0, 1, 0]}}",
                 ERR_JSON_VALUE, "camera.eye");
    expect_error("{" OBJECTS ", \"camera\": {\"eye\": [1, 2, 3], \"target\": [1, 2, 3]}}",
                 ERR_JSON_VALUE, "camera.target: [1, 2, 3]");
    expect_error("{" OBJECTS ", \"camera\": {\"target\": [1, 2, 3]}}", ERR_JSON_VALUE, "camera.eye");
    expect_error("{" OBJECTS ", \"film\": {\"width\": 0}}", ERR_JSON_VALUE, "film.width: 0");
    expect_error("{" OBJECTS ", \"film\": {\"height\": -3}}", ERR_JSON_VALUE, "film.height: -3");
    expect_error("{" OBJECTS ", \"render\": {\"spp\": 0}}", ERR_JSON_VALUE, "render.spp: 0");
    expect_error("{" OBJECTS ", \"render\": {\"max_depth\": 0}}", ERR_JSON_VALUE, "render.max_depth: 0");
    expect_error("{" OBJECTS ", \"render\": {\"sampler\": \"halton\"}}", ERR_JSON_VALUE, "render.sampler");
    expect_error("{" OBJECTS ", \"render\": {\"sampler\": 1}}", ERR_JSON_TYPE, "render.sampler");
    expect_error("{" OBJECTS ", \"render\": {\"spp\": 1e12}}", ERR_JSON_VALUE, "render.spp");
    expect_error("{" OBJECTS ", \"background\": [0, -1, 0]}", ERR_JSON_VALUE, "background");
    expect_error("{" CAMERA ", \"objects\": []}", ERR_JSON_VALUE, "objects: empty");
    expect_error("{" CAMERA "}", ERR_JSON_VALUE, "objects: empty");
    expect_error("{\"objects\": [{}]}", ERR_JSON_VALUE, "objects[0].obj");
}

Test(scene, good_scene_parses_with_defaults)
{
    const char *full = write_file("full.json",
        "{\n"
        "  \"camera\": {\"eye\": [1, 2, 3], \"target\": [0, 1, -1], \"up\": [0, 0, 1],\n"
        "             \"fov_y\": 55.5, \"aperture\": 0.1, \"focus_distance\": 2.5},\n"
        "  \"film\": {\"width\": 320, \"height\": 200},\n"
        "  \"render\": {\"spp\": 16, \"max_depth\": 3},\n"
        "  \"objects\": [{\"obj\": \"meshes/a.obj\"}, {\"obj\": \"/abs/b.obj\"}],\n"
        "  \"background\": [0.5, 0.25, 2]\n"
        "}\n");
    SceneDesc d;
    Error err = {0};
    cr_assert(scene_desc_load(full, &d, &err), "%s", err.message);
    cr_expect(d.camera_given);
    cr_expect_eq(d.camera.eye[1], 2.0f);
    cr_expect_eq(d.camera.target[2], -1.0f);
    cr_expect_eq(d.camera.up[2], 1.0f);
    cr_expect_eq(d.camera.fov_y, 55.5f);
    cr_expect_eq(d.camera.aperture, 0.1f);
    cr_expect_eq(d.camera.focus_distance, 2.5f);
    cr_expect_eq(d.width, 320);
    cr_expect_eq(d.height, 200);
    cr_expect_eq(d.spp, 16);
    cr_expect_eq(d.max_depth, 3);
    cr_expect_eq(d.background[2], 2.0f);
    cr_assert_eq(d.num_objects, 2);
    char expected[600];
    snprintf(expected, sizeof expected, "%s/meshes/a.obj", g_dir);
    cr_expect_str_eq(d.objects[0], expected, "relative to the scene file's folder");
    cr_expect_str_eq(d.objects[1], "/abs/b.obj");
    cr_expect_str_eq(d.path, full);
    scene_desc_free(&d);

    const char *minimal = write_file("minimal.json", "{" CAMERA ", " OBJECTS "}");
    cr_assert(scene_desc_load(minimal, &d, &err), "%s", err.message);
    cr_expect(d.camera_given);
    cr_expect_eq(d.camera.fov_y, 40.0f);
    cr_expect_eq(d.camera.aperture, 0.0f);
    cr_expect_eq(d.camera.focus_distance, 0.0f);
    cr_expect(d.camera.up[0] == 0.0f && d.camera.up[1] == 1.0f && d.camera.up[2] == 0.0f);
    cr_expect_eq(d.width, 512);
    cr_expect_eq(d.height, 512);
    cr_expect_eq(d.spp, 64);
    cr_expect_eq(d.max_depth, 8);
    cr_expect(d.background[0] == 0.0f && d.background[1] == 0.0f && d.background[2] == 0.0f);
    scene_desc_free(&d);

    const char *no_camera = write_file("nocam.json", "{" OBJECTS "}");
    cr_assert(scene_desc_load(no_camera, &d, &err), "%s", err.message);
    cr_expect_not(d.camera_given, "no camera: framed on the bounds like a bare OBJ");
    scene_desc_free(&d);
}

Test(scene, bare_obj_is_one_object_without_camera)
{
    const char *obj = write_file("tri.OBJ", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    SceneDesc d;
    Error err = {0};
    cr_assert(scene_desc_load(obj, &d, &err), "%s", err.message);
    cr_expect_not(d.camera_given);
    cr_assert_eq(d.num_objects, 1);
    cr_expect_str_eq(d.objects[0], obj);
    cr_expect_eq(d.spp, 64);
    scene_desc_free(&d);
}

/* True when point p projects inside the camera's frame (with its aspect ratio). */
static bool in_view(const Camera *cam, const float p[3])
{
    float d[3] = {p[0] - cam->eye.s[0], p[1] - cam->eye.s[1], p[2] - cam->eye.s[2]};
    float z = d[0] * cam->forward.s[0] + d[1] * cam->forward.s[1] + d[2] * cam->forward.s[2];
    float x = d[0] * cam->right.s[0] + d[1] * cam->right.s[1] + d[2] * cam->right.s[2];
    float y = d[0] * cam->up.s[0] + d[1] * cam->up.s[1] + d[2] * cam->up.s[2];
    float tan_half = cam->up.s[3], aspect = cam->forward.s[3];
    return z > 0.0f && fabsf(y) <= tan_half * z && fabsf(x) <= tan_half * aspect * z;
}

Test(scene, bare_obj_gets_a_camera_that_sees_all_of_it)
{
    REQUIRE_ASSETS();
    Scene scene;
    Error err = {0};
    cr_assert(scene_load(ASSETS_DIR "/cornell-box/CornellBox-Original.obj", &scene, &err), "%s",
              err.message);
    cr_expect_not(scene.desc.camera_given);
    Camera cam = camera_from_desc(&scene.desc.camera, scene.desc.width, scene.desc.height);
    const float *lo = scene.data.bounds_min, *hi = scene.data.bounds_max;
    cr_expect(lo[0] < -1.0f && hi[0] >= 1.0f && lo[1] == 0.0f && hi[1] > 1.98f, "bounds");
    for (int i = 0; i < 8; i++) {
        float corner[3] = {i & 1 ? hi[0] : lo[0], i & 2 ? hi[1] : lo[1], i & 4 ? hi[2] : lo[2]};
        cr_expect(in_view(&cam, corner), "corner %d (%g, %g, %g) outside the view", i,
                  (double)corner[0], (double)corner[1], (double)corner[2]);
    }
    scene_free(&scene);
}

Test(scene, folder_loads_scene_json_and_its_camera_fills_the_frame_with_the_box)
{
    Scene scene;
    Error err = {0};
    cr_assert(scene_load("scenes/cornell-box", &scene, &err), "%s", err.message);
    cr_expect_str_eq(scene.desc.path, "scenes/cornell-box/scene.json");
    cr_expect(scene.desc.camera_given);
    cr_expect_eq(scene.data.num_triangles, 36, "CornellBox-Original");
    cr_expect_eq(scene.data.num_emissive, 2);
    /* The front opening (z = 0.99) is inside the view, and the view is not much larger. */
    Camera cam = camera_from_desc(&scene.desc.camera, scene.desc.width, scene.desc.height);
    const float *lo = scene.data.bounds_min, *hi = scene.data.bounds_max;
    for (int i = 0; i < 4; i++) {
        float corner[3] = {i & 1 ? hi[0] : lo[0], i & 2 ? hi[1] : lo[1], hi[2]};
        cr_expect(in_view(&cam, corner), "front corner %d outside the view", i);
        float grown[3] = {corner[0] * 1.1f, 1.0f + (corner[1] - 1.0f) * 1.1f, corner[2]};
        cr_expect_not(in_view(&cam, grown), "front corner %d grown by 10%% still inside", i);
    }
    scene_free(&scene);
    const char *others[] = {"scenes/cornell-box/sphere.json", "scenes/cornell-box/mirror.json"};
    for (int i = 0; i < 2; i++) {
        Error e = {0};
        cr_expect(scene_load(others[i], &scene, &e), "%s", e.message);
        if (!error_is_set(&e)) {
            cr_expect_gt(scene.data.num_emissive, 0, "%s has a light", others[i]);
            scene_free(&scene);
        }
    }
}

static bool has_suffix(const char *name, const char *suffix)
{
    size_t n = strlen(name), s = strlen(suffix);
    return n >= s && strcmp(name + n - s, suffix) == 0;
}

Test(scene, every_public_obj_imports, .timeout = 60)
{
    REQUIRE_ASSETS();
    warnings_set_quiet(true);
    DIR *assets = opendir(ASSETS_DIR);
    cr_assert(assets);
    int found = 0, imported = 0;
    struct dirent *folder;
    while ((folder = readdir(assets))) {
        char folder_path[512];
        snprintf(folder_path, sizeof folder_path, ASSETS_DIR "/%s", folder->d_name);
        DIR *dir = folder->d_name[0] != '.' ? opendir(folder_path) : NULL;
        struct dirent *file;
        while (dir && (file = readdir(dir))) {
            if (!has_suffix(file->d_name, ".obj"))
                continue;
            found++;
            char path[1024];
            snprintf(path, sizeof path, "%s/%s", folder_path, file->d_name);
            Scene scene;
            Error err = {0};
            bool ok = scene_load(path, &scene, &err);
            cr_expect(ok, "%s: %s", path, err.message);
            if (ok) {
                cr_expect_gt(scene.data.num_triangles, 0, "%s", path);
                scene_free(&scene);
                imported++;
            }
        }
        if (dir)
            closedir(dir);
    }
    closedir(assets);
    cr_expect_eq(imported, found, "imported %d of %d OBJs", imported, found);
    cr_expect_geq(found, 19, "the assets hold 19 OBJs");
}

/* A camera far out (1e30) is named as too far out, not as "up is parallel to the view direction"
 * (the float view direction overflowed); "parallel" is kept for an up that is parallel. */
Test(scene, absurd_camera_coordinates_name_key_and_value)
{
    Error err = expect_error("{" OBJECTS ", \"camera\": {\"eye\": [0, 1, 1e30], \"target\": [0, 1, 0]}}",
                             ERR_JSON_VALUE, "camera.eye");
    cr_expect(strstr(err.message, "1e+30") && strstr(err.message, "too large"), "%s", err.message);
    cr_expect(!strstr(err.message, "parallel"), "%s", err.message);
    err = expect_error("{" OBJECTS ", \"camera\": {\"eye\": [0, 1, 4], \"target\": [-2e16, 1, 0]}}",
                       ERR_JSON_VALUE, "camera.target");
    cr_expect(strstr(err.message, "too large"), "%s", err.message);
    err = expect_error("{" OBJECTS ", \"camera\": {\"eye\": [0, 1, 4], \"target\": [0, 1, 0], \"up\": [0, 1e20, 0]}}",
                       ERR_JSON_VALUE, "camera.up");
    cr_expect(strstr(err.message, "too large"), "%s", err.message);
    /* Large but within the limit, and not parallel: accepted. */
    const char *path = write_file("far.json", "{" OBJECTS ", \"camera\": {\"eye\": [0, 1, 1e14], \"target\": [0, 1, 0]}}");
    write_file("box.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    SceneDesc desc;
    Error ok_err = {0};
    cr_expect(scene_desc_load(path, &desc, &ok_err), "%s", ok_err.message);
    if (!error_is_set(&ok_err))
        scene_desc_free(&desc);
    /* Parallel is still parallel. */
    err = expect_error("{" OBJECTS ", \"camera\": {\"eye\": [0, 1e14, 0], \"target\": [0, 1, 0]}}",
                       ERR_JSON_VALUE, "camera.up");
    cr_expect(strstr(err.message, "parallel"), "%s", err.message);
}

/* One depth limit for the scene file and the command line (the file took up to INT_MAX). */
Test(scene, max_depth_has_the_command_lines_limit)
{
    char json[256];
    snprintf(json, sizeof json, "{" OBJECTS ", \"render\": {\"max_depth\": %d}}", MAX_DEPTH_LIMIT + 1);
    expect_error(json, ERR_JSON_VALUE, "render.max_depth");
    expect_error("{" OBJECTS ", \"render\": {\"max_depth\": 2147483647}}", ERR_JSON_VALUE, "render.max_depth");
    cr_expect_eq(MAX_DEPTH_LIMIT, 1024);
}
