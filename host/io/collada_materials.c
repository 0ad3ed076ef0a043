// SPDX-License-Identifier: MIT
/* collada_materials.c: COLLADA materials and their effects, with the CGL (CS184/CMU462)
 * extras, and cameras and lights (io/collada_internal.h). */
#include "io/collada_internal.h"

#include <libxml/parser.h>
#include <libxml/tree.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/fs.h"

/* ---------------------------------------------------------------- materials */

static void default_material(ObjMaterial *m, const char *name)
{
    memset(m, 0, sizeof *m);
    snprintf(m->name, sizeof m->name, "%s", name);
    m->kd[0] = m->kd[1] = m->kd[2] = 0.8f;
    m->tf[0] = m->tf[1] = m->tf[2] = 1.0f;
    m->ni = 1.0f, m->d = 1.0f, m->illum = -1, m->bump_scale = 1.0f;
}

/* A <texture texture="..."> of an effect: its image's file, through COLLADA 1.4's
 * sampler2D -> surface -> image chain or straight to an image. */
static bool texture_file(Reader *r, const xmlNode *effect, const xmlNode *tex, char *out, size_t size)
{
    const char *name = collada_attr(tex, "texture");
    const xmlNode *image = NULL;
    for (int hops = 0; name && hops < 4 && !image; hops++) {
        const xmlNode *param = NULL;
        for (xmlNode *profile = effect->children; profile && !param; profile = profile->next)
            for (xmlNode *np = collada_child(profile, "newparam"); np && !param; np = collada_next_named(np, "newparam"))
                if (collada_attr(np, "sid") && strcmp(collada_attr(np, "sid"), name) == 0)
                    param = np;
        if (!param) {
            xmlNode *hit = collada_lookup(r, name);
            image = collada_is(hit, "image") ? hit : NULL;
            break;
        }
        xmlNode *sampler = collada_child(param, "sampler2D"), *surface = collada_child(param, "surface");
        name = sampler ? collada_text(collada_child(sampler, "source")) : surface ? collada_text(collada_child(surface, "init_from")) : NULL;
        if (sampler && collada_child(sampler, "instance_image")) { /* COLLADA 1.5 */
            xmlNode *hit = collada_lookup(r, collada_attr(collada_child(sampler, "instance_image"), "url"));
            image = collada_is(hit, "image") ? hit : NULL;
        }
    }
    const xmlNode *init = collada_child(image, "init_from");
    const char *file = collada_child(init, "ref") ? collada_text(collada_child(init, "ref")) : init ? collada_text(init) : NULL;
    if (!file || !*file) {
        collada_warn_once(r, DROP_TEXTURE, "a texture whose image cannot be found (\"%s\") dropped",
                  collada_attr(tex, "texture") ? collada_attr(tex, "texture") : "");
        return true;
    }
    if (strncmp(file, "file://", 7) == 0)
        file += 7;
    char decoded[1024];
    size_t k = 0;
    for (const char *s = file; *s && k + 1 < sizeof decoded; s++) {
        unsigned hex;
        if (s[0] == '%' && sscanf(s + 1, "%2x", &hex) == 1 && s[1] && s[2])
            decoded[k++] = (char)hex, s += 2;
        else
            decoded[k++] = *s;
    }
    decoded[k] = '\0';
    return fs_resolve_inside(r->path, decoded, "<image><init_from>", out, size, r->err);
}

static void read_cgl(Reader *r, const xmlNode *tech, ColladaMaterial *m)
{
    xmlNode *bsdf = NULL;
    for (xmlNode *c = tech ? tech->children : NULL; c && !bsdf; c = c->next)
        if (c->type == XML_ELEMENT_NODE)
            bsdf = c;
    if (!bsdf)
        return;
    float alpha_unused;
    for (int c = 0; c < 3; c++)
        m->reflectance[c] = m->transmittance[c] = 1.0f;
    m->ior = 1.5f;
    if (collada_is(bsdf, "emission")) {
        m->cgl = CGL_EMISSION;
        collada_color_of(collada_child(bsdf, "radiance"), m->radiance, &alpha_unused);
    } else if (collada_is(bsdf, "mirror")) {
        m->cgl = CGL_MIRROR;
        collada_color_of(collada_child(bsdf, "reflectance"), m->reflectance, &alpha_unused);
    } else if (collada_is(bsdf, "diffuse")) {
        m->cgl = CGL_DIFFUSE;
        collada_color_of(collada_child(bsdf, "reflectance"), m->reflectance, &alpha_unused);
    } else if (collada_is(bsdf, "microfacet")) {
        m->cgl = CGL_MICROFACET;
        double a = 0.5;
        bool bad;
        if (collada_child(bsdf, "alpha") && collada_read_numbers(collada_text(collada_child(bsdf, "alpha")), &a, 1, &bad) == 1 && a >= 0)
            m->alpha = (float)a;
        else
            m->alpha = 0.5f;
        collada_color_of(collada_child(bsdf, "eta"), m->eta, &alpha_unused);
        collada_color_of(collada_child(bsdf, "k"), m->k, &alpha_unused);
    } else if (collada_is(bsdf, "glass") || collada_is(bsdf, "refraction")) {
        if (collada_is(bsdf, "refraction"))
            collada_warn_once(r, DROP_REFRACTION, "CGL <refraction> (transmission only) read as glass%s", "");
        m->cgl = CGL_GLASS;
        double v;
        bool bad;
        if (collada_read_numbers(collada_text(collada_child(bsdf, "ior")), &v, 1, &bad) == 1 && v > 0)
            m->ior = (float)v;
        if (collada_read_numbers(collada_text(collada_child(bsdf, "roughness")), &v, 1, &bad) == 1 && v >= 0)
            m->roughness = (float)v;
        collada_color_of(collada_child(bsdf, "reflectance"), m->reflectance, &alpha_unused);
        collada_color_of(collada_child(bsdf, "transmittance"), m->transmittance, &alpha_unused);
    } else {
        collada_warn_once(r, DROP_CGL, "CGL technique <%s> not known: the common profile is used",
                  (const char *)bsdf->name);
    }
}

bool collada_read_material(Reader *r, const xmlNode *mat, ColladaMaterial *m)
{
    const char *id = collada_attr(mat, "id") ? collada_attr(mat, "id") : "";
    snprintf(m->id, sizeof m->id, "%s", id);
    default_material(&m->common, id);
    xmlNode *effect = collada_lookup(r, collada_attr(collada_child(mat, "instance_effect"), "url"));
    if (!collada_is(effect, "effect"))
        return true; /* COLLADA's default: a grey surface */
    xmlNode *tech = collada_path_child(effect, "profile_COMMON/technique");
    xmlNode *model = NULL;
    for (xmlNode *c = tech ? tech->children : NULL; c && !model; c = c->next)
        if (collada_is(c, "constant") || collada_is(c, "lambert") || collada_is(c, "phong") || collada_is(c, "blinn"))
            model = c;
    ObjMaterial *o = &m->common;
    if (model) {
        bool specular = collada_is(model, "phong") || collada_is(model, "blinn");
        o->illum = specular ? 2 : 1;
        float a;
        xmlNode *e;
        if ((e = collada_child(model, "diffuse"))) {
            if (collada_child(e, "color"))
                collada_color_of(collada_child(e, "color"), o->kd, &a);
            else if (collada_child(e, "texture")) {
                if (!texture_file(r, effect, collada_child(e, "texture"), o->map_kd, sizeof o->map_kd))
                    return false;
                o->kd[0] = o->kd[1] = o->kd[2] = 1.0f;
            }
        }
        if (collada_is(model, "constant")) /* unlit: its emission is the colour seen */
            o->kd[0] = o->kd[1] = o->kd[2] = 0.0f;
        if ((e = collada_child(collada_child(model, "emission"), "color")))
            collada_color_of(e, o->ke, &a);
        if (specular && (e = collada_child(collada_child(model, "specular"), "color")))
            collada_color_of(e, o->ks, &a);
        double v;
        bool bad;
        if (specular && collada_read_numbers(collada_text(collada_path_child(model, "shininess/float")), &v, 1, &bad) == 1)
            o->ns = (float)v, o->has_ns = true;
        if (collada_read_numbers(collada_text(collada_path_child(model, "index_of_refraction/float")), &v, 1, &bad) == 1 && v > 0)
            o->ni = (float)v;
        /* Opacity (COLLADA 1.4.1 spec 7-16): A_ONE (default) uses the transparent colour's
         * alpha times transparency; RGB_ZERO one minus their luminance. */
        xmlNode *transparent = collada_child(model, "transparent");
        double t = 1.0;
        collada_read_numbers(collada_text(collada_path_child(model, "transparency/float")), &t, 1, &bad);
        if (transparent && collada_child(transparent, "color")) {
            float rgb[3] = {0, 0, 0}, alpha = 1.0f;
            collada_color_of(collada_child(transparent, "color"), rgb, &alpha);
            const char *mode = collada_attr(transparent, "opaque");
            double opacity = mode && strcmp(mode, "RGB_ZERO") == 0
                                 ? 1.0 - t * (0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2])
                                 : alpha * t;
            o->d = (float)fmin(1.0, fmax(0.0, opacity));
        }
    }
    read_cgl(r, collada_cgl_technique(r, effect, 0), m);
    return true;
}

/* ---------------------------------------------------------------- cameras, lights */

void collada_read_camera(Reader *r, const xmlNode *cam, ColladaCamera *c)
{
    snprintf(c->id, sizeof c->id, "%s", collada_attr(cam, "id") ? collada_attr(cam, "id") : "");
    xmlNode *tech = collada_path_child(cam, "optics/technique_common");
    xmlNode *persp = collada_child(tech, "perspective");
    double v;
    bool bad;
    if (!persp) {
        c->orthographic = collada_child(tech, "orthographic") != NULL;
        collada_warn_once(r, DROP_ORTHO, "orthographic camera \"%s\" read as a perspective one", c->id);
        return;
    }
    if (collada_read_numbers(collada_text(collada_child(persp, "xfov")), &v, 1, &bad) == 1 && v > 0 && v < 180)
        c->xfov = (float)v;
    if (collada_read_numbers(collada_text(collada_child(persp, "yfov")), &v, 1, &bad) == 1 && v > 0 && v < 180)
        c->yfov = (float)v;
    if (collada_read_numbers(collada_text(collada_child(persp, "aspect_ratio")), &v, 1, &bad) == 1 && v > 0 && v < 1e4)
        c->aspect = (float)v;
}

void collada_read_light(Reader *r, const xmlNode *light, ColladaLight *l)
{
    snprintf(l->id, sizeof l->id, "%s", collada_attr(light, "id") ? collada_attr(light, "id") : "");
    l->falloff_angle = 180.0f;
    xmlNode *area = collada_path_child(collada_cgl_technique(r, light, 0), "area");
    float a;
    if (area) { /* CS184 reads the CGL technique before technique_common */
        l->type = COLLADA_LIGHT_AREA;
        collada_color_of(collada_child(area, "color"), l->color, &a);
        return;
    }
    xmlNode *tech = collada_path_child(light, "technique_common"), *kind = NULL;
    for (xmlNode *c = tech ? tech->children : NULL; c && !kind; c = c->next)
        if (c->type == XML_ELEMENT_NODE)
            kind = c;
    l->type = collada_is(kind, "spot") ? COLLADA_LIGHT_SPOT : collada_is(kind, "directional") ? COLLADA_LIGHT_DIRECTIONAL :
              collada_is(kind, "ambient") ? COLLADA_LIGHT_AMBIENT : COLLADA_LIGHT_POINT;
    collada_color_of(collada_child(kind, "color"), l->color, &a);
    double v;
    bool bad;
    if (collada_read_numbers(collada_text(collada_child(kind, "falloff_angle")), &v, 1, &bad) == 1 && v > 0 && v <= 360)
        l->falloff_angle = (float)v;
    double lin = 0, quad = 0;
    collada_read_numbers(collada_text(collada_child(kind, "linear_attenuation")), &lin, 1, &bad);
    collada_read_numbers(collada_text(collada_child(kind, "quadratic_attenuation")), &quad, 1, &bad);
    l->attenuated = lin != 0 || quad != 0;
}
