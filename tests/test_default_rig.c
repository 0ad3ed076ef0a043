// SPDX-License-Identifier: MIT
/* The first image of a bare model (shared/DESIGN.md "First contact"): which scenes get the default
 * rig (scene_default_rig_choice), the rig's parts (a sky brighter above than below, a sun above
 * the horizon on the camera's side, a ground at the lowest point along the up axis), the 3/4
 * framing that fits every corner of the bounds for any aspect, and a rendered bare sphere whose
 * lit side is clearly brighter than its shadow side (the uniform white sky it replaces gave a flat
 * grey disc). */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>

#include "base/vec3.h"
#include "io/image_io.h"
#include "scene/default_rig.h"
#include "scene/scene.h"
#include "support.h"

static Scene load(const char *path)
{
    Scene s;
    Error err = {0};
    cr_assert(scene_load(path, &s, &err), "%s", err.message);
    return s;
}

/* A tetrahedron-like box model: 2 x 1 x 1 above y = 3 (its lowest point), plus optional text. */
static const char *box_obj(const char *dir, const char *name, const char *extra)
{
    char text[2048];
    snprintf(text, sizeof text,
             "v -1 3 -0.5\nv 1 3 -0.5\nv 1 3 0.5\nv -1 3 0.5\n"
             "v -1 4 -0.5\nv 1 4 -0.5\nv 1 4 0.5\nv -1 4 0.5\n"
             "f 1 2 3\nf 1 3 4\nf 5 7 6\nf 5 8 7\nf 1 5 6\nf 1 6 2\nf 4 3 7\nf 4 7 8\n%s", extra);
    return test_write_file(dir, name, text);
}

Test(default_rig, choice_follows_the_rule)
{
    const char *dir = test_temp_dir();
    Scene s = load(box_obj(dir, "bare.obj", ""));
    cr_expect_eq(scene_default_rig_choice(&s), RIG_WITH_GROUND, "a bare model without light");
    scene_free(&s);

    /* Tiny emitters (a label of 0.01 x 0.01 on a 2 x 1 x 1 box, Ke 5): the rig as well. */
    test_write_file(dir, "label.mtl", "newmtl label\nKd 0 0 0\nKe 5 5 5\n");
    s = load(box_obj(dir, "label.obj", "mtllib label.mtl\nusemtl label\nv 0 3.5 0.51\nv 0.01 3.5 0.51\n"
                                      "v 0.01 3.51 0.51\nf 9 10 11\n"));
    cr_expect_eq(s.data.num_emissive, 1u);
    cr_expect_eq(scene_default_rig_choice(&s), RIG_WITH_GROUND, "tiny emitters do not light the model");
    scene_free(&s);

    /* A lamp as large as the box's side, Ke 5: the model's own light. */
    test_write_file(dir, "lamp.mtl", "newmtl lamp\nKd 0 0 0\nKe 5 5 5\n");
    s = load(box_obj(dir, "lamp.obj", "mtllib lamp.mtl\nusemtl lamp\nv -1 5 -1\nv 1 5 -1\nv 1 5 1\n"
                                     "v -1 5 1\nf 9 11 10\nf 9 12 11\n"));
    cr_expect_eq(scene_default_rig_choice(&s), RIG_NONE, "a lamp lights the model");
    /* A set lit by its own lamp is framed straight from its front (+z), as the Cornell box. */
    const CameraDesc *c = &s.desc.camera;
    cr_expect(fabsf(c->eye[0] - c->target[0]) < 1e-4f && fabsf(c->eye[1] - c->target[1]) < 1e-4f &&
                  c->eye[2] > c->target[2], "eye %g %g %g", c->eye[0], c->eye[1], c->eye[2]);
    scene_free(&s);

    /* A JSON scene: the sky and the sun without a ground when it has no light; nothing when it has
     * emitters (its author's light) or lights. */
    s = load(test_write_file(dir, "plain.json", "{\"objects\": [{\"obj\": \"bare.obj\"}]}"));
    cr_expect_eq(scene_default_rig_choice(&s), RIG_SKY_AND_KEY);
    scene_free(&s);
    s = load(test_write_file(dir, "labelled.json", "{\"objects\": [{\"obj\": \"label.obj\"}]}"));
    cr_expect_eq(scene_default_rig_choice(&s), RIG_NONE);
    scene_free(&s);
    s = load(test_write_file(dir, "lit.json", "{\"objects\": [{\"obj\": \"bare.obj\"}], \"lights\": "
                                              "[{\"type\": \"point\", \"position\": [0, 9, 0], \"intensity\": 1}]}"));
    cr_expect_eq(scene_default_rig_choice(&s), RIG_NONE);
    scene_free(&s);
    s = load(test_write_file(dir, "bg.json", "{\"objects\": [{\"obj\": \"bare.obj\"}], \"background\": [0.1, 0.1, 0.1]}"));
    cr_expect_eq(scene_default_rig_choice(&s), RIG_NONE);
    scene_free(&s);
}

/* The rig's sky, sun and ground on a bare model, for each up axis. */
static void check_rig(UpAxis up_axis)
{
    const char *dir = test_temp_dir();
    Scene s = load(box_obj(dir, "bare.obj", ""));
    scene_frame_camera(&s, up_axis);
    uint32_t triangles = s.data.num_triangles;
    float model_min[3], model_max[3];
    memcpy(model_min, s.data.bounds_min, sizeof model_min);
    memcpy(model_max, s.data.bounds_max, sizeof model_max);
    RigOptions options = {.up = up_axis};
    Error err = {0};
    cr_assert(scene_add_default_rig(&s, &options, &err), "%s", err.message);
    ViewBasis b = view_basis(up_axis);
    int axis = up_axis == UP_AXIS_Z ? 2 : 1;

    /* The sky: brighter straight up than straight down, and blue above. */
    float zenith[3], nadir[3], down[3] = {-b.up[0], -b.up[1], -b.up[2]};
    rig_sky_radiance(&b, b.up, zenith);
    rig_sky_radiance(&b, down, nadir);
    cr_expect(zenith[1] > 2.0f * nadir[1] && zenith[2] > zenith[0], "zenith %g %g %g, nadir %g",
              zenith[0], zenith[1], zenith[2], nadir[1]);
    cr_expect(s.data.environment.width == RIG_SKY_WIDTH && s.data.environment.mean_luminance > 0.0);

    /* The sun: one light, travelling downward (its source above the horizon). */
    cr_assert_eq(s.data.num_analytic, 1u);
    const AnalyticLight *sun = &s.data.analytic_lights[0];
    cr_expect_eq(sun->type, (unsigned)LIGHT_SUN);
    cr_expect(dot3(sun->position.s, b.up) < -0.5f, "the sun travels along %g %g %g", sun->position.s[0],
              sun->position.s[1], sun->position.s[2]);

    /* The ground: two triangles more, every new vertex at the model's lowest point along up, and
     * it reaches well beyond the model on both horizontal axes. */
    cr_assert_eq(s.data.num_triangles, triangles + 2);
    float lowest = model_min[axis];
    for (uint32_t t = triangles; t < s.data.num_triangles; t++)
        for (int c = 0; c < 3; c++) {
            const float *p = s.data.positions[s.data.triangles[t].v.s[c]].s;
            cr_expect(fabsf(p[axis] - lowest) < 1e-4f, "ground vertex at %g, lowest point %g", p[axis], lowest);
        }
    for (int i = 0; i < 3; i++)
        if (i != axis)
            cr_expect(s.data.bounds_min[i] < model_min[i] - 10.0f && s.data.bounds_max[i] > model_max[i] + 10.0f);
    cr_expect_not(s.data.two_level, "the ground joins the merged mesh");
    scene_free(&s);
}

Test(default_rig, sky_sun_and_ground_y_up) { check_rig(UP_AXIS_Y); }
Test(default_rig, sky_sun_and_ground_z_up) { check_rig(UP_AXIS_Z); }

Test(default_rig, no_ground_when_asked_or_flat)
{
    const char *dir = test_temp_dir();
    Scene s = load(box_obj(dir, "bare.obj", ""));
    uint32_t triangles = s.data.num_triangles;
    RigOptions options = {.up = UP_AXIS_Y, .no_ground = true};
    Error err = {0};
    cr_assert(scene_add_default_rig(&s, &options, &err), "%s", err.message);
    cr_expect_eq(s.data.num_triangles, triangles, "--no-ground");
    cr_expect_eq(s.data.num_analytic, 1u, "the sun stays");
    scene_free(&s);
    /* A plane at y = 0 (MorphPrimitivesTest's trait) is its own ground. */
    s = load(test_write_file(dir, "plane.obj", "v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nf 1 3 2\nf 1 4 3\n"));
    options.no_ground = false;
    cr_assert(scene_add_default_rig(&s, &options, &err), "%s", err.message);
    cr_expect_eq(s.data.num_triangles, 2u);
    scene_free(&s);
}

/* Projects p through the framed camera: x, y in [-1, 1] inside the film. */
static void project(const CameraDesc *c, float aspect, const float p[3], float *x, float *y)
{
    float f[3] = {c->target[0] - c->eye[0], c->target[1] - c->eye[1], c->target[2] - c->eye[2]}, r[3], u[3];
    normalize3(f);
    cross3(f, c->up, r);
    normalize3(r);
    cross3(r, f, u);
    float d[3] = {p[0] - c->eye[0], p[1] - c->eye[1], p[2] - c->eye[2]};
    float depth = dot3(d, f), t = tanf(0.5f * c->fov_y * 3.14159265f / 180.0f);
    cr_assert(depth > 0.0f, "a corner behind the camera");
    *x = dot3(d, r) / (depth * t * aspect);
    *y = dot3(d, u) / (depth * t);
}

Test(default_rig, framing_fits_every_corner_for_any_aspect)
{
    const float boxes[][6] = {{-1, 3, -0.5f, 1, 4, 0.5f},   /* wide */
                              {0, 0, 0, 0.1f, 5, 0.1f},     /* tall */
                              {-1, 0, -1, 1, 0, 1},         /* a plane at y = 0 */
                              {-0.2f, 0, -3, 0.2f, 0.3f, 3}}; /* long along the front axis (a rifle) */
    const float aspects[] = {0.5f, 1.0f, 16.0f / 9.0f, 3.0f};
    for (size_t k = 0; k < sizeof boxes / sizeof boxes[0]; k++)
        for (size_t a = 0; a < sizeof aspects / sizeof aspects[0]; a++)
            for (int up = 0; up < 2; up++) {
                ViewBasis b = view_basis(up ? UP_AXIS_Z : UP_AXIS_Y);
                const float *lo = boxes[k], *hi = boxes[k] + 3;
                CameraDesc c = camera_frame_model(lo, hi, aspects[a], &b);
                float extent = 0.0f;
                for (int i = 0; i < 8; i++) {
                    float p[3] = {i & 1 ? hi[0] : lo[0], i & 2 ? hi[1] : lo[1], i & 4 ? hi[2] : lo[2]}, x, y;
                    project(&c, aspects[a], p, &x, &y);
                    cr_expect(fabsf(x) <= 1.0f && fabsf(y) <= 1.0f, "box %zu aspect %g: corner %d at %g %g",
                              k, aspects[a], i, x, y);
                    extent = fmaxf(extent, fmaxf(fabsf(x), fabsf(y)));
                }
                /* Fitted, not lost in the frame (the bounding sphere alone left a plane small). */
                cr_expect(extent > 0.85f, "box %zu aspect %g: the model fills only %g", k, aspects[a], extent);
                /* Seen from above the horizon, from the front's side. */
                float view[3] = {c.eye[0] - c.target[0], c.eye[1] - c.target[1], c.eye[2] - c.target[2]};
                normalize3(view);
                cr_expect(dot3(view, b.up) > 0.2f && dot3(view, b.up) < 0.5f);
                if (k == 3 && !up) /* a long model is seen more from its side than its end */
                    cr_expect(fabsf(dot3(view, b.right)) > fabsf(dot3(view, b.front)), "box %zu seen end-on", k);
            }
}

/* Rendered: a bare sphere under the rig shows a lit side and a shadow side. */
Test(default_rig, bare_sphere_reads_as_a_shape, .timeout = 300)
{
    const char *dir = test_temp_dir();
    char text[65536];
    int n = 0;
    const int rings = 12, segments = 24;
    for (int i = 0; i <= rings; i++)
        for (int j = 0; j < segments; j++) {
            double th = 3.14159265358979 * i / rings, ph = 2.0 * 3.14159265358979 * j / segments;
            n += snprintf(text + n, sizeof text - (size_t)n, "v %f %f %f\n", sin(th) * cos(ph),
                          cos(th) + 1.0, sin(th) * sin(ph));
        }
    for (int i = 0; i < rings; i++)
        for (int j = 0; j < segments; j++) {
            int a = i * segments + j + 1, b = i * segments + (j + 1) % segments + 1;
            n += snprintf(text + n, sizeof text - (size_t)n, "f %d %d %d\nf %d %d %d\n", a, b, b + segments,
                          a, b + segments, a + segments);
        }
    const char *obj = test_write_file(dir, "sphere.obj", text);
    char cmd[4096], exr[1024];
    snprintf(exr, sizeof exr, "%s/out.exr", dir);
    snprintf(cmd, sizeof cmd, "'%s' render '%s' --spp 16 --width 48 --height 48 --quiet -o '%s' 2>/dev/null >/dev/null",
             test_pt_bin(), obj, exr);
    int status = system(cmd);
    cr_assert(WIFEXITED(status) && WEXITSTATUS(status) == 0, "pt render failed");
    float *rgb;
    int w, h;
    Error err = {0};
    cr_assert(image_read_exr(exr, &rgb, &w, &h, &err), "%s", err.message);
    /* The sphere fills the middle of the frame: compare its left and right thirds around the
     * centre row band (the sun comes from the camera's left). */
    double left = 0.0, right = 0.0;
    for (int y = h / 3; y < 2 * h / 3; y++)
        for (int x = w / 3; x < w / 2 - 2; x++) {
            const float *l = rgb + 3 * (y * w + x), *r = rgb + 3 * (y * w + (w - 1 - x));
            left += 0.2126 * l[0] + 0.7152 * l[1] + 0.0722 * l[2];
            right += 0.2126 * r[0] + 0.7152 * r[1] + 0.0722 * r[2];
        }
    free(rgb);
    cr_expect(left > 1.25 * right, "lit side %g, shadow side %g: the shape does not read", left, right);
}
