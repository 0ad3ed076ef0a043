// SPDX-License-Identifier: MIT
/* Bad media input (shared/DESIGN.md "Media"; host/scene/media_json.c, media_load.c,
 * object_media.c): every bad value, name, grid file and mesh is refused with one line naming its
 * key (test_media_scene.c has what is accepted). */
#include "media_scene_fixture.h"

/* ---- Bad input: one line naming the key ----------------------------------------------------- */

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
    refused(FOG(", \"emission\": -1"), "media.fog.emission: [-1, -1, -1] must be finite and >= 0");
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
    refused("\"media\": {\"smoke\": {\"type\": \"grid\", \"file\": \"smoke.vol\", "
            "\"grid\": \"temperature\"}}",
            "there is no grid 'temperature'");
}

Test(media_scene, bad_grid_singular_transform)
{
    refused("\"media\": {\"smoke\": {\"type\": \"grid\", \"file\": \"s.vol\", \"transform\": "
            "[{\"scale\": [1, 0, 1]}]}}",
            "media.smoke.transform[0].scale: [1, 0, 1] has a zero component");
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
            "objects[0] (the triangles of its subsurface materials): the mesh is not closed (3 edges with one "
            "face)");
}

/* Only the subsurface material's triangles must close: the open floor beside the ball is fine,
 * and the ball gets its walk medium. */
Test(media_scene, subsurface_closes_per_material)
{
    Scene s;
    load_ok("\"materials\": {\"skin\": {\"type\": \"principled\", \"subsurface\": 0.5}}, "
            "\"objects\": [{\"obj\": \"room.obj\"}]", &s);
    uint32_t walkers = 0;
    for (uint32_t i = 0; i < s.data.num_materials; i++)
        walkers += s.data.materials[i].subsurface > 0.0f &&
                   (s.data.materials[i].flags & MATERIAL_FLAG_MEDIUM_INTERFACE);
    cr_expect_eq(walkers, 1u, "%u subsurface materials with a walk medium", walkers);
    scene_free(&s);
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
            "black_holes: not rendered together with media (materials.p.subsurface is one)");
}

Test(media_scene, bad_grid_sigma_t_overflows_with_density_scale)
{
    refused("\"media\": {\"smoke\": {\"type\": \"grid\", \"file\": \"s.vol\", \"sigma_t\": 1e30, "
            "\"density_scale\": 1e30}}",
            "media.smoke.sigma_t: [1e+30, 1e+30, 1e+30] times the scale 1e+30 is not finite");
}
