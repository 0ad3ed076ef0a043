// SPDX-License-Identifier: MIT
/* mitsuba_media.c: Mitsuba 3 media as pt's "media" (shared/DESIGN.md "Media"):
 *   <medium type="homogeneous">: sigma_t, albedo (Mitsuba 3) or sigma_a, sigma_s (Mitsuba 0.6's
 *     names), scale, <phase type="hg"> g; sigma_s = albedo sigma_t scale, sigma_a = (1 - albedo)
 *     sigma_t scale;
 *   <medium type="heterogeneous"> whose sigma_t is a <volume type="gridvolume"> (.vol): a pt grid
 *     medium with density_scale = scale and a constant albedo. Mitsuba places the grid on the unit
 *     cube, then its to_world (use_grid_bbox false, the default), or on the file's bounding box
 *     then to_world (use_grid_bbox true: src/volumes/grid.cpp composes the box's transform into
 *     to_local); pt places a .vol on its header's box, so without use_grid_bbox the header is read
 *     here and the box mapped onto the unit cube first;
 *   a shape's <medium name="interior|exterior"> or <ref name="interior|exterior" id=...>: the
 *     object's interior / exterior; the sensor's <medium> or <ref id=...> to one: camera.medium.
 * Mitsuba has no world medium: the camera's and the shapes' exteriors say where media are. */
#include "scene/mitsuba_internal.h"

#include <stdio.h>
#include <string.h>

#include "io/volume_grid.h"

static const XmlElement *phase_of(const XmlElement *e)
{
    for (int i = 0; i < e->num_children; i++)
        if (strcmp(e->children[i]->name, "phase") == 0)
            return e->children[i];
    return NULL;
}

/* The medium's g: hg's, 0 for isotropic (and for the phase types pt does not have, warned). */
static bool phase_g(Mitsuba *m, const XmlElement *e, double *g)
{
    const XmlElement *phase = phase_of(e);
    const char *type = phase ? xml_attribute(phase, "type") : NULL;
    *g = 0.0;
    if (!phase || (type && strcmp(type, "isotropic") == 0))
        return true;
    ((XmlElement *)phase)->used = true;
    if (!type || strcmp(type, "hg")) {
        mi_warn_once(m, phase, "phase", "phase function \"%.40s\": pt's media scatter by "
                                        "Henyey-Greenstein; isotropic (g 0) instead",
                     type ? type : "");
        return true;
    }
    if (!mi_float(m, phase, "g", 0.8, g)) /* Mitsuba's hg defaults to g = 0.8 */
        return false;
    if (!(*g > -1.0 && *g < 1.0))
        return mi_fail(m, phase, "g %g is outside (-1, 1)", *g);
    mi_warn_unused(m, phase);
    return true;
}

/* A constant colour property (a float, rgb, spectrum or constvolume); *volume is the property
 * when it is another volume (a grid), which the caller decides about. */
static bool constant(Mitsuba *m, const XmlElement *e, const char *name, double fallback,
                     double rgb[3], const XmlElement **volume)
{
    XmlElement *p = mi_prop(m, e, name);
    rgb[0] = rgb[1] = rgb[2] = fallback;
    *volume = NULL;
    if (!p)
        return true;
    if (strcmp(p->name, "volume") != 0)
        return mi_spectrum_rgb(m, p, rgb);
    const char *type = xml_attribute(p, "type");
    if (type && strcmp(type, "constvolume") == 0) {
        const XmlElement *value = mi_prop(m, p, "value");
        return !value || mi_spectrum_rgb(m, value, rgb);
    }
    *volume = p;
    return true;
}

/* The .vol file's bounding box, its header checked as the reader checks it (io/volume_vol.c). */
static bool vol_bbox(Mitsuba *m, const XmlElement *e, const char *path, double box[6])
{
    Error inner = {0};
    return volume_vol_box(path, box, &inner) || mi_fail(m, e, "%s", inner.message);
}

/* A gridvolume's file and the transform that puts pt's grid (on the header's box) where Mitsuba
 * puts it. */
static bool grid_volume(Mitsuba *m, const XmlElement *v, cJSON *medium)
{
    const char *type = xml_attribute(v, "type");
    if (!type || strcmp(type, "gridvolume"))
        return mi_fail(m, v, "volume type \"%.40s\": pt reads gridvolume (.vol) grids",
                       type ? type : "");
    char file[1024], path[2048];
    Affine to_world, placed;
    bool use_bbox;
    if (!mi_file(m, v, mi_string(m, v, "filename", NULL), file, sizeof file) ||
        !mi_transform(m, v, "to_world", &to_world) ||
        !mi_bool(m, v, "use_grid_bbox", false, &use_bbox))
        return false;
    placed = to_world;
    if (!use_bbox) {
        const char *slash = file[0] == '/' ? NULL : strrchr(m->path, '/');
        double box[6];
        snprintf(path, sizeof path, "%.*s%s", slash ? (int)(slash - m->path) + 1 : 0, m->path, file);
        if (!vol_bbox(m, v, path, box))
            return false;
        Affine unit = {{{1.0 / (box[3] - box[0]), 0, 0, -box[0] / (box[3] - box[0])},
                        {0, 1.0 / (box[4] - box[1]), 0, -box[1] / (box[4] - box[1])},
                        {0, 0, 1.0 / (box[5] - box[2]), -box[2] / (box[5] - box[2])}}};
        placed = affine_mul(&to_world, &unit);
    }
    const char *filter = mi_string(m, v, "filter_type", "trilinear");
    if (filter && strcmp(filter, "trilinear"))
        mi_warn_once(m, v, "filter_type", "filter_type \"%.40s\": pt's grids are trilinear", filter);
    mi_prop(m, v, "raw");
    mi_warn_unused(m, v);
    cJSON_AddStringToObject(medium, "file", file);
    if (!affine_is_identity(&placed))
        cJSON_AddItemToObject(medium, "transform", mi_matrix_transform(&placed));
    return true;
}

/* The pt medium of a <medium> element, not yet in the scene. */
static bool build_medium(Mitsuba *m, const XmlElement *e, cJSON *medium)
{
    const char *type = xml_attribute(e, "type");
    if (!type || (strcmp(type, "homogeneous") && strcmp(type, "heterogeneous")))
        return mi_fail(m, e, "medium type \"%.40s\": pt reads homogeneous and heterogeneous",
                       type ? type : "");
    double sigma_t[3], albedo[3], scale, g;
    const XmlElement *grid, *albedo_grid;
    if (!constant(m, e, "sigma_t", 1.0, sigma_t, &grid) ||
        !constant(m, e, "albedo", 0.75, albedo, &albedo_grid) ||
        !mi_float(m, e, "scale", 1.0, &scale) || !phase_g(m, e, &g))
        return false;
    if (albedo_grid) {
        mi_warn_once(m, albedo_grid, "albedo-grid", "a grid albedo: pt's media take a constant "
                                                    "one (0.75 instead)");
        albedo[0] = albedo[1] = albedo[2] = 0.75;
    }
    for (int c = 0; c < 3; c++)
        if (!(albedo[c] >= 0.0 && albedo[c] <= 1.0))
            return mi_fail(m, e, "albedo %g is outside [0, 1]", albedo[c]);
    mi_prop(m, e, "sample_emitted");
    for (int i = 0; i < e->num_children; i++) /* mi_warn_unused leaves nested plugins alone */
        if (strcmp(e->children[i]->name, "volume") == 0 && !e->children[i]->used)
            mi_warn_once(m, e->children[i], "medium-volume", "volume \"%.40s\" ignored (pt's media "
                         "take sigma_t and albedo)", xml_attribute(e->children[i], "name")
                             ? xml_attribute(e->children[i], "name") : "");
    cJSON_AddNumberToObject(medium, "g", g);
    if (grid) {
        cJSON_AddStringToObject(medium, "type", "grid");
        cJSON_AddNumberToObject(medium, "density_scale", scale);
        cJSON_AddItemToObject(medium, "albedo", mi_rgb_json(albedo));
        return grid_volume(m, grid, medium);
    }
    /* Mitsuba 0.6's homogeneous took sigma_a and sigma_s; Mitsuba 3 sigma_t and albedo. */
    const XmlElement *a = mi_prop(m, e, "sigma_a"), *s = mi_prop(m, e, "sigma_s");
    double sigma_a[3] = {0, 0, 0}, sigma_s[3] = {0, 0, 0};
    if (a || s) {
        if ((a && !mi_spectrum_rgb(m, a, sigma_a)) || (s && !mi_spectrum_rgb(m, s, sigma_s)))
            return false;
    } else {
        for (int c = 0; c < 3; c++) {
            sigma_s[c] = albedo[c] * sigma_t[c];
            sigma_a[c] = (1.0 - albedo[c]) * sigma_t[c];
        }
    }
    cJSON_AddStringToObject(medium, "type", "homogeneous");
    cJSON_AddItemToObject(medium, "sigma_a", mi_rgb_json(sigma_a));
    cJSON_AddItemToObject(medium, "sigma_s", mi_rgb_json(sigma_s));
    cJSON_AddNumberToObject(medium, "scale", scale);
    return true;
}

bool mi_medium(Mitsuba *m, const XmlElement *e, char out[SCENE_NAME_LIMIT])
{
    bool done;
    if (!mi_follow(m, e, "medium", mi_medium, out, &done) || done)
        return done;
    cJSON *root = m->out->root, *media = cJSON_GetObjectItemCaseSensitive(root, "media");
    if (!media && !(media = cJSON_AddObjectToObject(root, "media")))
        return mi_fail(m, e, "out of memory");
    cJSON *medium = cJSON_CreateObject();
    if (!medium)
        return mi_fail(m, e, "out of memory");
    if (!build_medium(m, e, medium)) {
        cJSON_Delete(medium);
        return false;
    }
    mi_warn_unused(m, e);
    mi_new_name(m, e, "medium", out);
    cJSON_AddItemToObject(media, out, medium);
    return mi_remember(m, e, out);
}

bool mi_is_medium(const Mitsuba *m, const XmlElement *c)
{
    if (strcmp(c->name, "medium") == 0)
        return true;
    if (strcmp(c->name, "ref") || !xml_attribute(c, "id"))
        return false;
    const char *side = xml_attribute(c, "name"); /* a shape's: mi_medium refuses a non-medium */
    if (side && (strcmp(side, "interior") == 0 || strcmp(side, "exterior") == 0))
        return true;
    for (int i = 0; i < m->num_ids; i++)
        if (strcmp(xml_attribute(m->ids[i].element, "id"), xml_attribute(c, "id")) == 0)
            return strcmp(m->ids[i].element->name, "medium") == 0;
    return false;
}

bool mi_shape_media(Mitsuba *m, const XmlElement *shape, cJSON *object)
{
    for (int i = 0; i < shape->num_children; i++) {
        const XmlElement *c = shape->children[i];
        if (!mi_is_medium(m, c))
            continue;
        const char *side = xml_attribute(c, "name");
        if (!side || (strcmp(side, "interior") && strcmp(side, "exterior"))) {
            mi_warn_once(m, c, "shape-medium", "a shape's medium needs name=\"interior\" or "
                                               "\"exterior\": ignored");
            continue;
        }
        char name[SCENE_NAME_LIMIT];
        if (!mi_medium(m, c, name))
            return false;
        cJSON_DeleteItemFromObjectCaseSensitive(object, side);
        cJSON_AddStringToObject(object, side, name);
    }
    return true;
}

bool mi_sensor_medium(Mitsuba *m, const XmlElement *sensor, cJSON *camera)
{
    for (int i = 0; i < sensor->num_children; i++) {
        const XmlElement *c = sensor->children[i];
        char name[SCENE_NAME_LIMIT];
        if (!mi_is_medium(m, c))
            continue;
        if (!mi_medium(m, c, name))
            return false;
        cJSON_DeleteItemFromObjectCaseSensitive(camera, "medium");
        cJSON_AddStringToObject(camera, "medium", name);
    }
    return true;
}
