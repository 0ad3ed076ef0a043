// SPDX-License-Identifier: MIT
/* import_pbrt_materials.c: pbrt-v4 materials and textures as pt's JSON "materials" and
 * "textures" (DESIGN.md "Materials", "Textures").
 * Exact: diffuse; conductor (eta / k, RGB for named spectra); dielectric; mix (pbrt picks
 * materials[1] with probability amount, pt weights b by weight: the same expectation).
 * Roughness: pbrt's alpha is sqrt(r) with remaproughness (default), else r; pt's alpha is r^2, so
 * pt's r = sqrt(alpha). u/vroughness become pt's anisotropy when the u alpha is the larger.
 * Nearest model (warned once): coateddiffuse -> principled (Lambert under a GGX coat whose F0 comes
 * from the interface eta: same highlights, no darkening by the layer's inner reflections);
 * coatedconductor -> the conductor without its coat; thindielectric -> a mirror with opacity
 * R_thin(eta) = 2R / (1 + R) (right at normal incidence, no angle dependence); diffusetransmission
 * -> diffuse (transmission dropped); interface -> fully transparent (until pt has media).
 * Textures: import_pbrt_textures.c. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene/import_pbrt_internal.h"

/* A material value: colour (n 3) or scalar (n 1): a constant or a pt texture name. */
static bool value_json(PbrtImport *imp, PbrtParams *p, const char *name, int n, const float *fallback,
                       const char *kind, cJSON **out)
{
    PbrtParam *q = pbrt_param(p, name);
    float v[3] = {fallback[0], fallback[n == 3 ? 1 : 0], fallback[n == 3 ? 2 : 0]};
    if (q && q->type == PBRT_TEXTURE) {
        PbrtTexture *t = q->count == 1 ? pbrt_find_texture(imp, q->strings[0], n == 1) : NULL;
        if (!t)
            return pbrt_fail(imp, q->line, "\"%s\": no texture \"%s\"", name, q->count ? q->strings[0] : "");
        if (t->pt_texture[0]) {
            *out = cJSON_CreateString(t->pt_texture);
            return true;
        }
        memcpy(v, t->value, sizeof v);
    } else if (q && !pbrt_spectrum_rgb(imp, q, kind, v)) {
        return false;
    }
    if (n == 1) {
        if (q && q->type != PBRT_FLOAT && q->type != PBRT_INTEGER && q->type != PBRT_TEXTURE)
            return pbrt_fail(imp, q->line, "\"%s\": expected a float", name);
        *out = cJSON_CreateNumber(v[0]);
    } else {
        const double d[3] = {v[0], v[1], v[2]};
        *out = cJSON_CreateDoubleArray(d, 3);
    }
    return true;
}

static bool add_value(PbrtImport *imp, cJSON *m, const char *key, PbrtParams *p, const char *name,
                      int n, const float *fallback, const char *kind)
{
    cJSON *v;
    if (!value_json(imp, p, name, n, fallback, kind, &v))
        return false;
    cJSON_AddItemToObject(m, key, v);
    return true;
}

/* roughness / uroughness / vroughness / remaproughness as pt's roughness and anisotropy. */
static bool roughness(PbrtImport *imp, cJSON *m, PbrtParams *p, const char *prefix, bool anisotropy)
{
    char names[4][48];
    const char *suffix[4] = {"roughness", "uroughness", "vroughness", "remaproughness"};
    for (int i = 0; i < 4; i++)
        snprintf(names[i], sizeof names[i], "%s%s", prefix, suffix[i]);
    bool remap;
    if (!pbrt_bool(imp, p, "remaproughness", true, &remap))
        return false;
    PbrtParam *r = pbrt_param(p, names[0]), *u = pbrt_param(p, names[1]), *v = pbrt_param(p, names[2]);
    PbrtParam *textured = r && r->type == PBRT_TEXTURE ? r : u && u->type == PBRT_TEXTURE ? u : NULL;
    if (textured) {
        pbrt_warn_once(imp, "roughness texture", "\"%s\": a roughness texture is used as pt's "
                       "roughness (alpha = value^2) without pbrt's remapping", textured->name);
        return add_value(imp, m, "roughness", p, textured->name, 1, (float[]){0.0f}, "reflectance");
    }
    float base, ur, vr;
    if (!pbrt_float(imp, p, names[0], 0.0f, &base) || !pbrt_float(imp, p, names[1], base, &ur) ||
        !pbrt_float(imp, p, names[2], base, &vr))
        return false;
    if (ur < 0.0f || vr < 0.0f)
        return pbrt_fail(imp, (u ? u : v ? v : r)->line, "roughness %g / %g must be >= 0", ur, vr);
    double au = remap ? sqrt(ur) : ur, av = remap ? sqrt(vr) : vr;
    double pt_r = pow(au * av, 0.25); /* alpha_x alpha_y = r^4 */
    if (pt_r > 1.0)
        pt_r = 1.0;
    cJSON_AddNumberToObject(m, "roughness", pt_r);
    if (au == av || pt_r == 0.0)
        return true;
    if (!anisotropy || au < av) {
        pbrt_warn_once(imp, "anisotropy", "\"uroughness\" %g < \"vroughness\" %g (or a dielectric): pt's "
                       "anisotropy stretches along u only; rendered isotropic", ur, vr);
        return true;
    }
    double a = (1.0 - av / au) / 0.9; /* alpha_y / alpha_x = 1 - 0.9 a */
    cJSON_AddNumberToObject(m, "anisotropy", fmin(a, 0.999));
    return true;
}

static bool conductor(PbrtImport *imp, cJSON *m, PbrtParams *p, const char *prefix)
{
    static const float cu_eta[3] = {0.200f, 0.924f, 1.102f}, cu_k[3] = {3.912f, 2.452f, 2.142f};
    char eta[48], k[48];
    snprintf(eta, sizeof eta, "%seta", prefix);
    snprintf(k, sizeof k, "%sk", prefix);
    cJSON_AddStringToObject(m, "type", "conductor");
    if (!prefix[0] && pbrt_param(p, "reflectance")) {
        /* pt's reflectance times Fresnel 1 stands for pbrt's artist-friendly Schlick form. */
        if (!add_value(imp, m, "reflectance", p, "reflectance", 3, (float[]){1, 1, 1}, "reflectance"))
            return false;
    } else if (!add_value(imp, m, "eta", p, eta, 3, cu_eta, "eta") ||
               !add_value(imp, m, "k", p, k, 3, cu_k, "k")) {
        return false;
    }
    for (const char *key = "eta"; key; key = strcmp(key, "eta") == 0 ? "k" : NULL)
        if (cJSON_IsString(cJSON_GetObjectItemCaseSensitive(m, key)))
            return pbrt_fail(imp, imp->line, "Material \"conductor\": a textured \"%s\" is not "
                             "imported (pt's eta and k are constants)", key);
    return roughness(imp, m, p, prefix, true);
}

static bool dielectric_ior(PbrtImport *imp, PbrtParams *p, const char *name, float *ior)
{
    PbrtParam *q = pbrt_param(p, name);
    float v[3] = {1.5f, 1.5f, 1.5f};
    if (q && !pbrt_spectrum_rgb(imp, q, "eta", v))
        return false;
    *ior = v[1];
    if (!(*ior >= 1.0f && *ior <= 10.0f)) {
        if (*ior > 0.0f && *ior < 1.0f) {
            pbrt_warn_once(imp, "eta < 1", "\"%s\" %g < 1: imported as 1 / %g", name, *ior, *ior);
            *ior = 1.0f / *ior;
        } else {
            return pbrt_fail(imp, q ? q->line : imp->line, "\"%s\": %g is out of range (0, 10]", name, *ior);
        }
    }
    return true;
}

/* The type-specific part; false with err set. */
static bool material_body(PbrtImport *imp, cJSON *m, const char *type, PbrtParams *p)
{
    static const float half[3] = {0.5f, 0.5f, 0.5f};
    float ior;
    if (strcmp(type, "diffuse") == 0) {
        cJSON_AddStringToObject(m, "type", "diffuse");
        return add_value(imp, m, "albedo", p, "reflectance", 3, half, "reflectance");
    }
    if (strcmp(type, "conductor") == 0)
        return conductor(imp, m, p, "");
    if (strcmp(type, "coatedconductor") == 0) {
        pbrt_warn_once(imp, type, "Material \"coatedconductor\": imported as its conductor (the "
                       "clear coat is dropped)");
        return conductor(imp, m, p, "conductor.");
    }
    if (strcmp(type, "dielectric") == 0) {
        cJSON_AddStringToObject(m, "type", "dielectric");
        if (!dielectric_ior(imp, p, "eta", &ior))
            return false;
        cJSON_AddNumberToObject(m, "ior", ior);
        return roughness(imp, m, p, "", false);
    }
    if (strcmp(type, "thindielectric") == 0) {
        pbrt_warn_once(imp, type, "Material \"thindielectric\": imported as a mirror with opacity "
                       "2R/(1+R) (exact at normal incidence only)");
        if (!dielectric_ior(imp, p, "eta", &ior))
            return false;
        double r = ((ior - 1.0) / (ior + 1.0)) * ((ior - 1.0) / (ior + 1.0));
        cJSON_AddStringToObject(m, "type", "conductor");
        cJSON_AddNumberToObject(m, "opacity", 2.0 * r / (1.0 + r));
        return true;
    }
    if (strcmp(type, "coateddiffuse") == 0) {
        pbrt_warn_once(imp, type, "Material \"coateddiffuse\": imported as principled (Lambert "
                       "under a GGX coat with the interface's Fresnel)");
        cJSON_AddStringToObject(m, "type", "principled");
        cJSON_AddNumberToObject(m, "metallic", 0.0);
        if (!dielectric_ior(imp, p, "eta", &ior))
            return false;
        cJSON_AddNumberToObject(m, "ior", ior);
        (void)pbrt_param(p, "thickness");
        return add_value(imp, m, "base_color", p, "reflectance", 3, half, "reflectance") &&
               roughness(imp, m, p, "", false);
    }
    if (strcmp(type, "diffusetransmission") == 0) {
        pbrt_warn_once(imp, type, "Material \"diffusetransmission\": imported as diffuse (its "
                       "transmission is dropped)");
        cJSON_AddStringToObject(m, "type", "diffuse");
        (void)pbrt_param(p, "transmittance");
        return add_value(imp, m, "albedo", p, "reflectance", 3, (float[]){0.25f, 0.25f, 0.25f}, "reflectance");
    }
    if (strcmp(type, "mix") == 0) {
        PbrtParam *names = pbrt_param(p, "materials");
        if (!names || names->type != PBRT_STRING || names->count != 2)
            return pbrt_fail(imp, names ? names->line : imp->line, "Material \"mix\": needs "
                             "\"string materials\" [two names]");
        for (int i = 0; i < 2; i++)
            if (!cJSON_GetObjectItemCaseSensitive(imp->materials, names->strings[i]))
                return pbrt_fail(imp, names->line, "Material \"mix\": no material \"%s\"", names->strings[i]);
        cJSON_AddStringToObject(m, "type", "mix");
        cJSON_AddStringToObject(m, "a", names->strings[0]);
        cJSON_AddStringToObject(m, "b", names->strings[1]);
        return add_value(imp, m, "weight", p, "amount", 1, half, "reflectance");
    }
    if (strcmp(type, "interface") == 0 || strcmp(type, "none") == 0 || !type[0]) {
        pbrt_warn_once(imp, "interface", "Material \"interface\": an invisible boundary (pt has no "
                       "media yet)");
        cJSON_AddStringToObject(m, "type", "diffuse");
        cJSON_AddNumberToObject(m, "opacity", 0.0);
        return true;
    }
    char key[96];
    snprintf(key, sizeof key, "material %s", type);
    pbrt_warn_once(imp, key, "Material \"%s\": not imported (diffuse 0.5 used)", type);
    cJSON_AddStringToObject(m, "type", "diffuse");
    cJSON_AddNumberToObject(m, "albedo", 0.5);
    for (int i = 0; i < p->count; i++)
        p->items[i].used = true;
    return true;
}

bool pbrt_material(PbrtImport *imp, const char *name, const char *type, PbrtParams *p)
{
    if (cJSON_GetObjectItemCaseSensitive(imp->materials, name))
        return pbrt_fail(imp, imp->line, "MakeNamedMaterial: \"%s\" is defined twice", name);
    imp->num_materials++;
    cJSON *m = cJSON_CreateObject();
    if (!material_body(imp, m, type, p)) {
        cJSON_Delete(m);
        return false;
    }
    cJSON_AddItemToObject(imp->materials, name, m);
    bool ok = true;
    const char *normal = pbrt_string(imp, p, "normalmap", &ok);
    char texture[SCENE_NAME_LIMIT];
    if (normal && ok) {
        if (!pbrt_add_file_texture(imp, normal, "linear", imp->line, texture))
            return false;
        cJSON_AddStringToObject(m, "normal_map", texture);
    }
    if (pbrt_param(p, "displacement"))
        pbrt_warn_once(imp, "displacement", "Material \"%s\": \"displacement\" is not imported "
                       "(rendered undisplaced)", type);
    pbrt_warn_unused(imp, "Material", type, p);
    return ok;
}

/* ---- The material of one shape ------------------------------------------------------------- */

bool pbrt_shape_material(PbrtImport *imp, const float *emission, PbrtParams *shape, char out[SCENE_NAME_LIMIT])
{
    const char *base = imp->state.material;
    if (!base[0]) {
        base = "pbrt-default";
        if (!cJSON_GetObjectItemCaseSensitive(imp->materials, base)) {
            cJSON *m = cJSON_AddObjectToObject(imp->materials, base);
            cJSON_AddStringToObject(m, "type", "diffuse");
            cJSON_AddNumberToObject(m, "albedo", 0.5);
        }
    }
    cJSON *alpha = NULL;
    PbrtParam *q = pbrt_param(shape, "alpha");
    if (q && !value_json(imp, shape, "alpha", 1, (float[]){1.0f}, "reflectance", &alpha))
        return false;
    if (alpha && cJSON_IsNumber(alpha) && alpha->valuedouble >= 1.0) {
        cJSON_Delete(alpha);
        alpha = NULL;
    }
    if (!emission && !alpha) {
        snprintf(out, SCENE_NAME_LIMIT, "%s", base);
        return true;
    }
    /* A variant per (material, emission, alpha), shared by the shapes that agree. */
    char key[512];
    snprintf(key, sizeof key, "%s|%.9g,%.9g,%.9g|%s", base, emission ? emission[0] : -1.0,
             emission ? emission[1] : -1.0, emission ? emission[2] : -1.0,
             !alpha ? "" : cJSON_IsString(alpha) ? alpha->valuestring : "number");
    char number[32] = "";
    if (alpha && cJSON_IsNumber(alpha))
        snprintf(number, sizeof number, "%.9g", alpha->valuedouble);
    strncat(key, number, sizeof key - strlen(key) - 1);
    int index = 0;
    for (cJSON *v = imp->variants ? imp->variants->child : NULL; v; v = v->next, index++)
        if (strcmp(v->string, key) == 0) {
            snprintf(out, SCENE_NAME_LIMIT, "%s", v->valuestring);
            cJSON_Delete(alpha);
            return true;
        }
    cJSON *m = cJSON_Duplicate(cJSON_GetObjectItemCaseSensitive(imp->materials, base), true);
    if (emission)
        cJSON_AddItemToObject(m, "emission", cJSON_CreateDoubleArray((double[]){emission[0], emission[1], emission[2]}, 3));
    if (alpha) {
        cJSON_DeleteItemFromObject(m, "opacity");
        cJSON_AddItemToObject(m, "opacity", alpha);
    }
    snprintf(out, SCENE_NAME_LIMIT, "variant%d", index);
    while (cJSON_GetObjectItemCaseSensitive(imp->materials, out))
        snprintf(out, SCENE_NAME_LIMIT, "variant%d", ++index);
    cJSON_AddItemToObject(imp->materials, out, m);
    cJSON_AddStringToObject(imp->variants, key, out);
    return true;
}
