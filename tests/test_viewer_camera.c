// SPDX-License-Identifier: MIT
/* The viewer's camera controls (host/viewer/camera_controls.h) as plain functions: each control moves the
 * pose by the amount its contract states, and --camera JSON round-trips and names bad keys. */
#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "scene/camera.h"
#include "scene/scene.h"
#include "support.h"
#include "viewer/camera_controls.h"

#define PI 3.14159265f

/* scenes/cornell-box's camera. */
static CameraDesc box_camera(void)
{
    return (CameraDesc){.eye = {0, 1, 3.9f}, .target = {0, 1, 0}, .up = {0, 1, 0}, .fov_y = 39.3f};
}

static float distance3(const float a[3], const float b[3])
{
    float d[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
    return sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
}

static void expect_vec(const float got[3], float x, float y, float z, float tolerance, const char *what)
{
    cr_expect(fabsf(got[0] - x) <= tolerance && fabsf(got[1] - y) <= tolerance &&
                  fabsf(got[2] - z) <= tolerance,
              "%s: (%g, %g, %g), expected (%g, %g, %g)", what, got[0], got[1], got[2], x, y, z);
}

Test(viewer_camera, orbit_turns_the_eye_around_the_target)
{
    CameraDesc c = box_camera();
    viewer_camera_orbit(&c, PI / 2, 0.0f); /* a quarter turn toward the camera's right (+x) */
    expect_vec(c.eye, 3.9f, 1.0f, 0.0f, 1e-4f, "eye after yaw");
    expect_vec(c.target, 0, 1, 0, 0.0f, "target after yaw");

    c = box_camera();
    viewer_camera_orbit(&c, 0.0f, -PI / 4); /* 45 degrees up: polar angle 90 -> 45 degrees */
    expect_vec(c.eye, 0.0f, 1.0f + 3.9f * sqrtf(0.5f), 3.9f * sqrtf(0.5f), 1e-4f, "eye after pitch");

    /* Pitching past the pole stops short of it: the view frame stays well defined. */
    for (int direction = -1; direction <= 1; direction += 2) {
        c = box_camera();
        viewer_camera_orbit(&c, 0.3f, 10.0f * direction);
        cr_expect(fabsf(distance3(c.eye, c.target) - 3.9f) < 1e-4f, "distance kept");
        float horizontal = hypotf(c.eye[0] - c.target[0], c.eye[2] - c.target[2]);
        cr_expect(horizontal > 1e-3f && horizontal < 0.1f, "near the pole but off it: %g", horizontal);
        Camera cam = camera_from_desc(&c, 64, 64);
        float right_length = sqrtf(cam.right.s[0] * cam.right.s[0] + cam.right.s[1] * cam.right.s[1] +
                                   cam.right.s[2] * cam.right.s[2]);
        cr_expect(fabsf(right_length - 1.0f) < 1e-3f, "right vector degenerate: %g", right_length);
    }
}

Test(viewer_camera, pan_moves_eye_and_target_with_the_cursor)
{
    /* A cursor moved by the film's height crosses the whole view at the target's depth:
     * 2 d tan(fov / 2). Dragging right moves the camera left (the scene follows the cursor). */
    float span = 2.0f * 3.9f * tanf(0.5f * 39.3f * PI / 180.0f);
    CameraDesc c = box_camera();
    viewer_camera_pan(&c, 200.0f, 0.0f, 200);
    expect_vec(c.eye, -span, 1.0f, 3.9f, 1e-4f, "eye after pan right");
    expect_vec(c.target, -span, 1.0f, 0.0f, 1e-4f, "target after pan right");
    c = box_camera();
    viewer_camera_pan(&c, 0.0f, 100.0f, 200); /* cursor down half a film: camera up */
    expect_vec(c.eye, 0.0f, 1.0f + 0.5f * span, 3.9f, 1e-4f, "eye after pan down");
    expect_vec(c.target, 0.0f, 1.0f + 0.5f * span, 0.0f, 1e-4f, "target after pan down");
}

Test(viewer_camera, dolly_approaches_the_target_without_reaching_it)
{
    CameraDesc c = box_camera();
    viewer_camera_dolly(&c, 1.0f);
    expect_vec(c.eye, 0.0f, 1.0f, 3.9f * 0.85f, 1e-4f, "one step in");
    viewer_camera_dolly(&c, -1.0f);
    expect_vec(c.eye, 0.0f, 1.0f, 3.9f, 1e-4f, "and back out");
    viewer_camera_dolly(&c, 1000.0f);
    cr_expect(c.eye[2] > 0.0f && c.eye[2] < 1e-2f, "eye stays in front of the target: z = %g", c.eye[2]);
    expect_vec(c.target, 0, 1, 0, 0.0f, "target");
}

Test(viewer_camera, fly_moves_eye_and_target_together)
{
    CameraDesc c = box_camera();
    viewer_camera_fly(&c, (const float[3]){0, 0, 1}, 0.5f); /* forward is -z */
    expect_vec(c.eye, 0.0f, 1.0f, 3.4f, 1e-5f, "eye forward");
    expect_vec(c.target, 0.0f, 1.0f, -0.5f, 1e-5f, "target forward");
    c = box_camera();
    viewer_camera_fly(&c, (const float[3]){1, 1, 0}, 2.0f); /* right is +x, up is +y */
    expect_vec(c.eye, 2.0f, 3.0f, 3.9f, 1e-5f, "eye right and up");
    expect_vec(c.target, 2.0f, 3.0f, 0.0f, 1e-5f, "target right and up");
}

Test(viewer_camera, pixel_direction_follows_the_kernel_camera)
{
    CameraDesc c = box_camera();
    float dir[3], tan_half = tanf(0.5f * 39.3f * PI / 180.0f);
    viewer_camera_pixel_direction(&c, 200, 100, 100.0, 50.0, dir); /* the centre */
    expect_vec(dir, 0.0f, 0.0f, -1.0f, 1e-5f, "centre");
    viewer_camera_pixel_direction(&c, 200, 100, 100.0, 0.0, dir); /* top edge: y down in pixels */
    cr_expect(fabsf(dir[1] / -dir[2] - tan_half) < 1e-4f, "top edge at fov/2: %g", dir[1] / -dir[2]);
    viewer_camera_pixel_direction(&c, 200, 100, 200.0, 50.0, dir); /* right edge, aspect 2 */
    cr_expect(fabsf(dir[0] / -dir[2] - 2.0f * tan_half) < 1e-4f, "right edge: %g", dir[0] / -dir[2]);
    /* Focus is measured along the view axis: t cos(angle). */
    float axis = viewer_camera_axis_distance(&c, dir, 2.0f);
    cr_expect(fabsf(axis - 2.0f * -dir[2]) < 1e-5f, "axis distance %g", axis);
}

Test(viewer_camera, json_round_trips_and_keeps_missing_keys)
{
    CameraDesc c = {.eye = {1.25f, -2.5f, 3.125f}, .target = {0.1f, 0.2f, -0.3f}, .up = {0, 0, 1},
                    .fov_y = 55.5f, .aperture = 0.04f, .focus_distance = 4.5f};
    char json[1024];
    viewer_camera_format(&c, json, sizeof json);
    cr_expect(strncmp(json, "\"camera\": {", 11) == 0, "fragment to paste into a scene: %s", json);
    CameraDesc back = box_camera();
    Error err = {0};
    cr_assert(viewer_camera_parse(json, &back, &err), "%s", err.message);
    expect_vec(back.eye, 1.25f, -2.5f, 3.125f, 1e-6f, "eye");
    expect_vec(back.target, 0.1f, 0.2f, -0.3f, 1e-6f, "target");
    expect_vec(back.up, 0, 0, 1, 0.0f, "up");
    cr_expect(back.fov_y == 55.5f && back.aperture == 0.04f && back.focus_distance == 4.5f);

    /* A bare object with some keys: the others stay the scene's. */
    back = box_camera();
    cr_assert(viewer_camera_parse("{\"fov_y\": 60, \"target\": [0, 1.5, 0]}", &back, &err), "%s",
              err.message);
    cr_expect(back.fov_y == 60.0f);
    expect_vec(back.target, 0.0f, 1.5f, 0.0f, 0.0f, "target");
    expect_vec(back.eye, 0.0f, 1.0f, 3.9f, 0.0f, "eye kept");
}

Test(viewer_camera, json_errors_name_the_key_and_change_nothing)
{
    static const struct {
        const char *json;
        ErrorCode code;
        const char *needle;
    } cases[] = {
        {"{\"eye\": [0, 1]}", ERR_JSON_TYPE, "camera.eye"},
        {"{\"aperture\": \"wide\"}", ERR_JSON_TYPE, "camera.aperture"},
        {"{\"fov_y\": 200}", ERR_JSON_VALUE, "camera.fov_y"},
        {"{\"focus_distance\": -1}", ERR_JSON_VALUE, "camera.focus_distance"},
        {"{\"zoom\": 2}", ERR_JSON_UNKNOWN_KEY, "camera.zoom"},
        {"{\"eye\": [0, 1, 0]}", ERR_JSON_VALUE, "camera.target"}, /* eye == target */
        {"{\"up\": [0, 0, -2]}", ERR_JSON_VALUE, "camera.up"},    /* up along the view */
        {"{\"eye\": [0, 1, 3.9],", ERR_JSON_SYNTAX, "malformed"},
        {"[0, 1, 3.9]", ERR_JSON_TYPE, "object"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        CameraDesc c = box_camera(), before = c;
        Error err = {0};
        cr_expect(!viewer_camera_parse(cases[i].json, &c, &err), "%s accepted", cases[i].json);
        cr_expect_eq(err.code, cases[i].code, "%s: %s, expected %s", cases[i].json,
                     error_code_name(err.code), error_code_name(cases[i].code));
        cr_expect(strstr(err.message, cases[i].needle), "%s: '%s' not in: %s", cases[i].json,
                  cases[i].needle, err.message);
        cr_expect(strchr(err.message, '\n') == NULL, "one line: %s", err.message);
        cr_expect(memcmp(&c, &before, sizeof c) == 0, "%s changed the camera", cases[i].json);
    }
}

/* What C prints reads back as the very same floats (a pasted camera is the same view, as the
 * viewer tests rely on), and round values stay as short as they were typed. */
Test(viewer_camera, printed_camera_reads_back_exactly)
{
    CameraDesc c = box_camera();
    char json[1024];
    viewer_camera_format(&c, json, sizeof json);
    cr_expect(strstr(json, "\"eye\": [0, 1, 3.9]") && strstr(json, "\"fov_y\": 39.3"), "short: %s",
              json);
    viewer_camera_orbit(&c, 0.123f, -0.456f); /* values that need all nine digits */
    viewer_camera_dolly(&c, 0.7f);
    c.focus_distance = 1.0f / 3.0f;
    viewer_camera_format(&c, json, sizeof json);
    CameraDesc back = box_camera();
    Error err = {0};
    cr_assert(viewer_camera_parse(json, &back, &err), "%s", err.message);
    cr_expect(memcmp(&back, &c, sizeof c) == 0, "not the same floats: %s", json);
}

/* A camera refused in a scene file is refused by --camera with the same error: one reader
 * (scene/camera_json.c) behind both, so the code and the message after the input's name
 * ("file:line: " or "--camera: ") are identical. */
Test(viewer_camera, bad_cameras_get_the_scenes_error)
{
    static const char *const cameras[] = {
        "{\"eye\": [0, 1, 4], \"target\": [0, 1, 0], \"fov_y\": 0}",
        "{\"eye\": [0, 1, 1e30], \"target\": [0, 1, 0]}",
        "{\"eye\": [0, 1, 1e40], \"target\": [0, 1, 0]}",
        "{\"eye\": [1, 2, 3], \"target\": [1, 2, 3]}",
        "{\"eye\": [0, 1, 4], \"target\": [0, 1, 0], \"up\": [0, 0, -2]}",
        "{\"eye\": [0, 1, 4], \"target\": [0, 1, 0], \"up\": [0, 1e20, 0]}",
        "{\"eye\": [0, 1, 4], \"target\": [0, 1, 0], \"aperture\": -0.5}",
        "{\"eye\": [0, 1, 4], \"target\": [0, 1, 0], \"focus_distance\": -1}",
        "{\"eye\": [0, 1], \"target\": [0, 1, 0]}",
        "{\"eye\": [0, 1, 4], \"target\": [0, 1, 0], \"fov_y\": \"40\"}",
        "{\"eye\": [0, 1, 4], \"target\": [0, 1, 0], \"zoom\": 2}",
    };
    const char *dir = test_temp_dir();
    for (size_t i = 0; i < sizeof cameras / sizeof cameras[0]; i++) {
        char scene[512];
        snprintf(scene, sizeof scene, "{\"objects\": [{\"obj\": \"box.obj\"}], \"camera\": %s}",
                 cameras[i]);
        SceneDesc desc;
        Error scene_err = {0}, view_err = {0};
        bool scene_ok = scene_desc_load(test_write_file(dir, "camera.json", scene), &desc, &scene_err);
        if (scene_ok)
            scene_desc_free(&desc);
        CameraDesc c = box_camera();
        bool view_ok = viewer_camera_parse(cameras[i], &c, &view_err);
        cr_expect(!scene_ok && !view_ok, "%s: accepted by the scene (%d) or --camera (%d)",
                  cameras[i], scene_ok, view_ok);
        cr_expect_eq(scene_err.code, view_err.code, "%s: %s vs %s", cameras[i],
                     error_code_name(scene_err.code), error_code_name(view_err.code));
        const char *scene_says = strstr(scene_err.message, ": camera.");
        const char *view_says = strstr(view_err.message, ": camera.");
        cr_expect(scene_says && view_says && strcmp(scene_says, view_says) == 0,
                  "%s: different messages:\n  %s\n  %s", cameras[i], scene_err.message,
                  view_err.message);
        cr_expect(strncmp(view_err.message, "--camera: camera.", 17) == 0, "%s", view_err.message);
    }
}
