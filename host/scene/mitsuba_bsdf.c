// SPDX-License-Identifier: MIT
/* mitsuba_bsdf.c: Mitsuba BSDFs and textures as pt materials and textures (README.md "Mitsuba 3
 * scenes" has the table). Each element is mapped once (a bsdf shared by refs or by the instances
 * of a shapegroup is one material). */
#include "scene/mitsuba_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Mitsuba's named indices of refraction (its dielectric plugin's table). */
static const struct {
    const char *name;
    double ior;
} named_iors[] = {
    {"vacuum", 1.0},          {"helium", 1.000036},     {"hydrogen", 1.000132},
    {"air", 1.000277},        {"carbon dioxide", 1.00045}, {"water", 1.3330},
    {"acetone", 1.36},        {"ethanol", 1.361},       {"carbon tetrachloride", 1.461},
    {"glycerol", 1.4729},     {"benzene", 1.501},       {"silicone oil", 1.52045},
    {"bromine", 1.661},       {"water ice", 1.31},      {"fused quartz", 1.458},
    {"pyrex", 1.470},         {"acrylic glass", 1.49},  {"polypropylene", 1.49},
    {"bk7", 1.5046},          {"sodium chloride", 1.544}, {"amber", 1.55},
    {"pet", 1.5750},          {"diamond", 2.419},
};

/* Mitsuba's conductor presets as RGB complex indices (the spectral data averaged over sRGB's
 * primaries, as pbrt's and Mitsuba's RGB modes give them; "none" is Fresnel 1). */
static const struct {
    const char *name;
    double eta[3], k[3];
} conductors[] = {
    {"Ag", {0.155265, 0.116723, 0.138342}, {4.82835, 3.12225, 2.14696}},
    {"Al", {1.65746, 0.880369, 0.521229}, {9.22387, 6.26952, 4.837}},
    {"Au", {0.143119, 0.374957, 1.44248}, {3.98316, 2.38572, 1.60322}},
    {"Cu", {0.200438, 0.924033, 1.10221}, {3.91295, 2.45285, 2.14219}},
    {"CuZn", {0.444, 0.527, 1.094}, {3.695, 2.765, 1.829}},
    {"Cr", {4.36968, 2.9167, 1.6547}, {5.20637, 4.23132, 3.75469}},
    {"Hg", {2.39, 1.43, 0.91}, {6.31, 4.84, 3.62}},
    {"Ni", {1.98, 1.83, 1.68}, {3.72, 3.26, 2.82}},
    {"Pt", {2.37, 2.06, 1.78}, {4.26, 3.70, 3.13}},
    {"Ti", {2.74, 2.54, 2.27}, {3.81, 3.43, 3.04}},
    {"W", {4.37, 3.30, 2.99}, {3.51, 2.58, 2.49}},
};

static bool ior_value(Mitsuba *m, const XmlElement *e, const char *name, double fallback, double *out)
{
    const XmlElement *p = mi_prop(m, e, name);
    *out = fallback;
    if (!p)
        return true;
    if (strcmp(p->name, "string") == 0) {
        const char *v = xml_attribute(p, "value");
        for (size_t i = 0; v && i < sizeof named_iors / sizeof named_iors[0]; i++)
            if (strcmp(v, named_iors[i].name) == 0) {
                *out = named_iors[i].ior;
                return true;
            }
        return mi_fail(m, p, "\"%.40s\" is not one of Mitsuba's named indices of refraction", v ? v : "");
    }
    if (!mi_parse_number(m, p, "value", out))
        return false;
    if (!(*out > 0.0))
        return mi_fail(m, p, "an index of refraction must be > 0");
    return true;
}

/* ---- BSDFs ----------------------------------------------------------------------------------- */

/* alpha (or alpha_u, alpha_v) of a rough Mitsuba BSDF as pt's roughness r = sqrt(alpha) and
 * anisotropy a, inverting DESIGN's alpha_x = r^2 / sqrt(1 - 0.9 a), alpha_y = r^2 sqrt(1 - 0.9 a):
 * r^4 = alpha_u alpha_v and 1 - 0.9 a = alpha_v / alpha_u. */
static bool roughness(Mitsuba *m, const XmlElement *e, cJSON *material, bool anisotropic_ok)
{
    const char *distribution = mi_string(m, e, "distribution", "beckmann");
    if (strcmp(distribution, "ggx") && strcmp(distribution, "beckmann"))
        return mi_fail(m, e, "distribution \"%.40s\" is not ggx or beckmann", distribution);
    if (strcmp(distribution, "beckmann") == 0)
        mi_warn_once(m, e, "beckmann", "Beckmann distribution (Mitsuba's default) rendered as GGX "
                                       "with the same alpha (pt has GGX only)");
    mi_prop(m, e, "sample_visible");
    double alpha = 0.1, alpha_u, alpha_v;
    const XmlElement *p = mi_prop(m, e, "alpha");
    if (p && strcmp(p->name, "float"))
        mi_warn_once(m, p, "alpha-texture", "textured alpha: its default 0.1 instead");
    else if (p && !mi_parse_number(m, p, "value", &alpha))
        return false;
    if (!mi_float(m, e, "alpha_u", alpha, &alpha_u) || !mi_float(m, e, "alpha_v", alpha_u, &alpha_v))
        return false;
    if (!(alpha_u >= 0.0) || !(alpha_v >= 0.0) || alpha_u > 1.0 || alpha_v > 1.0)
        return mi_fail(m, e, "alpha %g, %g must be in [0, 1]", alpha_u, alpha_v);
    double r = pow(alpha_u * alpha_v, 0.25), a = alpha_u > 0.0 ? (1.0 - alpha_v / alpha_u) / 0.9 : 0.0;
    if (a != 0.0 && (!anisotropic_ok || a < 0.0 || a >= 1.0)) {
        mi_warn_once(m, e, "anisotropy", "alpha_u %g, alpha_v %g: pt's anisotropy stretches along u "
                                         "up to alpha_u/alpha_v = 10 only; isotropic alpha %g instead",
                     alpha_u, alpha_v, r * r);
        a = 0.0;
    }
    cJSON_AddNumberToObject(material, "roughness", r);
    if (a > 0.0)
        cJSON_AddNumberToObject(material, "anisotropy", a);
    return true;
}

static bool conductor(Mitsuba *m, const XmlElement *e, bool rough, cJSON *material)
{
    cJSON_AddStringToObject(material, "type", "conductor");
    const char *preset = mi_string(m, e, "material", NULL);
    const XmlElement *eta = mi_prop(m, e, "eta"), *k = mi_prop(m, e, "k");
    double eta_rgb[3] = {0.0, 0.0, 0.0}, k_rgb[3] = {1.0, 1.0, 1.0}; /* Mitsuba's defaults */
    if (eta || k) {
        if ((eta && !mi_spectrum_rgb(m, eta, eta_rgb)) || (k && !mi_spectrum_rgb(m, k, k_rgb)))
            return false;
    } else {
        preset = preset ? preset : "none"; /* Mitsuba's default: eta 0, k 1, Fresnel 1 */
        size_t i = 0, n = sizeof conductors / sizeof conductors[0];
        while (i < n && strcmp(conductors[i].name, preset))
            i++;
        if (i == n && strcmp(preset, "none"))
            mi_warn_once(m, e, preset, "conductor material \"%s\" not in pt's table: a perfect mirror", preset);
        if (i < n) {
            memcpy(eta_rgb, conductors[i].eta, sizeof eta_rgb);
            memcpy(k_rgb, conductors[i].k, sizeof k_rgb);
        } else {
            eta_rgb[0] = -1.0; /* pt's Fresnel 1: no eta, no k */
        }
    }
    if (eta_rgb[0] >= 0.0) {
        cJSON_AddItemToObject(material, "eta", mi_rgb_json(eta_rgb));
        cJSON_AddItemToObject(material, "k", mi_rgb_json(k_rgb));
    }
    cJSON *reflectance;
    if (!mi_colour(m, e, "specular_reflectance", 1.0, &reflectance))
        return false;
    cJSON_AddItemToObject(material, "reflectance", reflectance);
    return !rough || roughness(m, e, material, true);
}

static bool ior_ratio(Mitsuba *m, const XmlElement *e, double int_default, double *out)
{
    double int_ior, ext_ior;
    if (!ior_value(m, e, "int_ior", int_default, &int_ior) || !ior_value(m, e, "ext_ior", 1.000277, &ext_ior))
        return false;
    *out = int_ior / ext_ior;
    return true;
}

static bool dielectric(Mitsuba *m, const XmlElement *e, bool rough, cJSON *material)
{
    double ior;
    cJSON *tint;
    if (!ior_ratio(m, e, 1.5046, &ior) || !mi_colour(m, e, "specular_transmittance", 1.0, &tint))
        return false;
    cJSON_AddStringToObject(material, "type", "dielectric");
    cJSON_AddNumberToObject(material, "ior", ior);
    cJSON_AddItemToObject(material, "tint", tint);
    mi_prop(m, e, "specular_reflectance");
    return !rough || roughness(m, e, material, false);
}

/* A thin sheet reflects R = 2 R0 / (1 + R0) and passes the rest straight through: a mirror that
 * rays cross with probability 1 - R (pt's opacity), R0 the Fresnel reflectance at normal
 * incidence (the angular dependence is lost). */
static bool thin_dielectric(Mitsuba *m, const XmlElement *e, cJSON *material)
{
    double ior;
    if (!ior_ratio(m, e, 1.5046, &ior))
        return false;
    double r0 = (ior - 1.0) * (ior - 1.0) / ((ior + 1.0) * (ior + 1.0)), r = 2.0 * r0 / (1.0 + r0);
    mi_warn_once(m, e, "thindielectric", "thindielectric as a mirror with opacity %g (pt has no thin "
                                         "dielectric; the reflectance does not vary with angle)", r);
    cJSON_AddStringToObject(material, "type", "conductor");
    cJSON_AddNumberToObject(material, "opacity", r);
    mi_prop(m, e, "specular_reflectance");
    mi_prop(m, e, "specular_transmittance");
    return true;
}

/* A colour or scalar parameter read into material[key] at once (nothing to free on a later
 * failure: the material owns it). */
static bool add_colour(Mitsuba *m, const XmlElement *e, const char *name, double fallback, cJSON *material,
                       const char *key)
{
    cJSON *value;
    if (!mi_colour(m, e, name, fallback, &value))
        return false;
    cJSON_AddItemToObject(material, key, value);
    return true;
}

static bool add_scalar(Mitsuba *m, const XmlElement *e, const char *name, double fallback, cJSON *material,
                       const char *key)
{
    cJSON *value;
    if (!mi_scalar(m, e, name, fallback, &value))
        return false;
    cJSON_AddItemToObject(material, key, value);
    return true;
}

/* plastic: a diffuse base under a smooth or rough dielectric coat, as pt's principled with
 * metallic 0 (Lambert under a GGX specular lobe with Schlick Fresnel at the coat's ior): the same
 * highlight and base colour, without the coat's internal reflections that darken and saturate
 * Mitsuba's diffuse part. */
static bool plastic(Mitsuba *m, const XmlElement *e, bool rough, cJSON *material)
{
    double ior;
    cJSON_AddStringToObject(material, "type", "principled");
    if (!ior_ratio(m, e, 1.49, &ior) || !add_colour(m, e, "diffuse_reflectance", 0.5, material, "base_color"))
        return false;
    const XmlElement *specular = mi_prop(m, e, "specular_reflectance");
    if (specular && (strcmp(specular->name, "texture") == 0 || strcmp(specular->name, "ref") == 0))
        mi_warn_once(m, specular, "plastic-specular", "textured specular_reflectance: white (pt's "
                                                      "specular_color takes a colour)");
    else if (specular && !add_colour(m, e, "specular_reflectance", 1.0, material, "specular_color"))
        return false;
    cJSON_AddNumberToObject(material, "metallic", 0.0);
    cJSON_AddNumberToObject(material, "ior", ior);
    mi_prop(m, e, "nonlinear");
    mi_warn_once(m, e, "plastic", "plastic as pt's principled (metallic 0): no internal scattering in the coat");
    if (!rough) {
        cJSON_AddNumberToObject(material, "roughness", 0.0);
        return true;
    }
    return roughness(m, e, material, false);
}

/* Mitsuba's principled is Disney's; pt's is glTF's: base colour, metallic and roughness carry
 * over, specular s (F0 = 0.08 s) becomes the ior with that F0. */
static bool principled(Mitsuba *m, const XmlElement *e, cJSON *material)
{
    double specular;
    cJSON_AddStringToObject(material, "type", "principled");
    if (!add_colour(m, e, "base_color", 0.5, material, "base_color") ||
        !add_scalar(m, e, "metallic", 0.0, material, "metallic") ||
        !add_scalar(m, e, "roughness", 0.5, material, "roughness") || !mi_float(m, e, "specular", 0.5, &specular))
        return false;
    double f0 = fmin(fmax(0.08 * specular, 0.0), 0.99), root = sqrt(f0);
    if (f0 > 0.0)
        cJSON_AddNumberToObject(material, "ior", (1.0 + root) / (1.0 - root));
    else
        cJSON_AddNumberToObject(material, "specular", 0.0);
    return true;
}

/* The nested bsdf elements of e (twosided, blendbsdf, mask, normalmap, bumpmap). */
static int nested_bsdfs(const XmlElement *e, const XmlElement *out[2])
{
    int n = 0;
    for (int i = 0; i < e->num_children; i++) {
        const XmlElement *c = e->children[i];
        if (strcmp(c->name, "bsdf") == 0 || (strcmp(c->name, "ref") == 0 && !xml_attribute(c, "name")) ||
            (strcmp(c->name, "ref") == 0 && xml_attribute(c, "name") &&
             strncmp(xml_attribute(c, "name"), "bsdf", 4) == 0)) {
            if (n < 2)
                out[n] = c;
            n++;
        }
    }
    return n;
}

static bool build_material(Mitsuba *m, const XmlElement *e, cJSON **material);

/* A wrapper's material: the nested one's JSON, then changed. A nested bsdf of its own is built
 * in place (no material of its own: the scene holds what shapes use); a shared one (a ref) is
 * copied. */
static bool copy_nested(Mitsuba *m, const XmlElement *e, const XmlElement *nested, cJSON **material)
{
    cJSON *copy = NULL;
    if (strcmp(nested->name, "bsdf") == 0 && !mi_find_mapped(m, nested)) {
        if (!build_material(m, nested, &copy))
            return false;
    } else {
        char inner[SCENE_NAME_LIMIT];
        if (!mi_bsdf(m, nested, inner))
            return false;
        copy = cJSON_Duplicate(cJSON_GetObjectItemCaseSensitive(m->materials, inner), true);
    }
    if (!copy)
        return mi_fail(m, e, "out of memory");
    cJSON_Delete(*material);
    *material = copy;
    return true;
}

static void replace_item(cJSON *object, const char *key, cJSON *value)
{
    cJSON_DeleteItemFromObjectCaseSensitive(object, key);
    cJSON_AddItemToObject(object, key, value);
}

static bool wrapper(Mitsuba *m, const XmlElement *e, const char *type, cJSON **material)
{
    const XmlElement *nested[2] = {NULL, NULL};
    int n = nested_bsdfs(e, nested);
    int wanted = strcmp(type, "blendbsdf") == 0 ? 2 : 1;
    if (n < wanted || (n > wanted && strcmp(type, "twosided")))
        return mi_fail(m, e, "needs %d nested bsdf%s", wanted, wanted == 1 ? "" : "s");
    if (strcmp(type, "twosided") == 0) {
        if (n == 2)
            mi_warn_once(m, e, "twosided2", "two different sides: pt shades both with the first");
        return copy_nested(m, e, nested[0], material); /* pt's surfaces are two-sided already */
    }
    if (strcmp(type, "blendbsdf") == 0) {
        char a[SCENE_NAME_LIMIT], b[SCENE_NAME_LIMIT];
        cJSON *weight;
        if (!mi_bsdf(m, nested[0], a) || !mi_bsdf(m, nested[1], b) || !mi_scalar(m, e, "weight", 0.5, &weight))
            return false;
        cJSON_AddStringToObject(*material, "type", "mix");
        cJSON_AddStringToObject(*material, "a", a);
        cJSON_AddStringToObject(*material, "b", b);
        cJSON_AddItemToObject(*material, "weight", weight);
        return true;
    }
    if (!copy_nested(m, e, nested[0], material))
        return false;
    cJSON *value;
    if (strcmp(type, "mask") == 0) {
        if (!mi_scalar(m, e, "opacity", 0.5, &value))
            return false;
        replace_item(*material, "opacity", value);
        return true;
    }
    const XmlElement *p = NULL;
    for (int i = 0; i < e->num_children && !p; i++)
        if (strcmp(e->children[i]->name, "texture") == 0 || (strcmp(e->children[i]->name, "ref") == 0 &&
                                                             e->children[i] != nested[0]))
            p = e->children[i];
    if (!p)
        return mi_fail(m, e, "needs a nested texture");
    ((XmlElement *)p)->used = true;
    char texture[SCENE_NAME_LIMIT];
    double mean[3];
    bool is_texture;
    if (!mi_texture(m, p, true, texture, mean, &is_texture))
        return false;
    if (!is_texture)
        return true; /* warned: no map */
    if (strcmp(type, "normalmap") == 0) {
        replace_item(*material, "normal_map", cJSON_CreateString(texture));
        return true;
    }
    double scale;
    if (!mi_float(m, e, "scale", 1.0, &scale))
        return false;
    replace_item(*material, "bump_map", cJSON_CreateString(texture));
    replace_item(*material, "bump_scale", cJSON_CreateNumber(scale));
    return true;
}

static bool map_bsdf(Mitsuba *m, const XmlElement *e, cJSON **material)
{
    const char *type = xml_attribute(e, "type");
    if (!type)
        return mi_fail(m, e, "missing type=\"...\"");
    if (strcmp(type, "diffuse") == 0) {
        cJSON_AddStringToObject(*material, "type", "diffuse");
        return add_colour(m, e, "reflectance", 0.5, *material, "albedo");
    }
    if (strcmp(type, "conductor") == 0 || strcmp(type, "roughconductor") == 0)
        return conductor(m, e, type[0] == 'r', *material);
    if (strcmp(type, "dielectric") == 0 || strcmp(type, "roughdielectric") == 0)
        return dielectric(m, e, type[0] == 'r', *material);
    if (strcmp(type, "thindielectric") == 0)
        return thin_dielectric(m, e, *material);
    if (strcmp(type, "plastic") == 0 || strcmp(type, "roughplastic") == 0)
        return plastic(m, e, type[0] == 'r', *material);
    if (strcmp(type, "principled") == 0)
        return principled(m, e, *material);
    if (strcmp(type, "null") == 0) { /* invisible: only where media meet (a shape's interior) */
        cJSON_AddStringToObject(*material, "type", "interface");
        return true;
    }
    static const char *const wrappers[] = {"twosided", "blendbsdf", "mask", "normalmap", "bumpmap"};
    for (size_t i = 0; i < sizeof wrappers / sizeof wrappers[0]; i++)
        if (strcmp(type, wrappers[i]) == 0)
            return wrapper(m, e, type, material);
    char key[64];
    snprintf(key, sizeof key, "bsdf.%.40s", type);
    mi_warn_once(m, e, key, "bsdf type not read by pt: diffuse 0.5 instead");
    cJSON_AddStringToObject(*material, "type", "diffuse");
    cJSON_AddNumberToObject(*material, "albedo", 0.5);
    return true;
}

bool mi_bsdf(Mitsuba *m, const XmlElement *e, char out[SCENE_NAME_LIMIT])
{
    bool done;
    if (!mi_follow(m, e, "bsdf", mi_bsdf, out, &done) || done)
        return done;
    cJSON *material;
    if (!build_material(m, e, &material))
        return false;
    mi_new_name(m, e, "bsdf", out);
    cJSON_AddItemToObject(m->materials, out, material);
    return mi_remember(m, e, out);
}

/* The pt material of a <bsdf> element, not yet in the scene. */
static bool build_material(Mitsuba *m, const XmlElement *e, cJSON **material)
{
    if (m->include_depth > 64)
        return mi_fail(m, e, "bsdfs nested too deeply");
    m->include_depth++;
    *material = cJSON_CreateObject();
    bool ok = *material && map_bsdf(m, e, material);
    m->include_depth--;
    if (!ok) {
        cJSON_Delete(*material);
        *material = NULL;
        return error_is_set(m->err) ? false : mi_fail(m, e, "out of memory");
    }
    mi_warn_unused(m, e);
    return true;
}
