// SPDX-License-Identifier: MIT
/* glTF import (io/gltf_loader.cc, scene/gltf_scene.c): the files of tools/make_gltf_tests.py
 * (every accessor component type, sparse accessors, strides, strips and fans, nested TRS and
 * matrix nodes, a mirroring node, a mesh placed by 3 nodes) as .gltf + .bin, .glb and base64 data
 * URIs give the same world-space triangles and material parameters as the generator's JSON + OBJ
 * scene and render like it; the 3-node mesh is one mesh with 3 instances; the file's camera and
 * light; {"gltf"} objects with transform and material; each broken file gives one line naming
 * the file and the JSON path. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>

#include "scene/gltf_scene.h"
#include "support.h"

/* The generator's files in a fresh folder (python3 is a build dependency: make runs the other
 * generators too). */
static const char *generate(void)
{
    const char *dir = test_temp_dir();
    char command[2048];
    snprintf(command, sizeof command, "python3 tools/make_gltf_tests.py '%s'", dir);
    cr_assert_eq(system(command), 0, "%s failed", command);
    return dir;
}

static const char *at(const char *dir, const char *name)
{
    static char path[4][1024];
    static int next;
    char *p = path[next++ % 4];
    snprintf(p, sizeof path[0], "%s/%s", dir, name);
    return p;
}

static void load(const char *path, InstancingMode mode, Scene *s)
{
    Error err = {0};
    cr_assert(scene_load_with(path, mode, s, &err), "%s: %s", path, err.message);
}

static const float *corner(const Scene *s, uint32_t t, int k)
{
    return s->data.positions[s->data.triangles[t].v.s[k]].s;
}

/* Triangle t of a and u of b: the same corners in the same cyclic order (the same front). */
static bool same_triangle(const Scene *a, uint32_t t, const Scene *b, uint32_t u)
{
    for (int r = 0; r < 3; r++) {
        bool same = true;
        for (int k = 0; k < 3 && same; k++)
            for (int c = 0; c < 3; c++)
                same = same && fabsf(corner(a, t, k)[c] - corner(b, u, (k + r) % 3)[c]) < 2e-5f;
        if (same)
            return true;
    }
    return false;
}

static bool same_material(const Material *x, const Material *y)
{
    for (int c = 0; c < 3; c++)
        if (fabsf(x->base.s[c] - y->base.s[c]) > 1e-6f || fabsf(x->emission.s[c] - y->emission.s[c]) > 1e-5f)
            return false;
    return x->type == y->type && fabsf(x->metallic - y->metallic) < 1e-6f &&
           fabsf(x->roughness - y->roughness) < 1e-6f;
}

/* Every triangle of a has its own match in b, of the same material parameters, and vice versa
 * (equal counts). */
static void expect_same_triangles(const Scene *a, const Scene *b, const char *what)
{
    cr_assert_eq(a->data.num_triangles, b->data.num_triangles, "%s: %u triangles, the reference %u",
                 what, a->data.num_triangles, b->data.num_triangles);
    uint32_t n = a->data.num_triangles;
    bool *used = calloc(n, sizeof *used);
    for (uint32_t t = 0; t < n; t++) {
        uint32_t u = 0;
        while (u < n && (used[u] || !same_triangle(a, t, b, u)))
            u++;
        cr_assert(u < n, "%s: triangle %u (%g %g %g) has no match in the reference", what, t,
                  corner(a, t, 0)[0], corner(a, t, 0)[1], corner(a, t, 0)[2]);
        used[u] = true;
        cr_expect(same_material(&a->data.materials[a->data.material_ids[t]],
                                &b->data.materials[b->data.material_ids[u]]),
                  "%s: triangle %u's material differs from the reference's", what, t);
    }
    free(used);
}

Test(gltf, every_encoding_gives_the_reference_triangles, .timeout = 120)
{
    const char *dir = generate();
    Scene ref;
    load(at(dir, "reference.json"), INSTANCING_NEVER, &ref);
    cr_assert_eq(ref.data.num_triangles, 3 * 12 + 2 + 4 + 3 + 2 + 1 + 2, "the reference scene");
    const char *files[] = {"features.gltf", "features.glb", "features_embedded.gltf"};
    for (int i = 0; i < 3; i++) {
        Scene s;
        load(at(dir, files[i]), INSTANCING_NEVER, &s);
        expect_same_triangles(&s, &ref, files[i]);
        scene_free(&s);
    }
    scene_free(&ref);
}

/* The box is placed by 3 nodes: one mesh (decoded and built once), 3 instances of it. */
Test(gltf, a_mesh_placed_by_three_nodes_is_one_mesh, .timeout = 60)
{
    const char *dir = generate();
    Scene s;
    load(at(dir, "features.gltf"), INSTANCING_ALWAYS, &s);
    cr_assert_eq(s.data.num_meshes, 7, "box, quad, strip, fan, 2 sparse primitives, lamp");
    cr_assert_eq(s.data.num_instances, 9);
    int box_instances = 0;
    for (uint32_t i = 0; i < s.data.num_instances; i++)
        box_instances += s.data.meshes[s.data.instances[i].mesh].num_triangles == 12;
    cr_assert_eq(box_instances, 3);
    uint32_t box_meshes = 0;
    for (uint32_t m = 0; m < s.data.num_meshes; m++)
        box_meshes += s.data.meshes[m].num_triangles == 12;
    cr_assert_eq(box_meshes, 1);
    scene_free(&s);
}

/* A bare glTF takes its first perspective camera (over framing) and its lights, 683 cd = 1 W/sr;
 * a JSON scene's camera wins over the file's; a JSON object's transform and material apply to
 * every primitive. */
Test(gltf, camera_lights_and_json_objects, .timeout = 60)
{
    const char *dir = generate();
    SceneDesc d;
    Error err = {0};
    cr_assert(scene_desc_load(at(dir, "features.glb"), &d, &err), "%s", err.message);
    cr_assert(d.camera_given, "the file's camera is used");
    cr_assert_float_eq(d.camera.eye[2], 5.0f, 1e-6f);
    cr_assert_float_eq(d.camera.target[2], 4.0f, 1e-6f);
    cr_assert_float_eq(d.camera.fov_y, 0.7f * 180.0f / 3.14159265f, 1e-4f);
    /* Point, spot and directional lights as the reference's JSON lights (683 lm/W). */
    SceneDesc ref;
    cr_assert(scene_desc_load(at(dir, "reference.json"), &ref, &err), "%s", err.message);
    cr_assert_eq(d.num_lights, 3);
    cr_assert_eq(ref.num_lights, 3);
    for (int i = 0; i < 3; i++) {
        const AnalyticLight *g = &d.lights[i], *r = &ref.lights[i];
        cr_expect_eq(g->type, r->type, "light %d", i);
        for (int c = 0; c < 4; c++) {
            cr_expect(fabsf(g->position.s[c] - r->position.s[c]) < 1e-5f, "light %d position %d", i, c);
            cr_expect(fabsf(g->color.s[c] - r->color.s[c]) < 1e-5f, "light %d colour %d: %g vs %g", i,
                      c, g->color.s[c], r->color.s[c]);
            cr_expect(fabsf(g->axis.s[c] - r->axis.s[c]) < 1e-5f, "light %d axis %d", i, c);
            cr_expect(fabsf(g->params.s[c] - r->params.s[c]) < 1e-5f, "light %d params %d", i, c);
        }
    }
    scene_desc_free(&ref);
    scene_desc_free(&d);
    const char *json = test_write_file(dir, "placed.json",
        "{\"camera\": {\"eye\": [0, 0, 9], \"target\": [0, 0, 0]},\n"
        " \"materials\": {\"grey\": {\"type\": \"diffuse\", \"albedo\": [0.5, 0.5, 0.5]}},\n"
        " \"objects\": [{\"gltf\": \"features.gltf\", \"material\": \"grey\",\n"
        "               \"transform\": [{\"translate\": [10, 0, 0]}]},\n"
        "              {\"obj\": \"reference_red.obj\"}]}\n");
    cr_assert(scene_desc_load(json, &d, &err), "%s", err.message);
    cr_assert_float_eq(d.camera.eye[2], 9.0f, 1e-6f, "the JSON camera wins");
    cr_assert_eq(d.num_objects, 9 + 1);
    cr_assert_eq(d.num_lights, 3);
    cr_assert_eq(d.object_formats[9], MESH_OBJ);
    cr_assert_float_eq(d.lights[0].position.s[0], 10.0f, 1e-5f, "the light moves with the object");
    scene_desc_free(&d);
    Scene a, b;
    load(json, INSTANCING_NEVER, &a);
    load(at(dir, "features.gltf"), INSTANCING_NEVER, &b);
    uint32_t n = b.data.num_triangles;
    cr_assert_eq(a.data.num_triangles, n + 3 * 12 + 2, "plus reference_red.obj");
    float shift_min = INFINITY, shift_max = -INFINITY;
    for (uint32_t t = 0; t < n; t++) {
        /* INSTANCING_NEVER merges objects in order: the glTF's come first. */
        cr_assert_eq(a.data.materials[a.data.material_ids[t]].type, MATERIAL_DIFFUSE);
        float dx = corner(&a, t, 0)[0] - corner(&b, t, 0)[0];
        shift_min = fminf(shift_min, dx), shift_max = fmaxf(shift_max, dx);
    }
    cr_assert(fabsf(shift_min - 10.0f) < 1e-4f && fabsf(shift_max - 10.0f) < 1e-4f, "%g %g",
              shift_min, shift_max);
    scene_free(&a);
    scene_free(&b);
}

Test(gltf, bad_files_name_the_file_and_json_path, .timeout = 60)
{
    const char *dir = generate();
    char list[1024];
    snprintf(list, sizeof list, "%s/bad/cases.txt", dir);
    FILE *f = fopen(list, "r");
    cr_assert(f);
    char line[512];
    int cases = 0;
    while (fgets(line, sizeof line, f)) {
        line[strcspn(line, "\n")] = 0;
        char *tab = strchr(line, '\t');
        cr_assert(tab);
        *tab = 0;
        char path[1024];
        snprintf(path, sizeof path, "%s/bad/%s", dir, line);
        Scene s;
        Error err = {0};
        cr_expect_not(scene_load(path, &s, &err), "%s loaded", line);
        cr_expect(strstr(err.message, line) && strstr(err.message, tab + 1) && !strchr(err.message, '\n'),
                  "%s: \"%s\" should name the file and \"%s\" on one line", line, err.message, tab + 1);
        cases++;
    }
    fclose(f);
    cr_assert_geq(cases, 14);
    /* Through the binary: exit status 1, one line. */
    char command[2048];
    snprintf(command, sizeof command, "%s render '%s/bad/truncated.glb' --spp=1 -o '%s/x.png' 2>'%s/err.txt'",
             test_pt_bin(), dir, dir, dir);
    int status = system(command);
    cr_assert(WIFEXITED(status) && WEXITSTATUS(status) == 1, "status %d", status);
    size_t size;
    char *text = test_read_file(at(dir, "err.txt"), &size);
    cr_assert(strstr(text, "truncated GLB") && strchr(text, '\n') == text + size - 1, "%s", text);
    free(text);
}

/* Mean of each 2 x 2 block of a 16 x 16 image over `renders` seeds, and its standard error. */
static void block_means(const char *path, int renders, double mean[4][3], double se[4][3])
{
    RenderFixture f;
    render_fixture_open(&f, path, 16, 16);
    double sum[4][3] = {{0}}, sum2[4][3] = {{0}};
    for (int k = 0; k < renders; k++) {
        float *rgb = render_fixture_render(&f, (RenderSettings){.spp = 16, .max_depth = 4,
                                                                .seed = 11u + 101u * (unsigned)k}, NULL);
        double m[4][3] = {{0}};
        for (int p = 0; p < 256; p++)
            for (int c = 0; c < 3; c++)
                m[(p / 16 / 8) * 2 + p % 16 / 8][c] += rgb[3 * p + c] / 64.0;
        for (int b = 0; b < 4; b++)
            for (int c = 0; c < 3; c++)
                sum[b][c] += m[b][c], sum2[b][c] += m[b][c] * m[b][c];
        free(rgb);
    }
    render_fixture_close(&f);
    for (int b = 0; b < 4; b++)
        for (int c = 0; c < 3; c++) {
            mean[b][c] = sum[b][c] / renders;
            se[b][c] = sqrt(fmax(sum2[b][c] / renders - mean[b][c] * mean[b][c], 0.0) / (renders - 1));
        }
}

/* The glTF (instances, its camera and light) renders like the JSON + OBJ reference (one merged
 * mesh): each quadrant within z < 5 of the two estimates' noise. */
Test(gltf, renders_like_the_reference, .timeout = 300)
{
    const char *dir = generate();
    double a[4][3], sa[4][3], b[4][3], sb[4][3];
    block_means(at(dir, "features.glb"), 4, a, sa);
    block_means(at(dir, "reference.json"), 4, b, sb);
    double total = 0;
    for (int q = 0; q < 4; q++)
        for (int c = 0; c < 3; c++) {
            total += a[q][c];
            double z = fabs(a[q][c] - b[q][c]) / (sqrt(sa[q][c] * sa[q][c] + sb[q][c] * sb[q][c]) + 1e-6);
            cr_expect(z < 5.0, "quadrant %d channel %d: %f vs %f (z = %.1f)", q, c, a[q][c], b[q][c], z);
        }
    cr_assert(total > 0.01, "the image is black");
}

/* scenes/cornell-box/CornellBox-Original.gltf (tools/obj_to_gltf.py, with scene.json's camera)
 * renders like the OBJ scene: Kd-only MTL materials are principled with specularFactor 0 (pure
 * Lambert) and metallic 0, the lamp's Ke is its emissive strength. */
Test(gltf, cornell_box_renders_like_the_obj, .timeout = 300)
{
    double a[4][3], sa[4][3], b[4][3], sb[4][3];
    block_means("scenes/cornell-box/CornellBox-Original.gltf", 4, a, sa);
    block_means("scenes/cornell-box/scene.json", 4, b, sb);
    for (int q = 0; q < 4; q++)
        for (int c = 0; c < 3; c++) {
            double z = fabs(a[q][c] - b[q][c]) / (sqrt(sa[q][c] * sa[q][c] + sb[q][c] * sb[q][c]) + 1e-6);
            cr_expect(z < 5.0, "quadrant %d channel %d: %f vs %f (z = %.1f)", q, c, a[q][c], b[q][c], z);
        }
    for (int q = 0; q < 4; q++)
        cr_expect(a[q][0] + a[q][1] + a[q][2] > 0.1, "quadrant %d is dark", q);
}

/* Unknown extensionsUsed are one warning naming them all; the file still loads. */
Test(gltf, unknown_used_extensions_are_one_warning, .timeout = 60)
{
    const char *dir = generate();
    size_t size;
    char *text = test_read_file(at(dir, "features.gltf"), &size);
    const char *used = "\"extensionsUsed\": [";
    char *p = strstr(text, used);
    cr_assert(p);
    size_t head = (size_t)(p - text) + strlen(used);
    char *changed = malloc(size + 64);
    snprintf(changed, size + 64, "%.*s\"EXT_one\", \"EXT_two\", %s", (int)head, text, text + head);
    const char *path = test_write_file(dir, "used.gltf", changed);
    int before = warning_count();
    SceneDesc d;
    Error err = {0};
    cr_assert(scene_desc_load(path, &d, &err), "%s", err.message);
    cr_assert_eq(warning_count(), before + 1);
    scene_desc_free(&d);
    free(changed);
    free(text);
}

/* Every field of scene/gltf_material.h as the file states it: factors, textureInfos with their
 * image, sampler and KHR_texture_transform, the KHR_materials_* extensions; images embedded in
 * the GLB's buffer and as a data URI (encoded bytes), or a file beside it (url-decoded path). */
Test(gltf, materials_and_images_are_read_as_written, .timeout = 60)
{
    const char *dir = generate();
    GltfFile f;
    Error err = {0};
    cr_assert(gltf_load(at(dir, "textured.glb"), &f, &err), "%s", err.message);
    GltfMaterial *m;
    GltfImage *images;
    int count, num_images;
    cr_assert(gltf_read_materials(&f, &m, &count, &images, &num_images));
    cr_assert_eq(count, 2, "the file's material and glTF's default");
    cr_assert_eq(num_images, 3);
    size_t png_size;
    char *png = test_read_file(at(dir, "tex file.png"), &png_size);
    for (int i = 0; i < 2; i++) {
        cr_assert_eq(images[i].size, png_size, "images[%d] holds the encoded PNG", i);
        cr_assert(!memcmp(images[i].bytes, png, png_size));
        cr_assert_eq(images[i].path[0], 0);
    }
    free(png);
    cr_assert_str_eq(images[0].mime, "image/png");
    cr_assert_str_eq(images[2].path, at(dir, "tex file.png"));
    cr_assert_str_eq(images[2].json_path, "images[2]");
    const GltfMaterial *g = &m[0];
    cr_assert_str_eq(g->name, "everything");
    cr_assert_str_eq(g->json_path, "materials[0]");
    cr_assert_float_eq(g->base_color[3], 0.6f, 1e-7f);
    cr_assert_float_eq(g->metallic, 0.4f, 1e-7f);
    cr_assert_float_eq(g->roughness, 0.3f, 1e-7f);
    const GltfTextureRef *t = &g->base_color_texture;
    cr_assert_eq(t->image, 0);
    cr_assert_eq(t->wrap_s, GLTF_WRAP_CLAMP);
    cr_assert_eq(t->wrap_t, GLTF_WRAP_MIRROR);
    cr_assert(t->nearest && t->has_transform);
    cr_assert(t->offset[0] == 0.5f && t->offset[1] == 0.25f && t->rotation == 0.75f &&
              t->scale[0] == 2.0f && t->scale[1] == 3.0f);
    cr_assert_str_eq(t->json_path, "materials[0].pbrMetallicRoughness.baseColorTexture");
    cr_assert_eq(g->metallic_roughness_texture.image, 1);
    cr_assert_eq(g->metallic_roughness_texture.wrap_s, GLTF_WRAP_REPEAT);
    cr_assert(!g->metallic_roughness_texture.has_transform);
    cr_assert_eq(g->normal_texture.image, 2);
    cr_assert_float_eq(g->normal_texture.amount, 0.5f, 1e-7f);
    cr_assert_float_eq(g->occlusion_texture.amount, 0.25f, 1e-7f);
    cr_assert_eq(g->emissive_texture.image, 1);
    cr_assert_float_eq(g->emissive[2], 0.3f, 1e-7f);
    cr_assert_float_eq(g->emissive_strength, 4.0f, 1e-7f);
    cr_assert_eq(g->alpha_mode, GLTF_ALPHA_MASK);
    cr_assert_float_eq(g->alpha_cutoff, 0.375f, 1e-7f);
    cr_assert(g->double_sided);
    cr_assert_float_eq(g->specular, 0.625f, 1e-7f);
    cr_assert_float_eq(g->specular_color[1], 0.75f, 1e-7f);
    cr_assert_eq(g->specular_texture.image, 0);
    cr_assert_eq(g->specular_color_texture.image, 1);
    cr_assert_str_eq(g->specular_color_texture.json_path,
                     "materials[0].extensions.KHR_materials_specular.specularColorTexture");
    cr_assert_float_eq(g->transmission, 0.875f, 1e-7f);
    cr_assert_eq(g->transmission_texture.image, 2);
    cr_assert_float_eq(g->ior, 1.25f, 1e-7f);
    cr_assert(g->has_volume);
    cr_assert_float_eq(g->thickness, 0.125f, 1e-7f);
    cr_assert_float_eq(g->attenuation_distance, 2.5f, 1e-7f);
    cr_assert_float_eq(g->attenuation_color[2], 0.75f, 1e-7f);
    cr_assert_eq(m[1].base_color_texture.image, -1, "the default material");
    cr_assert_float_eq(m[1].roughness, 1.0f, 1e-7f);
    free(m);
    free(images);
    gltf_free(&f);
}
