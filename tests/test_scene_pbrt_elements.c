// SPDX-License-Identifier: MIT
/* The pbrt-v4 importer's mapping of each element (host/scene/import_pbrt_*.c) onto pt's scene
 * description, read back from the SceneDesc: materials (roughness remapping, anisotropy, named
 * metals, the nearest-model mappings, mix), textures, lights (units, power, directions mirrored
 * into pt's world), shapes (sphere and disk uvs and fronts, ReverseOrientation, bilinear patches,
 * alpha), the equal-area environment conversion, and pbrt's defaults. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <stdio.h>
#include <string.h>

#include "io/image_io.h"
#include "scene/scene.h"
#include "support.h"

#define PI 3.14159265358979323846

static void load_desc(const char *world, SceneDesc *d)
{
    char text[8192];
    snprintf(text, sizeof text, "Film \"rgb\" \"integer xresolution\" 16 \"integer yresolution\" 16\n"
             "WorldBegin\n%s", world);
    const char *path = test_write_file(test_temp_dir(), "scene.pbrt", text);
    Error err = {0};
    cr_assert(scene_desc_load(path, d, &err), "%s", err.message);
}

static const Material *material(const SceneDesc *d, const char *name)
{
    int i = material_desc_find(d->materials, d->num_materials, name);
    cr_assert(i >= 0, "no material %s", name);
    return &d->materials[i].m;
}

static const char *const tri = "Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0]\n";

Test(pbrt_elements, conductor_roughness_named_metals_and_anisotropy)
{
    SceneDesc d;
    char world[2048];
    snprintf(world, sizeof world,
             "MakeNamedMaterial \"au\" \"string type\" \"conductor\" \"spectrum eta\" \"metal-Au-eta\"\n"
             "  \"spectrum k\" \"metal-Au-k\" \"float roughness\" 0.0625\n"
             "MakeNamedMaterial \"raw\" \"string type\" \"conductor\" \"float roughness\" 0.25 \"bool remaproughness\" false\n"
             "MakeNamedMaterial \"aniso\" \"string type\" \"conductor\" \"float uroughness\" 0.16 \"float vroughness\" 0.01\n"
             "MakeNamedMaterial \"cu\" \"string type\" \"conductor\"\n"
             "NamedMaterial \"au\" %s", tri);
    load_desc(world, &d);
    const Material *au = material(&d, "au");
    cr_expect(au->type == MATERIAL_CONDUCTOR);
    cr_expect(au->eta.s[0] == 0.143f && au->eta.s[2] == 1.442f && au->k.s[0] == 3.983f, "metal-Au RGB");
    cr_expect(fabsf(au->roughness - 0.5f) < 1e-6f, "remapped: alpha = sqrt(0.0625) = 0.25 = r^2 -> r 0.5, "
              "not %g", au->roughness);
    cr_expect(fabsf(material(&d, "raw")->roughness - 0.5f) < 1e-6f, "not remapped: alpha 0.25 -> r 0.5");
    const Material *an = material(&d, "aniso");
    /* alpha_u = 0.4, alpha_v = 0.1: r^4 = 0.04, alpha_v / alpha_u = 0.25 = 1 - 0.9 a */
    cr_expect(fabsf(an->roughness - powf(0.04f, 0.25f)) < 1e-6f, "%g", an->roughness);
    cr_expect(fabsf(an->anisotropy - 0.75f / 0.9f) < 1e-6f, "%g", an->anisotropy);
    cr_expect(material(&d, "cu")->eta.s[1] == 0.924f, "pbrt's default conductor is copper");
    scene_desc_free(&d);
}

Test(pbrt_elements, dielectrics_coated_and_mix)
{
    SceneDesc d;
    char world[2048];
    snprintf(world, sizeof world,
             "MakeNamedMaterial \"glass\" \"string type\" \"dielectric\" \"float eta\" 1.33 \"float roughness\" 0.01\n"
             "MakeNamedMaterial \"thin\" \"string type\" \"thindielectric\" \"float eta\" 1.5\n"
             "MakeNamedMaterial \"coat\" \"string type\" \"coateddiffuse\" \"rgb reflectance\" [0.1 0.2 0.3]\n"
             "MakeNamedMaterial \"mix\" \"string type\" \"mix\" \"string materials\" [\"glass\" \"coat\"] \"float amount\" 0.25\n"
             "MakeNamedMaterial \"none\" \"string type\" \"interface\"\n"
             "NamedMaterial \"mix\" %s", tri);
    load_desc(world, &d);
    const Material *g = material(&d, "glass");
    cr_expect(g->type == MATERIAL_DIELECTRIC && fabsf(g->ior - 1.33f) < 1e-6f);
    cr_expect(fabsf(g->roughness - powf(0.01f, 0.25f)) < 1e-6f);
    const Material *t = material(&d, "thin");
    cr_expect(t->type == MATERIAL_CONDUCTOR && (t->flags & MATERIAL_FLAG_FRESNEL_ONE), "a mirror");
    cr_expect(fabsf(t->opacity - 2.0f * 0.04f / 1.04f) < 1e-6f, "opacity = R_thin = 2R/(1+R), %g", t->opacity);
    const Material *c = material(&d, "coat");
    cr_expect(c->type == MATERIAL_PRINCIPLED && c->metallic == 0.0f && c->base.s[2] == 0.3f);
    cr_expect(fabsf(c->ior - 1.5f) < 1e-6f, "the coat's Fresnel: eta 1.5");
    const Material *m = material(&d, "mix");
    cr_expect(m->type == MATERIAL_MIX && m->weight == 0.25f, "pbrt picks materials[1] with probability amount");
    cr_expect(m->mix_a == (uint32_t)material_desc_find(d.materials, d.num_materials, "glass"));
    cr_expect(m->mix_b == (uint32_t)material_desc_find(d.materials, d.num_materials, "coat"));
    cr_expect(material(&d, "none")->opacity == 0.0f, "interface: invisible");
    scene_desc_free(&d);
}

Test(pbrt_elements, textures_imagemap_scale_and_constant)
{
    SceneDesc d;
    const char *dir = test_temp_dir();
    test_write_file(dir, "t.png", "not read by scene_desc_load");
    test_write_file(dir, "t.jpg", "not read either");
    char world[2048];
    snprintf(world, sizeof world,
             "Texture \"img\" \"spectrum\" \"imagemap\" \"string filename\" \"t.png\" \"float uscale\" 4\n"
             "Texture \"half\" \"spectrum\" \"scale\" \"texture tex\" \"img\" \"float scale\" 0.5\n"
             "Texture \"k\" \"float\" \"constant\" \"float value\" 0.3\n"
             "Texture \"jpg\" \"spectrum\" \"imagemap\" \"string filename\" \"t.jpg\"\n"
             "Material \"diffuse\" \"texture reflectance\" \"half\"\n%s"
             "Material \"diffuse\" \"texture reflectance\" \"k\"\n%s", tri, tri);
    load_desc(world, &d);
    cr_assert_eq(d.num_textures, 3, "the image, its scaled copy and the JPEG");
    cr_expect(d.textures[0].encoding == TEXTURE_ENCODING_DEFAULT, "PNG: pt's default, sRGB for 8 bits as pbrt");
    cr_expect(d.textures[2].encoding == TEXTURE_ENCODING_LINEAR, "pbrt reads other files linear");
    const Material *a = &d.materials[0].m, *b = &d.materials[1].m;
    cr_assert(a->tex[MATERIAL_TEX_BASE] != NO_TEXTURE);
    const TextureDesc *t = &d.textures[a->tex[MATERIAL_TEX_BASE]];
    cr_expect(strstr(t->path, "t.png") && t->sampling.has_scale && t->sampling.scale == 0.5f);
    cr_expect(t->sampling.has_transform && t->sampling.transform[0] == 4.0f, "uscale 4");
    cr_expect(b->tex[MATERIAL_TEX_BASE] == NO_TEXTURE && fabsf(b->base.s[1] - 0.3f) < 1e-6f,
              "a float constant texture is its value");
    scene_desc_free(&d);
}

Test(pbrt_elements, lights_units_and_directions)
{
    SceneDesc d;
    char world[2048];
    snprintf(world, sizeof world,
             "LightSource \"point\" \"rgb I\" [1 2 3] \"point3 from\" [1 2 3]\n"
             "LightSource \"point\" \"rgb I\" [1 1 1] \"float power\" 100\n"
             "Translate 1 0 0 LightSource \"spot\" \"rgb I\" [1 1 1] \"point3 to\" [0 -1 0] \"float coneangle\" 30 \"float conedelta\" 10\n"
             "LightSource \"distant\" \"rgb L\" [2 2 2] \"float scale\" 3 \"point3 from\" [1 0 0] \"point3 to\" [0 0 0]\n"
             "LightSource \"infinite\" \"rgb L\" [0.1 0.2 0.3] \"float scale\" 2\n%s", tri);
    load_desc(world, &d);
    cr_assert_eq(d.num_lights, 4);
    const AnalyticLight *l = d.lights;
    cr_expect(l[0].type == LIGHT_POINT && l[0].position.s[0] == -1.0f && l[0].position.s[1] == 2.0f,
              "pbrt x is pt -x");
    cr_expect(l[0].color.s[2] == 3.0f);
    cr_expect(fabsf(l[1].color.s[0] - 100.0f / (4.0f * (float)PI)) < 1e-4f, "power / 4 pi");
    cr_expect(l[2].type == LIGHT_SPOT && l[2].position.s[0] == -1.0f && l[2].axis.s[1] < -0.99f);
    cr_expect(fabsf(l[2].params.s[0] - 30.0f * (float)PI / 180.0f) < 1e-5f, "cone 30");
    cr_expect(fabsf(l[2].params.s[1] - 20.0f * (float)PI / 180.0f) < 1e-5f, "falloff 30 - 10");
    cr_expect(l[3].type == LIGHT_DIRECTIONAL && l[3].position.s[0] > 0.99f && l[3].color.s[0] == 6.0f,
              "distant from pbrt +x travels toward pbrt -x = pt +x; irradiance L x scale");
    cr_expect(fabsf(d.background[2] - 0.6f) < 1e-6f, "infinite L x scale is the background");
    scene_desc_free(&d);
}

/* Shapes read back through the flattened scene. */
static void load_scene(const char *world, Scene *s)
{
    char text[8192];
    snprintf(text, sizeof text, "WorldBegin\n%s", world);
    const char *path = test_write_file(test_temp_dir(), "scene.pbrt", text);
    Error err = {0};
    cr_assert(scene_load_with(path, INSTANCING_NEVER, s, &err), "%s", err.message);
}

/* The geometric normal of triangle t (counter-clockwise front, pt's convention). */
static void face_normal(const SceneData *d, uint32_t t, float n[3])
{
    const float *p0 = d->positions[d->triangles[t].v.s[0]].s, *p1 = d->positions[d->triangles[t].v.s[1]].s,
                *p2 = d->positions[d->triangles[t].v.s[2]].s;
    float e1[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]}, e2[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
}

Test(pbrt_elements, disk_faces_plus_z_and_reverse_orientation_flips_it)
{
    Scene s;
    load_scene("Shape \"disk\" \"float height\" 2 \"float radius\" 3\n"
               "ReverseOrientation Shape \"disk\" \"float height\" -2\n", &s);
    const SceneData *d = &s.data;
    float n[3];
    face_normal(d, 0, n);
    cr_expect(n[2] > 0.0f, "pbrt's disk faces +z");
    face_normal(d, d->num_triangles - 1, n);
    cr_expect(n[2] < 0.0f, "ReverseOrientation flips it");
    float zmax = -1e9f, rmax = 0.0f;
    for (uint32_t v = 0; v < d->num_vertices; v++) {
        zmax = fmaxf(zmax, d->positions[v].s[2]);
        rmax = fmaxf(rmax, hypotf(d->positions[v].s[0], d->positions[v].s[1]));
    }
    cr_expect(zmax == 2.0f && fabsf(rmax - 3.0f) < 1e-5f, "height and radius");
    scene_free(&s);
}

Test(pbrt_elements, sphere_uv_v_grows_toward_plus_z)
{
    Scene s;
    load_scene("Shape \"sphere\" \"float radius\" 2\n", &s);
    const SceneData *d = &s.data;
    for (uint32_t v = 0; v < d->num_vertices; v += 97) {
        float z = d->positions[v].s[2];
        float expected = 1.0f - acosf(fmaxf(-1.0f, fminf(1.0f, z / 2.0f))) / (float)PI;
        cr_expect(fabsf(d->uvs[v].s[1] - expected) < 1e-3f, "pbrt v = (theta - pi) / -pi at z %g: %g", z,
                  d->uvs[v].s[1]);
    }
    scene_free(&s);
}

Test(pbrt_elements, bilinear_patch_two_triangles_and_alpha_opacity)
{
    Scene s;
    load_scene("Shape \"bilinearmesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0 1 1 0] \"float alpha\" 0.25\n", &s);
    const SceneData *d = &s.data;
    cr_expect_eq(d->num_triangles, 2);
    float n[3];
    for (uint32_t t = 0; t < 2; t++) {
        face_normal(d, t, n);
        /* pbrt: n = dpdu x dpdv = +z; the mirror (x -> -x) keeps a +z normal (and the front) */
        cr_expect(n[2] > 0.0f, "triangle %u faces %g", t, n[2]);
    }
    cr_expect(d->materials[d->material_ids[0]].opacity == 0.25f, "alpha 0.25 is opacity 0.25");
    scene_free(&s);
}

/* An equal-area map whose octants are coloured by the light-space signs (red: +x, green: +y, blue:
 * +z), under the usual z-up-to-y-up "Rotate -90 1 0 0": the converted lat-long map must show each
 * colour where pbrt would (pt direction -> pbrt world (x -> -x) -> light space). */
Test(pbrt_elements, equal_area_environment_is_converted_with_its_orientation)
{
    const char *dir = test_temp_dir();
    char cache[1100];
    snprintf(cache, sizeof cache, "%s/cache", dir);
    setenv("XDG_CACHE_HOME", cache, 1);
    enum { N = 64 };
    static float square[N * N * 3];
    for (int y = 0; y < N; y++)
        for (int x = 0; x < N; x++) {
            double u = 2.0 * (x + 0.5) / N - 1.0, v = 2.0 * (y + 0.5) / N - 1.0;
            float *t = &square[3 * (y * N + x)];
            t[0] = u > 0.0, t[1] = v > 0.0, t[2] = fabs(u) + fabs(v) < 1.0;
        }
    char exr[1100];
    snprintf(exr, sizeof exr, "%s/sky.exr", dir);
    Error err = {0};
    cr_assert(image_write_exr(exr, square, N, N, &err), "%s", err.message);
    SceneDesc d;
    char world[512];
    snprintf(world, sizeof world, "AttributeBegin Rotate -90 1 0 0\n"
             "LightSource \"infinite\" \"string filename\" \"sky.exr\" \"float scale\" 2\nAttributeEnd\n%s", tri);
    char text[1024];
    snprintf(text, sizeof text, "WorldBegin\n%s", world);
    cr_assert(scene_desc_load(test_write_file(dir, "scene.pbrt", text), &d, &err), "%s", err.message);
    cr_assert(strstr(d.environment, "/cache/pt/pbrt-env/"), "converted into the cache: %s", d.environment);
    cr_expect(d.environment_scale == 2.0f);
    float *map;
    int w, h;
    cr_assert(image_read_exr(d.environment, &map, &w, &h, &err), "%s", err.message);
    cr_expect(w == 2 * N && h == N);
    static const struct { double d[3]; float rgb[3]; } probes[] = {
        {{0.8, 0.3, -0.5}, {0, 1, 1}},  /* light (-0.8, 0.5, 0.3) */
        {{-0.5, -0.4, 0.6}, {1, 0, 0}}, /* light (0.5, -0.6, -0.4) */
        {{0.0, 1.0, 0.0}, {0, 0, 1}},   /* up is light +z (the diamond's centre) */
    };
    for (int i = 0; i < 3; i++) {
        const double *p = probes[i].d;
        double len = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
        double u = 0.5 + atan2(p[0] / len, -p[2] / len) / (2.0 * PI), v = acos(p[1] / len) / PI;
        int x = (int)(u * w), y = (int)(v * h);
        y = y >= h ? h - 1 : y;
        const float *t = &map[3 * (y * w + x)];
        for (int k = 0; k < 3 && i < 2; k++)
            cr_expect(fabsf(t[k] - probes[i].rgb[k]) < 0.01f, "probe %d channel %d: %g", i, k, t[k]);
        if (i == 2)
            cr_expect(t[2] > 0.99f, "up: blue %g", t[2]);
    }
    free(map);
    scene_desc_free(&d);
}

/* Spectra: a flat sampled spectrum keeps its value in every channel; a spectrum file (.spd) that is
 * high in the blue and zero in the red gives a blue RGB; blackbody light colours are normalised to
 * luminance 1. */
Test(pbrt_elements, sampled_spectra_files_and_blackbody)
{
    const char *dir = test_temp_dir();
    test_write_file(dir, "blue.spd", "# blue only\n380 1\n480 1\n520 0\n780 0\n");
    char text[2048];
    snprintf(text, sizeof text, "WorldBegin\n"
             "MakeNamedMaterial \"flat\" \"string type\" \"diffuse\" \"spectrum reflectance\" [300 .4 800 .4]\n"
             "MakeNamedMaterial \"blue\" \"string type\" \"diffuse\" \"spectrum reflectance\" \"blue.spd\"\n"
             "LightSource \"point\" \"blackbody I\" 2700\n%s", tri);
    SceneDesc d;
    Error err = {0};
    cr_assert(scene_desc_load(test_write_file(dir, "scene.pbrt", text), &d, &err), "%s", err.message);
    const Material *flat = material(&d, "flat"), *blue = material(&d, "blue");
    for (int k = 0; k < 3; k++)
        cr_expect(fabsf(flat->base.s[k] - 0.4f) < 1e-4f, "flat channel %d: %g", k, flat->base.s[k]);
    cr_expect(blue->base.s[2] > 0.8f && blue->base.s[0] < 0.05f, "blue: %g %g %g", blue->base.s[0],
              blue->base.s[1], blue->base.s[2]);
    const float *c = d.lights[0].color.s;
    cr_expect(fabsf(0.2126f * c[0] + 0.7152f * c[1] + 0.0722f * c[2] - 1.0f) < 1e-3f, "luminance 1");
    cr_expect(c[0] > c[1] && c[1] > c[2], "2700 K is warm: %g %g %g", c[0], c[1], c[2]);
    scene_desc_free(&d);
    Error e = {0};
    Scene s;
    snprintf(text, sizeof text, "WorldBegin\nMaterial \"diffuse\" \"spectrum reflectance\" \"nope.spd\"\n%s", tri);
    cr_expect_not(scene_load(test_write_file(dir, "bad.pbrt", text), &s, &e));
    cr_expect(strstr(e.message, "bad.pbrt:2: \"reflectance\": not a named spectrum") && strstr(e.message, "nope.spd"),
              "%s", e.message);
}
