// SPDX-License-Identifier: MIT
/* glTF materials, the rest of what the mapping promises: KHR_materials_specular's factor 0 leaves
 * pure Lambert diffuse (the BSDF evaluated on the device equals a diffuse one, pdf included);
 * textureInfos sampled alike share one TextureDesc and differently sampled ones share texels;
 * embedded image bytes decode as the same file does; bad input is one error naming the glTF
 * file, the image (images[i]) and the material that uses it. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <stb_image_write.h>

#include "bsdf_harness.h"
#include "gltf_material_fixture.h"

Test(gltf_material_input, specular_zero_is_pure_lambert)
{
    GltfMaterial g;
    gltf_material_default(&g);
    g.base_color[0] = 0.6f, g.base_color[1] = 0.4f, g.base_color[2] = 0.2f;
    g.metallic = 0.0f, g.roughness = 0.3f, g.specular = 0.0f;
    Material principled = fixture_gltf_one(&g);
    Material diffuse = bsdf_material(MATERIAL_DIFFUSE);
    diffuse.base = principled.base;
    enum { N = 24 };
    cl_float4 wo[N], wi[N], f_p[N], f_d[N];
    for (int i = 0; i < N; i++) {
        wo[i] = bsdf_dir(5.0 + 3.5 * i, 17.0 * i, 1);
        wi[i] = bsdf_dir(85.0 - 3.3 * i, 180.0 + 11.0 * i, 1);
    }
    wi[3] = (cl_float4){{-wo[3].s[0], -wo[3].s[1], wo[3].s[2], 1.0f}}; /* the mirror direction */
    BsdfHarness h;
    bsdf_harness_open(&h);
    bsdf_harness_eval(&h, &principled, wo, wi, N, f_p);
    bsdf_harness_eval(&h, &diffuse, wo, wi, N, f_d);
    for (int i = 0; i < N; i++)
        for (int c = 0; c < 4; c++) /* rgb f cos and the pdf */
            cr_expect(fabsf(f_p[i].s[c] - f_d[i].s[c]) <= 1e-5f * (1.0f + f_d[i].s[c]),
                      "direction %d component %d: principled %g, Lambert %g", i, c,
                      (double)f_p[i].s[c], (double)f_d[i].s[c]);
    /* The default specular 1 has its lobe: the mirror direction differs. */
    g.specular = 1.0f;
    Material glossy = fixture_gltf_one(&g);
    cl_float4 f_g[N];
    bsdf_harness_eval(&h, &glossy, wo, wi, N, f_g);
    cr_expect(f_g[3].s[0] > 1.5f * f_d[3].s[0], "specular 1 at the mirror direction: %g vs %g",
              (double)f_g[3].s[0], (double)f_d[3].s[0]);
    bsdf_harness_close(&h);
}

static void write_base_png(void)
{
    const unsigned char px[] = {200, 100, 50, 51, 20, 40, 60, 255, 255, 0, 0, 128, 0, 255, 0, 204};
    cr_assert(stbi_write_png(fixture_path("base.png"), 2, 2, 4, px, 8));
}

Test(gltf_material_input, same_image_and_sampling_share_one_texture)
{
    write_base_png();
    GltfImage images[1];
    fixture_file_images(images, (const char *[]){"base.png"}, 1);
    GltfMaterial g[3];
    for (int i = 0; i < 3; i++) {
        gltf_material_default(&g[i]);
        snprintf(g[i].json_path, sizeof g[i].json_path, "materials[%d]", i);
        g[i].base_color_texture.image = 0;
        g[i].metallic_roughness_texture.image = 0;
    }
    g[2].base_color_texture.wrap_s = GLTF_WRAP_CLAMP;
    MaterialDesc *md = NULL;
    TextureDesc *td = NULL;
    int nm = 0, nt = 0;
    Error err = {0};
    cr_assert(gltf_materials_append(g, 3, images, 1, "test.gltf", "p:", &md, &nm, &td, &nt, &err),
              "%s", err.message);
    cr_expect_eq(nm, 3);
    cr_expect_str_eq(md[1].name, "p:materials[1]");
    uint32_t base0 = md[0].m.tex[MATERIAL_TEX_BASE], base2 = md[2].m.tex[MATERIAL_TEX_BASE];
    cr_expect_eq(md[1].m.tex[MATERIAL_TEX_BASE], base0, "same image and sampler: one desc");
    cr_expect_eq(md[1].m.tex[MATERIAL_TEX_ROUGHNESS], md[0].m.tex[MATERIAL_TEX_ROUGHNESS]);
    cr_expect_neq(base2, base0, "another wrap mode: another desc");
    /* base (sRGB), clamped base, roughness (g) and metallic (b) of the linear image. */
    cr_expect_eq(nt, 4, "%d texture descs", nt);
    Loaded l;
    cr_assert(fixture_load_descs(&l, td, nt, md, nm, &err), "%s", err.message);
    const Material *m0 = &l.materials[0], *m2 = &l.materials[2];
    const TextureInfo *infos = l.set.infos;
    cr_expect_eq(infos[m0->tex[MATERIAL_TEX_BASE]].offset, infos[m2->tex[MATERIAL_TEX_BASE]].offset,
                 "both samplings read the same texels");
    cr_expect_eq(infos[m0->tex[MATERIAL_TEX_ROUGHNESS]].offset,
                 infos[m0->tex[MATERIAL_TEX_METALLIC]].offset, "g and b of one copy");
    cr_expect_eq(l.set.num_texels, 4u + 4u, "one 8-bit sRGB and one 8-bit linear copy");
    fixture_free(&l);
    free(md);
    free(td);
}

Test(gltf_material_input, embedded_bytes_decode_like_the_file)
{
    write_base_png();
    size_t size = 0;
    char *bytes = test_read_file(fixture_path("base.png"), &size);
    cr_assert(bytes);
    GltfImage images[2];
    fixture_file_images(images, (const char *[]){"base.png", "unused"}, 2);
    images[1].path[0] = '\0';
    images[1].bytes = (const unsigned char *)bytes;
    images[1].size = size;
    GltfMaterial g[2];
    for (int i = 0; i < 2; i++) {
        gltf_material_default(&g[i]);
        g[i].base_color_texture.image = i;
    }
    Loaded l;
    Error err = {0};
    cr_assert(fixture_gltf(&l, g, 2, images, 2, &err), "%s", err.message);
    cr_assert_neq(l.materials[1].tex[MATERIAL_TEX_BASE], NO_TEXTURE, "the embedded image is used");
    expect_same_texture(&l, l.materials[0].tex[MATERIAL_TEX_BASE], &l,
                        l.materials[1].tex[MATERIAL_TEX_BASE], "embedded vs file");
    fixture_free(&l);
    free(bytes);
}

/* The mapping and loading of g fail with a message containing every one of `parts`. */
static void expect_error(const GltfMaterial *g, const GltfImage *images, int n, const char **parts,
                         int num_parts)
{
    Loaded l;
    Error err = {0};
    bool ok = fixture_gltf(&l, g, 1, images, n, &err);
    if (ok)
        fixture_free(&l);
    cr_assert_not(ok, "accepted");
    for (int i = 0; i < num_parts; i++)
        cr_expect(strstr(err.message, parts[i]), "\"%s\" not in: %s", parts[i], err.message);
}

Test(gltf_material_input, bad_images_name_the_file_the_image_and_its_user)
{
    GltfImage images[1];
    fixture_file_images(images, (const char *[]){"absent.png"}, 1);
    GltfMaterial g;
    gltf_material_default(&g);
    snprintf(g.json_path, sizeof g.json_path, "materials[4]");
    g.emissive[0] = 1.0f;
    g.emissive_texture.image = 0;
    snprintf(g.emissive_texture.json_path, sizeof g.emissive_texture.json_path,
             "materials[4].emissiveTexture");
    expect_error(&g, images, 1,
                 (const char *[]){"test.gltf", "images[0]", "absent.png", "materials[4].emissiveTexture"},
                 4);
    /* Corrupt embedded bytes. */
    const unsigned char junk[] = "\x89PNG\r\n\x1a\n this is not a PNG at all";
    images[0].path[0] = '\0';
    images[0].bytes = junk;
    images[0].size = sizeof junk;
    expect_error(&g, images, 1,
                 (const char *[]){"test.gltf", "images[0]", "materials[4].emissiveTexture"}, 3);
    /* An index past the images. */
    g.emissive_texture.image = 3;
    expect_error(&g, images, 1, (const char *[]){"test.gltf", "materials[4].emissiveTexture", "images[3]"},
                 3);
}

Test(gltf_material_input, bad_values_name_the_key)
{
    GltfMaterial g;
    gltf_material_default(&g);
    snprintf(g.json_path, sizeof g.json_path, "materials[1]");
    g.metallic = 1.5f;
    expect_error(&g, NULL, 0, (const char *[]){"test.gltf", "materials[1]", "metallicFactor", "1.5"}, 4);
    gltf_material_default(&g);
    g.ior = 0.5f;
    expect_error(&g, NULL, 0, (const char *[]){"KHR_materials_ior", "0.5"}, 2);
    gltf_material_default(&g);
    g.base_color[0] = NAN;
    expect_error(&g, NULL, 0, (const char *[]){"baseColorFactor", "nan"}, 2);
    GltfImage images[1];
    write_base_png();
    fixture_file_images(images, (const char *[]){"base.png"}, 1);
    gltf_material_default(&g);
    g.base_color_texture.image = 0;
    g.base_color_texture.wrap_t = 1234;
    expect_error(&g, images, 1, (const char *[]){"1234", "wrap"}, 2);
}
