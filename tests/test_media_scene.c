// SPDX-License-Identifier: MIT
/* The scene format of media (shared/DESIGN.md "Media"; host/scene/media_json.c, media_load.c,
 * object_media.c): the "media" block's keys land in the kernels' Medium with DESIGN's defaults,
 * the world's and the camera's medium, objects' interior / exterior as derived materials (other
 * objects of the same material keep theirs, instanced meshes too), closed-mesh checks, the
 * "interface" material, principled subsurface's walk medium against Van de Hulst's formula, the
 * scene hash, and every bad value as one line naming its key. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene/object_media.h"
#include "scene/scene.h"
#include "scene/scene_hash.h"
#include "scene/scene_media.h"
#include "support.h"

static char g_dir[64];

static const char *write_file(const char *name, const char *text)
{
    if (!g_dir[0])
        snprintf(g_dir, sizeof g_dir, "%s", test_temp_dir());
    return test_write_file(g_dir, name, text);
}

/* cube.obj: a closed cube of 12 triangles (outward, counter-clockwise); open.obj: one triangle;
 * seams.obj: the same cube with one normal per face, so that corners at one position become
 * distinct vertices (closed all the same); finned.obj: the cube plus a triangle on one of its
 * edges (three faces there). */
static void write_meshes(void)
{
    static const char cube[] = "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\n"
                               "v -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n";
    static const char faces[] = "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\n"
                                "f 4 8 7\nf 4 7 3\nf 1 5 8\nf 1 8 4\nf 2 3 7\nf 2 7 6\n";
    char text[2048];
    snprintf(text, sizeof text, "%s%s", cube, faces);
    write_file("cube.obj", text);
    write_file("open.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    snprintf(text, sizeof text, "%s%s", cube,
             "vn 0 0 -1\nvn 0 0 1\nvn 0 -1 0\nvn 0 1 0\nvn -1 0 0\nvn 1 0 0\n"
             "f 1//1 3//1 2//1\nf 1//1 4//1 3//1\nf 5//2 6//2 7//2\nf 5//2 7//2 8//2\n"
             "f 1//3 2//3 6//3\nf 1//3 6//3 5//3\nf 4//4 8//4 7//4\nf 4//4 7//4 3//4\n"
             "f 1//5 5//5 8//5\nf 1//5 8//5 4//5\nf 2//6 3//6 7//6\nf 2//6 7//6 6//6\n");
    write_file("seams.obj", text);
    snprintf(text, sizeof text, "%sv 0 -3 -3\n%sf 1 2 9\n", cube, faces);
    write_file("finned.obj", text);
    snprintf(text, sizeof text, "%s%s", cube,
             "f 1 2 3\nf 1 3 4\nf 5 7 6\nf 5 8 7\nf 1 6 2\nf 1 5 6\n"
             "f 4 7 8\nf 4 3 7\nf 1 8 5\nf 1 4 8\nf 2 7 3\nf 2 6 7\n");
    write_file("inside_out.obj", text);
}

static const char camera[] = "\"camera\": {\"eye\": [0, 0, 5], \"target\": [0, 0, 0]}";

/* Loads {camera, json} (with its own "objects", else one fog-filled cube). */
static bool load_with(const char *json, InstancingMode mode, Scene *scene, Error *err)
{
    write_meshes();
    char text[8192];
    snprintf(text, sizeof text, "{%s%s%s%s}", strstr(json, "\"camera\"") ? "" : camera,
             strstr(json, "\"camera\"") ? "" : ", ",
             strstr(json, "\"objects\"") ? "" : "\"objects\": [{\"obj\": \"cube.obj\"}], ", json);
    const char *path = write_file("scene.json", text);
    return scene_load_with(path, mode, scene, err);
}

static bool load(const char *json, Scene *scene, Error *err)
{
    return load_with(json, INSTANCING_AUTO, scene, err);
}

static void load_ok(const char *json, Scene *scene)
{
    Error err = {0};
    cr_assert(load(json, scene, &err), "%s", err.message);
}

/* The scene must be refused with one line holding `needle` (the key and what is wrong). */
static void refused(const char *json, const char *needle)
{
    Scene scene;
    Error err = {0};
    bool ok = load(json, &scene, &err);
    if (ok)
        scene_free(&scene);
    cr_assert(!ok, "accepted; expected an error with \"%s\"", needle);
    cr_expect(strstr(err.message, needle), "\"%s\" does not hold \"%s\"", err.message, needle);
    cr_expect(!strchr(err.message, '\n'), "more than one line: %s", err.message);
}

static void expect_rgb(const float4 v, float r, float g, float b, const char *what)
{
    cr_expect(fabsf(v.s[0] - r) <= 1e-6f * fmaxf(1.0f, fabsf(r)) &&
                  fabsf(v.s[1] - g) <= 1e-6f * fmaxf(1.0f, fabsf(g)) &&
                  fabsf(v.s[2] - b) <= 1e-6f * fmaxf(1.0f, fabsf(b)),
              "%s: [%g, %g, %g], expected [%g, %g, %g]", what, v.s[0], v.s[1], v.s[2], r, g, b);
}

/* A little-endian Mitsuba .vol of res^3 float32 densities: value(i) at voxel i. */
static void write_vol(const char *name, int res, float (*value)(int))
{
    char path[256];
    snprintf(path, sizeof path, "%s/%s", g_dir, name);
    FILE *f = fopen(path, "wb");
    cr_assert(f);
    int32_t header[5] = {1, res, res, res, 1};
    float bbox[6] = {0, 0, 0, 1, 1, 1};
    fwrite("VOL\3", 1, 4, f);
    fwrite(header, sizeof header, 1, f);
    fwrite(bbox, sizeof bbox, 1, f);
    for (int i = 0; i < res * res * res; i++) {
        float v = value(i);
        fwrite(&v, sizeof v, 1, f);
    }
    fclose(f);
}

static float ramp(int i) { return (float)(i % 7) * 0.5f; }

/* ---- The "media" block ---------------------------------------------------------------------- */

Test(media_scene, homogeneous_defaults_scale_g_and_emission)
{
    Scene s;
    load_ok("\"media\": {\"empty\": {\"type\": \"homogeneous\"}, \"fog\": {\"type\": "
            "\"homogeneous\", \"sigma_a\": [0.1, 0.2, 0.3], \"sigma_s\": 0.5, \"scale\": 4, "
            "\"g\": -0.25, \"emission\": [1, 2, 3]}}",
            &s);
    cr_assert_eq(s.data.num_media, 2);
    const Medium *e = &s.data.media[0], *f = &s.data.media[1];
    cr_expect_eq(e->type, MEDIUM_HOMOGENEOUS);
    expect_rgb(e->sigma_a, 0, 0, 0, "default sigma_a");
    expect_rgb(e->sigma_s, 0, 0, 0, "default sigma_s");
    expect_rgb(e->emission, 0, 0, 0, "default emission");
    cr_expect_eq(e->sigma_a.s[3], 0.0f, "default g");
    cr_expect_eq(e->flags, 0u);
    cr_expect_eq(f->type, MEDIUM_HOMOGENEOUS);
    expect_rgb(f->sigma_a, 0.4f, 0.8f, 1.2f, "sigma_a times scale");
    expect_rgb(f->sigma_s, 2.0f, 2.0f, 2.0f, "sigma_s times scale");
    expect_rgb(f->emission, 1, 2, 3, "emission (not scaled)");
    cr_expect_eq(f->sigma_a.s[3], -0.25f, "g");
    cr_expect_eq(f->flags, MEDIUM_FLAG_SCATTERS | MEDIUM_FLAG_EMITS);
    cr_expect_eq(s.data.world_medium, 0u, "no \"medium\": no world medium");
    cr_expect_eq(s.data.camera_medium, 0u);
    scene_free(&s);
}

Test(media_scene, grid_defaults_and_coefficients_per_unit_density)
{
    write_meshes();
    write_vol("smoke.vol", 4, ramp);
    Scene s;
    load_ok("\"media\": {\"plain\": {\"type\": \"grid\", \"file\": \"smoke.vol\"}, "
            "\"smoke\": {\"type\": \"grid\", \"file\": \"smoke.vol\", \"grid\": \"density\", "
            "\"density_scale\": 2, \"sigma_t\": [1, 2, 4], \"albedo\": [0.5, 0.25, 1], \"g\": 0.5, "
            "\"emission\": 0.5, \"transform\": [{\"scale\": 2}, {\"translate\": [1, 0, 0]}]}}",
            &s);
    cr_assert_eq(s.data.num_media, 2);
    const Medium *p = &s.data.media[0], *m = &s.data.media[1];
    cr_expect_eq(p->type, MEDIUM_GRID);
    expect_rgb(p->sigma_s, 1, 1, 1, "default: sigma_t 1, albedo 1: all scattering");
    expect_rgb(p->sigma_a, 0, 0, 0, "albedo 1: no absorption");
    cr_expect_eq(p->sigma_s.s[3], 3.0f, "the largest density (6 * 0.5)");
    cr_expect_eq(p->res_x, 4u);
    /* sigma_t density_scale = [2, 4, 8]; albedo splits it. */
    expect_rgb(m->sigma_s, 1.0f, 1.0f, 8.0f, "albedo sigma_t density_scale");
    expect_rgb(m->sigma_a, 1.0f, 3.0f, 0.0f, "(1 - albedo) sigma_t density_scale");
    cr_expect_eq(m->sigma_a.s[3], 0.5f, "g");
    expect_rgb(m->emission, 0.5f, 0.5f, 0.5f, "emission");
    /* World (3, 0, 0) = 2 (1, 0, 0) + (1, 0, 0): the grid's unit-cube x = 1, index x = 4. */
    float x = m->to_index[0].s[0] * 3.0f + m->to_index[0].s[3];
    cr_expect(fabsf(x - 4.0f) < 1e-5f, "transform: world x 3 is index x %g, expected 4", x);
    cr_expect(s.data.num_grid_bricks > 0 && s.data.num_grid_values > 0);
    scene_free(&s);
}

Test(media_scene, world_medium_and_camera_medium_default_to_it)
{
    Scene s;
    load_ok("\"media\": {\"air\": {\"type\": \"homogeneous\", \"sigma_s\": 0.01}, \"water\": "
            "{\"type\": \"homogeneous\", \"sigma_a\": 0.1}}, \"medium\": \"water\"",
            &s);
    cr_expect_eq(s.data.world_medium, 2u, "slot of the second medium");
    cr_expect_eq(s.data.camera_medium, 2u, "camera.medium defaults to the world's");
    scene_free(&s);
    char json[1024];
    snprintf(json, sizeof json,
             "\"camera\": {\"eye\": [0, 0, 5], \"target\": [0, 0, 0], \"medium\": \"air\"}, "
             "\"objects\": [{\"obj\": \"cube.obj\"}], \"media\": {\"air\": {\"type\": "
             "\"homogeneous\"}, \"water\": {\"type\": \"homogeneous\"}}, \"medium\": \"water\"");
    write_meshes();
    char text[2048];
    snprintf(text, sizeof text, "{%s}", json);
    Error err = {0};
    cr_assert(scene_load(write_file("cam.json", text), &s, &err), "%s", err.message);
    cr_expect_eq(s.data.camera_medium, 1u);
    cr_expect_eq(s.data.world_medium, 2u);
    cr_expect_eq(s.desc.camera.eye[2], 5.0f, "the camera's other keys still read");
    scene_free(&s);
}

/* ---- Objects' interior / exterior ----------------------------------------------------------- */

/* The material of the triangles of instance `inst`'s mesh (all alike in these scenes). */
static const Material *mesh_material(const Scene *s, uint32_t mesh)
{
    return &s->data.materials[s->data.material_ids[s->data.meshes[mesh].first_triangle]];
}

Test(media_scene, interior_goes_on_a_copy_other_objects_keep_the_material)
{
    Scene s;
    load_ok("\"media\": {\"fog\": {\"type\": \"homogeneous\", \"sigma_s\": 1}}, "
            "\"materials\": {\"glass\": {\"type\": \"dielectric\"}}, \"objects\": ["
            "{\"obj\": \"cube.obj\", \"material\": \"glass\"}, "
            "{\"obj\": \"seams.obj\", \"material\": \"glass\", \"interior\": \"fog\"}]",
            &s);
    /* Both merged into mesh 0: cube's 12 triangles, then seams' 12. */
    cr_assert_eq(s.data.num_triangles, 24);
    const Material *plain = &s.data.materials[s.data.material_ids[0]];
    const Material *filled = &s.data.materials[s.data.material_ids[12]];
    cr_expect_eq(s.data.material_ids[0], 0u, "the first object keeps materials.glass");
    cr_expect_eq(plain->flags & MATERIAL_FLAG_MEDIUM_INTERFACE, 0u);
    cr_expect_eq(plain->interior, 0u);
    cr_expect_neq(s.data.material_ids[12], 0u, "the second has a copy");
    cr_expect_eq(filled->type, MATERIAL_DIELECTRIC);
    cr_expect_eq(filled->flags & MATERIAL_FLAG_MEDIUM_INTERFACE, MATERIAL_FLAG_MEDIUM_INTERFACE);
    cr_expect_eq(filled->interior, 1u);
    cr_expect_eq(filled->exterior, MEDIUM_SLOT_WORLD, "exterior defaults to the world");
    for (uint32_t t = 12; t < 24; t++)
        cr_expect_eq(s.data.material_ids[t], s.data.material_ids[12], "one copy per object");
    scene_free(&s);
}

Test(media_scene, instanced_meshes_with_and_without_interior_are_not_shared)
{
    Scene s;
    Error err = {0};
    cr_assert(load_with("\"media\": {\"fog\": {\"type\": \"homogeneous\", \"sigma_s\": 1}}, "
                        "\"materials\": {\"box\": {\"type\": \"interface\"}}, \"objects\": ["
                        "{\"obj\": \"cube.obj\", \"material\": \"box\"}, "
                        "{\"obj\": \"cube.obj\", \"material\": \"box\", \"interior\": \"fog\", "
                        "\"transform\": [{\"translate\": [3, 0, 0]}]}, "
                        "{\"obj\": \"cube.obj\", \"material\": \"box\", \"interior\": \"fog\", "
                        "\"transform\": [{\"translate\": [6, 0, 0]}]}]",
                        INSTANCING_ALWAYS, &s, &err),
              "%s", err.message);
    cr_assert_eq(s.data.num_instances, 3);
    uint32_t m0 = s.data.instances[0].mesh, m1 = s.data.instances[1].mesh,
             m2 = s.data.instances[2].mesh;
    cr_expect_neq(m0, m1, "the cube with an interior has its own mesh");
    cr_expect_eq(m1, m2, "two cubes with the same interior share one");
    cr_expect_eq(mesh_material(&s, m0)->flags & MATERIAL_FLAG_MEDIUM_INTERFACE, 0u);
    cr_expect_eq(mesh_material(&s, m1)->interior, 1u);
    cr_expect_eq(mesh_material(&s, m1)->type, MATERIAL_INTERFACE);
    scene_free(&s);
}

Test(media_scene, exterior_alone_and_the_default_material)
{
    Scene s;
    load_ok("\"media\": {\"fog\": {\"type\": \"homogeneous\"}}, "
            "\"objects\": [{\"obj\": \"open.obj\", \"exterior\": \"fog\"}]",
            &s);
    const Material *m = &s.data.materials[s.data.material_ids[0]];
    cr_expect_eq(m->type, MATERIAL_DIFFUSE, "the default material's copy");
    cr_expect_eq(m->flags & MATERIAL_FLAG_MEDIUM_INTERFACE, MATERIAL_FLAG_MEDIUM_INTERFACE);
    cr_expect_eq(m->interior, 0u, "no interior: nothing behind it");
    cr_expect_eq(m->exterior, 1u);
    scene_free(&s);
}

Test(media_scene, a_mix_gets_the_media_on_its_copy_leaves_unchanged)
{
    Scene s;
    load_ok("\"media\": {\"fog\": {\"type\": \"homogeneous\"}}, \"materials\": {"
            "\"a\": {\"type\": \"diffuse\"}, \"b\": {\"type\": \"dielectric\"}, "
            "\"m\": {\"type\": \"mix\", \"a\": \"a\", \"b\": \"b\"}}, "
            "\"objects\": [{\"obj\": \"cube.obj\", \"material\": \"m\", \"interior\": \"fog\"}]",
            &s);
    const Material *m = &s.data.materials[s.data.material_ids[0]];
    cr_expect_eq(m->type, MATERIAL_MIX);
    cr_expect_eq(m->flags & MATERIAL_FLAG_MEDIUM_INTERFACE, MATERIAL_FLAG_MEDIUM_INTERFACE);
    cr_expect_eq(m->interior, 1u);
    cr_expect_eq(m->mix_a, 0u);
    cr_expect_eq(m->mix_b, 1u);
    cr_expect_eq(s.data.materials[0].flags & MATERIAL_FLAG_MEDIUM_INTERFACE, 0u);
    cr_expect_eq(s.data.materials[1].flags & MATERIAL_FLAG_MEDIUM_INTERFACE, 0u);
    scene_free(&s);
}

Test(media_scene, open_edges_are_counted_by_position)
{
    Scene s;
    load_ok("\"objects\": [{\"obj\": \"seams.obj\"}]", &s);
    uint64_t one = 9, many = 9;
    cr_assert(mesh_open_edges(&s.data, 0, s.data.num_triangles, &one, &many));
    cr_expect(s.data.num_vertices > 8, "the seams split vertices (%u)", s.data.num_vertices);
    cr_expect_eq(one, 0u, "a cube split at its normals' seams is closed");
    cr_expect_eq(many, 0u);
    cr_assert(mesh_open_edges(&s.data, 0, 11, &one, &many));
    cr_expect_eq(one, 3u, "one triangle less: its three edges have one face");
    scene_free(&s);
}

/* ---- Subsurface ----------------------------------------------------------------------------- */

/* Van de Hulst's inversion as Cycles' subsurface_random_walk_remap writes it, g = 0. */
static double van_de_hulst(double a)
{
    double s = 4.20863 * a - sqrt(9.59217 + 41.6808 * a + 17.7126 * a * a) + 4.09712;
    return 1.0 - s * s;
}

Test(media_scene, subsurface_medium_has_the_formula_coefficients)
{
    Scene s;
    load_ok("\"materials\": {\"skin\": {\"type\": \"principled\", \"base_color\": [0.8, 0.5, 0.2],"
            " \"subsurface\": 0.7, \"subsurface_radius\": [1, 0.5, 0.25]}}, "
            "\"objects\": [{\"obj\": \"cube.obj\", \"material\": \"skin\"}]",
            &s);
    const Material *m = &s.data.materials[0];
    cr_expect_eq(m->subsurface, 0.7f);
    cr_expect_eq(m->flags & MATERIAL_FLAG_MEDIUM_INTERFACE, MATERIAL_FLAG_MEDIUM_INTERFACE);
    cr_assert_eq(m->interior, 1u);
    cr_expect_eq(m->exterior, MEDIUM_SLOT_WORLD);
    cr_assert_eq(s.data.num_media, 1);
    const Medium *md = &s.data.media[0];
    const double colour[3] = {0.8, 0.5, 0.2}, radius[3] = {1, 0.5, 0.25};
    for (int c = 0; c < 3; c++) {
        double sigma_t = 1.0 / radius[c], alpha = van_de_hulst(colour[c]);
        cr_expect(alpha > 0.0 && alpha < 1.0, "alpha %g", alpha);
        cr_expect(fabs(md->sigma_s.s[c] - alpha * sigma_t) < 1e-5 * sigma_t,
                  "channel %d: sigma_s %g, expected %g", c, md->sigma_s.s[c], alpha * sigma_t);
        cr_expect(fabs(md->sigma_a.s[c] - (1.0 - alpha) * sigma_t) < 1e-5 * sigma_t,
                  "channel %d: sigma_a %g, expected %g", c, md->sigma_a.s[c],
                  (1.0 - alpha) * sigma_t);
    }
    cr_expect_eq(md->sigma_a.s[3], 0.0f, "g 0");
    scene_free(&s);
    /* The inversion's ends: a black colour absorbs everything, white loses (almost) nothing. */
    cr_expect(subsurface_albedo(0.0f) >= 0.0f && subsurface_albedo(0.0f) < 1e-4f, "%g",
              subsurface_albedo(0.0f));
    cr_expect(subsurface_albedo(1.0f) > 0.999f && subsurface_albedo(1.0f) < 1.0f);
}

Test(media_scene, subsurface_radius_defaults_to_blenders)
{
    Scene s;
    load_ok("\"materials\": {\"skin\": {\"type\": \"principled\", \"base_color\": 0.5, "
            "\"subsurface\": 1}}, \"objects\": [{\"obj\": \"cube.obj\", \"material\": \"skin\"}]",
            &s);
    const Medium *md = &s.data.media[0];
    const double radius[3] = {0.05, 0.01, 0.005};
    for (int c = 0; c < 3; c++) {
        double t = md->sigma_s.s[c] + md->sigma_a.s[c];
        cr_expect(fabs(t - 1.0 / radius[c]) < 1e-4 / radius[c], "sigma_t %g, expected %g", t,
                  1.0 / radius[c]);
    }
    scene_free(&s);
    load_ok("\"materials\": {\"p\": {\"type\": \"principled\"}}", &s);
    cr_expect_eq(s.data.num_media, 0, "subsurface 0: no medium");
    cr_expect_eq(s.data.materials[0].flags & MATERIAL_FLAG_MEDIUM_INTERFACE, 0u);
    scene_free(&s);
}

/* ---- The scene hash ------------------------------------------------------------------------- */

static uint64_t hash_of(const char *json)
{
    Scene s;
    load_ok(json, &s);
    uint64_t h = scene_hash(&s);
    scene_free(&s);
    return h;
}

Test(media_scene, scene_hash_sees_the_media)
{
    const char *fog = "\"media\": {\"fog\": {\"type\": \"homogeneous\", \"sigma_s\": 1}}, "
                      "\"objects\": [{\"obj\": \"cube.obj\", \"interior\": \"fog\"}]";
    uint64_t h = hash_of(fog);
    cr_expect_eq(hash_of(fog), h);
    cr_expect_neq(hash_of("\"media\": {\"fog\": {\"type\": \"homogeneous\", \"sigma_s\": 1.01}}, "
                          "\"objects\": [{\"obj\": \"cube.obj\", \"interior\": \"fog\"}]"),
                  h, "a coefficient");
    cr_expect_neq(hash_of("\"media\": {\"fog\": {\"type\": \"homogeneous\", \"sigma_s\": 1}}, "
                          "\"objects\": [{\"obj\": \"cube.obj\", \"exterior\": \"fog\"}]"),
                  h, "interior against exterior (the materials' slots)");
    cr_expect_neq(hash_of("\"media\": {\"fog\": {\"type\": \"homogeneous\", \"sigma_s\": 1}}, "
                          "\"objects\": [{\"obj\": \"cube.obj\", \"interior\": \"fog\"}], "
                          "\"medium\": \"fog\""),
                  h, "the world medium");
}

/* ---- Bad input: one line naming the key ----------------------------------------------------- */

#define FOG(body) "\"media\": {\"fog\": {\"type\": \"homogeneous\"" body "}}"

Test(media_scene, bad_g_outside_minus_one_one)
{
    refused(FOG(", \"g\": 1.2"), "media.fog.g: 1.2 is outside (-1, 1)");
    refused(FOG(", \"g\": -1"), "media.fog.g: -1 is outside (-1, 1)");
}

Test(media_scene, bad_negative_coefficient)
{
    refused(FOG(", \"sigma_a\": [0.1, -0.2, 0.3]"), "media.fog.sigma_a: [0.1, -0.2, 0.3]");
}

Test(media_scene, bad_infinite_coefficient)
{
    refused(FOG(", \"sigma_s\": 1e999"), "media.fog.sigma_s: inf is not a finite number");
}

Test(media_scene, bad_negative_scale)
{
    refused(FOG(", \"scale\": -2"), "media.fog.scale: -2 must be >= 0");
}

Test(media_scene, bad_scale_overflowing_the_coefficient)
{
    refused(FOG(", \"sigma_a\": 1e30, \"scale\": 1e30"), "media.fog.sigma_a: [1e+30, 1e+30, 1e+30] "
                                                          "times the scale 1e+30 is not finite");
}

Test(media_scene, bad_negative_emission)
{
    refused(FOG(", \"emission\": -1"), "media.fog.emission:");
}

Test(media_scene, bad_coefficient_type)
{
    refused(FOG(", \"sigma_s\": \"thick\""), "media.fog.sigma_s: expected an array of 3 numbers");
}

Test(media_scene, bad_unknown_key)
{
    refused(FOG(", \"density\": 1"), "media.fog.density: unknown key");
}

Test(media_scene, bad_type)
{
    refused("\"media\": {\"fog\": {\"type\": \"cloud\"}}",
            "media.fog.type: \"cloud\" is not a medium type");
    refused("\"media\": {\"fog\": {\"sigma_s\": 1}}", "media.fog.type: missing");
    refused("\"media\": {\"fog\": 3}", "media.fog: expected an object");
    refused("\"media\": [1]", "media: expected an object of named media");
}

Test(media_scene, bad_grid_albedo_above_one)
{
    refused("\"media\": {\"smoke\": {\"type\": \"grid\", \"file\": \"s.vol\", \"albedo\": 1.5}}",
            "media.smoke.albedo: [1.5, 1.5, 1.5] is outside [0, 1]");
}

Test(media_scene, bad_grid_negative_density_scale)
{
    refused("\"media\": {\"smoke\": {\"type\": \"grid\", \"file\": \"s.vol\", "
            "\"density_scale\": -1}}",
            "media.smoke.density_scale: -1 must be >= 0");
}

Test(media_scene, bad_grid_without_file)
{
    refused("\"media\": {\"smoke\": {\"type\": \"grid\"}}", "media.smoke.file: missing");
}

Test(media_scene, bad_grid_missing_file)
{
    refused("\"media\": {\"smoke\": {\"type\": \"grid\", \"file\": \"nowhere.vol\"}}",
            "media.smoke.file: ");
    refused("\"media\": {\"smoke\": {\"type\": \"grid\", \"file\": \"nowhere.vol\"}}",
            "nowhere.vol");
}

Test(media_scene, bad_grid_corrupt_file)
{
    write_meshes();
    write_file("bad.vol", "VOL\3 this is not a grid");
    refused("\"media\": {\"smoke\": {\"type\": \"grid\", \"file\": \"bad.vol\"}}",
            "media.smoke.file: ");
}

Test(media_scene, bad_grid_name_not_in_file)
{
    write_meshes();
    write_vol("smoke.vol", 2, ramp);
    refused("\"media\": {\"smoke\": {\"type\": \"grid\", \"file\": \"smoke.vol\", "
            "\"grid\": \"temperature\"}}",
            "media.smoke.grid: ");
}

Test(media_scene, bad_grid_singular_transform)
{
    refused("\"media\": {\"smoke\": {\"type\": \"grid\", \"file\": \"s.vol\", \"transform\": "
            "[{\"scale\": [1, 0, 1]}]}}",
            "media.smoke.transform");
}

Test(media_scene, bad_world_medium_name)
{
    refused(FOG("") ", \"medium\": \"smoke\"", "medium: unknown medium \"smoke\"");
    refused(FOG("") ", \"medium\": 1", "medium: expected a medium name");
}

Test(media_scene, bad_camera_medium_name)
{
    refused(FOG("") ", \"objects\": [{\"obj\": \"cube.obj\"}], \"camera\": {\"eye\": [0, 0, 5], "
                    "\"target\": [0, 0, 0], \"medium\": \"smoke\"}",
            "camera.medium: unknown medium \"smoke\"");
}

Test(media_scene, bad_interior_name)
{
    refused(FOG("") ", \"objects\": [{\"obj\": \"cube.obj\", \"interior\": \"smoke\"}]",
            "objects[0].interior: unknown medium \"smoke\" (not in \"media\")");
}

Test(media_scene, bad_exterior_type)
{
    refused(FOG("") ", \"objects\": [{\"obj\": \"cube.obj\", \"exterior\": [1]}]",
            "objects[0].exterior: expected a medium name (string)");
}

Test(media_scene, bad_interior_on_an_open_mesh)
{
    refused(FOG("") ", \"objects\": [{\"obj\": \"cube.obj\"}, {\"obj\": \"open.obj\", "
                    "\"interior\": \"fog\"}]",
            "objects[1].interior: the mesh is not closed (3 edges with one face); a medium needs "
            "a closed surface");
}

Test(media_scene, bad_interior_on_a_mesh_with_a_fin)
{
    refused(FOG("") ", \"objects\": [{\"obj\": \"finned.obj\", \"interior\": \"fog\"}]",
            "objects[0].interior: the mesh is not closed (2 edges with one face)");
}

Test(media_scene, bad_subsurface_on_an_open_mesh)
{
    refused("\"materials\": {\"skin\": {\"type\": \"principled\", \"subsurface\": 0.5}}, "
            "\"objects\": [{\"obj\": \"open.obj\", \"material\": \"skin\"}]",
            "objects[0] (a material with subsurface): the mesh is not closed (3 edges with one "
            "face)");
}

Test(media_scene, bad_interior_with_subsurface)
{
    refused(FOG("") ", \"materials\": {\"skin\": {\"type\": \"principled\", \"subsurface\": 0.5}}"
                    ", \"objects\": [{\"obj\": \"cube.obj\", \"material\": \"skin\", "
                    "\"interior\": \"fog\"}]",
            "objects[0].interior: its material already fills the inside (subsurface)");
}

Test(media_scene, bad_interior_with_absorption)
{
    refused(FOG("") ", \"materials\": {\"g\": {\"type\": \"dielectric\", \"absorption\": 1}}"
                    ", \"objects\": [{\"obj\": \"cube.obj\", \"material\": \"g\", "
                    "\"interior\": \"fog\"}]",
            "objects[0].interior: its material already fills the inside (absorption)");
}

Test(media_scene, bad_interface_with_parameters)
{
    refused("\"materials\": {\"box\": {\"type\": \"interface\", \"emission\": 1}}",
            "materials.box.emission: unknown key (accepted: type)");
}

Test(media_scene, bad_interface_inside_a_mix)
{
    refused("\"materials\": {\"box\": {\"type\": \"interface\"}, \"d\": {\"type\": \"diffuse\"}, "
            "\"m\": {\"type\": \"mix\", \"a\": \"d\", \"b\": \"box\"}}",
            "materials.m.b: \"box\" is an interface, which cannot be mixed");
}

Test(media_scene, bad_subsurface_weight)
{
    refused("\"materials\": {\"p\": {\"type\": \"principled\", \"subsurface\": 1.5}}",
            "materials.p.subsurface: 1.5 is out of range [0, 1]");
}

Test(media_scene, bad_subsurface_radius)
{
    refused("\"materials\": {\"p\": {\"type\": \"principled\", \"subsurface\": 1, "
            "\"subsurface_radius\": [1, 0, 1]}}",
            "materials.p.subsurface_radius: [1, 0, 1] must be > 0");
}

Test(media_scene, bad_black_holes_with_media)
{
    refused(FOG("") ", \"black_holes\": [{\"position\": [5, 5, 5], \"mass\": 0.1}]",
            "black_holes: not rendered together with media");
    refused("\"materials\": {\"p\": {\"type\": \"principled\", \"subsurface\": 1}}, "
            "\"black_holes\": [{\"position\": [5, 5, 5], \"mass\": 0.1}]",
            "materials.p.subsurface");
}

/* ---- Rendering ------------------------------------------------------------------------------ */

/* A fog box in front of a white sky, seen through an interface: the fog darkens the middle (it
 * absorbs), and the border, which misses the box, stays the sky. */
Test(media_scene, a_fog_box_renders_darker_than_the_sky, .timeout = 1200)
{
    write_meshes();
    const char *path = write_file(
        "fogbox.json",
        "{\"camera\": {\"eye\": [0, 0, 6], \"target\": [0, 0, 0], \"fov_y\": 40}, "
        "\"film\": {\"width\": 16, \"height\": 16}, \"background\": [1, 1, 1], "
        "\"media\": {\"fog\": {\"type\": \"homogeneous\", \"sigma_a\": 1, \"sigma_s\": 0.5}}, "
        "\"materials\": {\"box\": {\"type\": \"interface\"}}, "
        "\"objects\": [{\"obj\": \"cube.obj\", \"material\": \"box\", \"interior\": \"fog\"}]}");
    RenderFixture f;
    render_fixture_open(&f, path, 16, 16);
    float *rgb = render_fixture_render(&f, (RenderSettings){.spp = 16, .max_depth = 8, .seed = 1},
                                       NULL);
    float centre = rgb[3 * (8 * 16 + 8) + 1], corner = rgb[1];
    cr_expect(fabsf(corner - 1.0f) < 1e-4f, "the sky through no fog: %g", corner);
    /* Through 2 units of sigma_a 1 at least exp(-2) is absorbed; scattering only loses more
     * (a white sky all around, but the absorption takes its share on every path). */
    cr_expect(centre > 0.0f && centre < 0.5f, "through the fog: %g", centre);
    free(rgb);
    render_fixture_close(&f);
}

/* A glass with absorption in fog (an exterior alone): its absorption is still its inside, one
 * medium for every object asking the same. */
Test(media_scene, absorption_stays_the_interior_when_only_the_exterior_is_given)
{
    Scene s;
    load_ok("\"media\": {\"fog\": {\"type\": \"homogeneous\", \"sigma_s\": 0.1}}, \"medium\": "
            "\"fog\", \"materials\": {\"glass\": {\"type\": \"dielectric\", \"absorption\": [1, 2, "
            "3]}}, \"objects\": [{\"obj\": \"cube.obj\", \"material\": \"glass\", \"exterior\": "
            "\"fog\"}, {\"obj\": \"seams.obj\", \"material\": \"glass\", \"exterior\": \"fog\"}]",
            &s);
    const Material *m = &s.data.materials[s.data.material_ids[0]];
    cr_expect_eq(m->exterior, 1u);
    cr_assert(m->interior >= 2 && m->interior <= s.data.num_media, "interior %u", m->interior);
    expect_rgb(s.data.media[m->interior - 1].sigma_a, 1, 2, 3, "the absorption medium");
    cr_expect_eq(s.data.material_ids[12], s.data.material_ids[0], "one copy for both objects");
    uint32_t absorbing = 0;
    for (uint32_t i = 0; i < s.data.num_media; i++)
        absorbing += s.data.media[i].sigma_a.s[0] == 1.0f;
    cr_expect_eq(absorbing, 2u, "the copy's and materials.glass's own (unused here), not one "
                                "per object");
    scene_free(&s);
}

/* An inside-out mesh (every front facing in) is legal but holds its medium outside: said once. */
Test(media_scene, an_inside_out_interior_is_warned_about)
{
    Scene s;
    int before = warning_count();
    load_ok(FOG("") ", \"objects\": [{\"obj\": \"cube.obj\", \"interior\": \"fog\"}]", &s);
    cr_expect_eq(warning_count(), before, "an outward cube: no warning (%d, %d)", before, warning_count());
    scene_free(&s);
    load_ok(FOG("") ", \"objects\": [{\"obj\": \"inside_out.obj\", \"interior\": \"fog\"}]", &s);
    cr_expect_eq(warning_count(), before + 1, "the inside-out cube is warned about");
    scene_free(&s);
}

/* The same medium on both sides of an open mesh (a floor inside a fog-filled world) is no
 * boundary at all: allowed, and the copy carries it on both sides. */
Test(media_scene, an_open_mesh_in_one_medium_on_both_sides_is_allowed)
{
    Scene s;
    load_ok(FOG("") ", \"medium\": \"fog\", \"objects\": [{\"obj\": \"open.obj\", "
                    "\"interior\": \"fog\"}]",
            &s);
    const Material *m = &s.data.materials[s.data.material_ids[0]];
    cr_expect_eq(m->interior, 1u);
    cr_expect_eq(m->exterior, MEDIUM_SLOT_WORLD);
    scene_free(&s);
    load_ok(FOG("") ", \"objects\": [{\"obj\": \"open.obj\", \"interior\": \"fog\", "
                    "\"exterior\": \"fog\"}]",
            &s);
    scene_free(&s);
    refused(FOG("") ", \"objects\": [{\"obj\": \"open.obj\", \"interior\": \"fog\"}]",
            "objects[0].interior: the mesh is not closed");
}

/* A subsurface object in fog: its copy keeps the walk medium inside and has the fog outside. */
Test(media_scene, subsurface_with_an_exterior_keeps_its_walk_medium)
{
    Scene s;
    load_ok(FOG("") ", \"materials\": {\"skin\": {\"type\": \"principled\", \"subsurface\": 1}}, "
                    "\"objects\": [{\"obj\": \"cube.obj\", \"material\": \"skin\", \"exterior\": "
                    "\"fog\"}]",
            &s);
    cr_assert_eq(s.data.num_media, 2, "fog, then the walk medium");
    const Material *m = &s.data.materials[s.data.material_ids[0]];
    cr_expect_eq(m->interior, 2u, "the walk medium");
    cr_expect_eq(m->exterior, 1u, "the fog");
    cr_expect_eq(s.data.materials[0].exterior, MEDIUM_SLOT_WORLD, "the material itself unchanged");
    scene_free(&s);
}
