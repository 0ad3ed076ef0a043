// SPDX-License-Identifier: MIT
/* The scene format of media (shared/DESIGN.md "Media"; host/scene/media_json.c, media_load.c,
 * object_media.c): the "media" block's keys land in the kernels' Medium with DESIGN's defaults,
 * the world's and the camera's medium, objects' interior / exterior as derived materials (other
 * objects of the same material keep theirs, instanced meshes too), closed-mesh checks, the
 * "interface" material, principled subsurface's walk medium against Van de Hulst's formula, the
 * scene hash and renders (test_media_scene_bad_input.c: every bad value). */
#include "scene/object_media.h"
#include "scene/scene.h"
#include "scene/scene_hash.h"
#include "scene/scene_media.h"
#include "media_scene_fixture.h"
#include "support.h"

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
    cr_assert(mesh_open_edges(&s.data, 0, s.data.num_triangles, NULL, &one, &many));
    cr_expect(s.data.num_vertices > 8, "the seams split vertices (%u)", s.data.num_vertices);
    cr_expect_eq(one, 0u, "a cube split at its normals' seams is closed");
    cr_expect_eq(many, 0u);
    cr_assert(mesh_open_edges(&s.data, 0, 11, NULL, &one, &many));
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

/* A medium that emits is a light: a scene lit by it alone gets no default rig (no sky and sun over
 * it, no "has no light" warning); the same scene with a medium that does not emit does. */
Test(media_scene, an_emissive_medium_counts_as_light_for_the_default_rig)
{
    Scene s;
    load_ok("\"media\": {\"glow\": {\"type\": \"homogeneous\", \"sigma_a\": 0.5, \"emission\": 2}}, "
            "\"materials\": {\"skin\": {\"type\": \"interface\"}}, "
            "\"objects\": [{\"obj\": \"cube.obj\", \"material\": \"skin\", \"interior\": \"glow\"}]",
            &s);
    cr_expect_eq(scene_default_rig_choice(&s), RIG_NONE);
    scene_free(&s);
    load_ok("\"media\": {\"dark\": {\"type\": \"homogeneous\", \"sigma_a\": 0.5}}, "
            "\"materials\": {\"skin\": {\"type\": \"interface\"}}, "
            "\"objects\": [{\"obj\": \"cube.obj\", \"material\": \"skin\", \"interior\": \"dark\"}]",
            &s);
    cr_expect_neq(scene_default_rig_choice(&s), RIG_NONE, "nothing lights this one");
    scene_free(&s);
}
