// SPDX-License-Identifier: MIT
/* mitsuba_sensor.c: a Mitsuba sensor (perspective, thinlens) with its film and sampler as pt's
 * camera, film and render.spp; the integrator's max_depth as render.max_depth. */
#include "scene/mitsuba_internal.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "scene/scene_types.h"

#define PI 3.14159265358979323846


/* Mitsuba's fov (along fov_axis, or from focal_length on a 36 x 24 mm diagonal) as pt's vertical
 * field of view for a film of the given aspect. */
static bool vertical_fov(Mitsuba *m, const XmlElement *e, double aspect, double *fov_y)
{
    double fov;
    const char *axis = mi_string(m, e, "fov_axis", "x");
    const char *focal = mi_string(m, e, "focal_length", NULL);
    if (!mi_float(m, e, "fov", 0.0, &fov))
        return false;
    if (!mi_prop(m, e, "fov")) {
        double mm = focal ? atof(focal) : 50.0;
        if (!(mm > 0.0))
            return mi_fail(m, e, "focal_length \"%.20s\" is not <x>mm", focal);
        fov = 2.0 * atan(sqrt(36.0 * 36.0 + 24.0 * 24.0) / (2.0 * mm)) * 180.0 / PI;
        axis = "diagonal";
    }
    if (!(fov > 0.0 && fov < 180.0))
        return mi_fail(m, e, "fov %g must be in (0, 180)", fov);
    if (strcmp(axis, "smaller") == 0)
        axis = aspect > 1.0 ? "y" : "x";
    else if (strcmp(axis, "larger") == 0)
        axis = aspect > 1.0 ? "x" : "y";
    if (strcmp(axis, "y") == 0) { /* as given: no tan/atan rounding */
        *fov_y = fov;
        return true;
    }
    double t = tan(0.5 * fov * PI / 180.0);
    if (strcmp(axis, "x") == 0)
        t /= aspect;
    else if (strcmp(axis, "diagonal") == 0)
        t /= sqrt(1.0 + aspect * aspect);
    else
        return mi_fail(m, e, "fov_axis \"%.20s\" is not x, y, diagonal, smaller or larger", axis);
    *fov_y = 2.0 * atan(t) * 180.0 / PI;
    return true;
}

static bool film(Mitsuba *m, const XmlElement *e, cJSON *root)
{
    const char *type = xml_attribute(e, "type");
    if (type && strcmp(type, "hdrfilm"))
        mi_warn_once(m, e, "film", "film type %.40s read as hdrfilm (width, height)", type);
    if (!mi_int(m, e, "width", 768, &m->width) || !mi_int(m, e, "height", 576, &m->height))
        return false;
    if (m->width < 1 || m->height < 1 || m->width > 65536 || m->height > 65536)
        return mi_fail(m, e, "width %d, height %d out of range", m->width, m->height);
    cJSON *f = cJSON_AddObjectToObject(root, "film");
    cJSON_AddNumberToObject(f, "width", m->width);
    cJSON_AddNumberToObject(f, "height", m->height);
    const XmlElement *filter = NULL;
    for (int i = 0; i < e->num_children; i++)
        if (strcmp(e->children[i]->name, "rfilter") == 0)
            filter = e->children[i];
    const char *filter_type = filter ? xml_attribute(filter, "type") : "gaussian";
    if (!filter_type || strcmp(filter_type, "box"))
        mi_warn_once(m, filter ? filter : e, "rfilter", "reconstruction filter %s%s: pt's film is a box filter",
                     filter_type ? filter_type : "?", filter ? "" : " (Mitsuba's default)");
    static const char *const harmless[] = {"pixel_format", "component_format", "file_format", "banner",
                                           "sample_border", "compensate", NULL};
    for (int i = 0; harmless[i]; i++)
        mi_prop(m, e, harmless[i]);
    mi_warn_unused(m, e);
    return true;
}

static bool sampler(Mitsuba *m, const XmlElement *e, cJSON *render)
{
    int spp;
    if (!mi_int(m, e, "sample_count", 4, &spp))
        return false;
    if (spp < 1)
        return mi_fail(m, e, "sample_count %d must be >= 1", spp);
    mi_prop(m, e, "seed");
    mi_prop(m, e, "jitter");
    cJSON_AddNumberToObject(render, "spp", spp);
    return true;
}

static void vec3(cJSON *o, const char *key, const double v[3])
{
    cJSON_AddItemToObject(o, key, cJSON_CreateDoubleArray(v, 3));
}

/* Mitsuba's camera looks along +z of to_world with +y up; its image's x runs along -x (look_at's
 * "left" column is up x dir): pt's right-handed frame when to_world does not mirror. */
bool mi_sensor(Mitsuba *m, const XmlElement *e, cJSON *root, cJSON *render)
{
    const char *type = xml_attribute(e, "type");
    if (m->has_sensor) {
        mi_warn_once(m, e, "sensor2", "a second sensor: ignored (pt renders the first)");
        return true;
    }
    m->has_sensor = true;
    if (!type || (strcmp(type, "perspective") && strcmp(type, "thinlens")))
        return mi_fail(m, e, "sensor type \"%.40s\" is not perspective or thinlens", type ? type : "");
    for (int i = 0; i < e->num_children; i++) { /* the film first: fov_axis needs its aspect */
        const XmlElement *c = e->children[i];
        if (strcmp(c->name, "film") == 0 && !film(m, c, root))
            return false;
        if (strcmp(c->name, "sampler") == 0 && !sampler(m, c, render))
            return false;
    }
    if (!m->width && !film(m, &(XmlElement){.name = "film", .line = e->line}, root))
        return false;
    Affine a;
    double fov_y = 0.0;
    if (!mi_transform(m, e, "to_world", &a) || !vertical_fov(m, e, (double)m->width / m->height, &fov_y))
        return false;
    double o[3] = {0, 0, 0}, z[3] = {0, 0, 1}, y[3] = {0, 1, 0}, x[3] = {1, 0, 0};
    double eye[3], dir[3], up[3], left[3], target[3];
    affine_point(&a, o, eye);
    affine_vector(&a, z, dir);
    affine_vector(&a, y, up);
    affine_vector(&a, x, left);
    double right_check[3] = {dir[1] * up[2] - dir[2] * up[1], dir[2] * up[0] - dir[0] * up[2],
                             dir[0] * up[1] - dir[1] * up[0]};
    if (right_check[0] * left[0] + right_check[1] * left[1] + right_check[2] * left[2] > 0.0)
        mi_warn_once(m, e, "mirror-camera", "to_world mirrors the image: pt renders it unmirrored");
    double length = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
    if (!(length > 0.0))
        return mi_fail(m, e, "to_world collapses the view direction");
    for (int i = 0; i < 3; i++)
        target[i] = eye[i] + dir[i] / length;
    cJSON *camera = cJSON_AddObjectToObject(root, "camera");
    vec3(camera, "eye", eye);
    vec3(camera, "target", target);
    vec3(camera, "up", up);
    cJSON_AddNumberToObject(camera, "fov_y", fov_y);
    if (!mi_sensor_medium(m, e, camera))
        return false;
    if (strcmp(type, "thinlens") == 0) {
        double radius, focus;
        if (!mi_float(m, e, "aperture_radius", 0.0, &radius) || !mi_float(m, e, "focus_distance", 1.0, &focus))
            return false;
        if (!(radius >= 0.0) || !(focus > 0.0))
            return mi_fail(m, e, "aperture_radius %g must be >= 0 and focus_distance %g > 0", radius, focus);
        cJSON_AddNumberToObject(camera, "aperture", 2.0 * radius); /* pt: the lens diameter */
        cJSON_AddNumberToObject(camera, "focus_distance", focus);
    }
    if (strcmp(type, "perspective") == 0)
        mi_prop(m, e, "focus_distance"); /* Mitsuba's perspective takes it and ignores it */
    mi_prop(m, e, "near_clip");
    mi_prop(m, e, "far_clip");
    mi_warn_unused(m, e);
    return true;
}

/* Mitsuba's max_depth counts as pt's (1: emitters seen directly, 2: direct light); -1 is
 * unlimited, pt's limit instead. */
bool mi_integrator(Mitsuba *m, const XmlElement *e, cJSON *render)
{
    const char *type = xml_attribute(e, "type");
    int depth;
    if (type && (strcmp(type, "path") == 0 || strcmp(type, "volpath") == 0 || strcmp(type, "volpathmis") == 0 ||
                 strcmp(type, "prb") == 0)) {
        if (!mi_int(m, e, "max_depth", -1, &depth))
            return false;
    } else if (type && strcmp(type, "direct") == 0) {
        depth = 2;
        mi_warn_once(m, e, "direct", "direct illumination as pt's path tracer with max_depth 2");
    } else {
        mi_warn_once(m, e, "integrator", "integrator \"%.40s\" not read by pt: its path tracer", type ? type : "");
        return true;
    }
    if (depth == -1 || depth > MAX_DEPTH_LIMIT) {
        mi_warn_once(m, e, "max_depth", "max_depth %d: pt's limit %d", depth, MAX_DEPTH_LIMIT);
        depth = MAX_DEPTH_LIMIT;
    }
    if (depth < 1)
        return mi_fail(m, e, "max_depth %d: pt needs at least 1", depth);
    bool hide;
    if (!mi_bool(m, e, "hide_emitters", false, &hide))
        return false;
    if (hide)
        mi_warn_once(m, e, "hide_emitters", "hide_emitters: pt shows emitters");
    mi_prop(m, e, "rr_depth");
    mi_warn_unused(m, e);
    cJSON_DeleteItemFromObjectCaseSensitive(render, "max_depth");
    cJSON_AddNumberToObject(render, "max_depth", depth);
    return true;
}

