// SPDX-License-Identifier: MIT
/* import_pbrt_lights.c: pbrt-v4 lights and the camera as pt's JSON.
 * - AreaLightSource "diffuse": L x scale becomes the emission of the shapes that follow (their
 *   material's variant, import_pbrt_materials.c); "power" divides by pi x area (x 2 when
 *   twosided) as pbrt-v4 does; "twosided" adds the shape facing the other way (pt's emitters are
 *   one-sided).
 * - point (I, from), spot (from, to, coneangle, conedelta: pt's cone_angle = coneangle, falloff_angle
 *   = coneangle - conedelta; pbrt's falloff is a smoothstep in cos, pt's linear in angle, so the
 *   rim differs slightly), distant (L x scale is the irradiance, along to - from); "power" as
 *   pbrt-v4 (4 pi for a point, 2 pi (1 - (cos_start + cos_end) / 2) for a spot).
 * - infinite: L -> background; filename -> a converted environment (import_pbrt_environment.c).
 * - Camera "perspective": pbrt's fov spans the shorter image axis; pt's fov_y the vertical one.
 *   lensradius r -> aperture 2 r (a diameter); focaldistance -> focus_distance. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "scene/import_pbrt_internal.h"

#define PI_D 3.14159265358979323846

static cJSON *vec_json(const double v[3]) { return cJSON_CreateDoubleArray(v, 3); }

/* A pbrt-world point / vector under the light's ctm, in pt's world. */
static void to_pt(const PbrtImport *imp, const float in[3], bool point, double out[3])
{
    Affine m = affine_mul(&imp->pt_from_pbrt, &imp->state.ctm);
    const double v[3] = {in[0], in[1], in[2]};
    if (point)
        affine_point(&m, v, out);
    else
        affine_vector(&m, v, out);
}

static bool light_colour(PbrtImport *imp, PbrtParams *p, const char *name, double scale, double out[3])
{
    float c[3] = {1.0f, 1.0f, 1.0f}, s;
    PbrtParam *q = pbrt_param(p, name);
    if ((q && !pbrt_spectrum_rgb(imp, q, "illuminant", c)) || !pbrt_float(imp, p, "scale", 1.0f, &s))
        return false;
    for (int k = 0; k < 3; k++)
        out[k] = c[k] * s * scale;
    return true;
}

bool pbrt_area_light(PbrtImport *imp, const char *type, PbrtParams *p)
{
    if (strcmp(type, "diffuse") != 0) {
        pbrt_warn_once(imp, "area type", "AreaLightSource \"%s\": not imported", type);
        return true;
    }
    double l[3];
    float power;
    bool twosided;
    if (!light_colour(imp, p, "L", 1.0, l) || !pbrt_float(imp, p, "power", -1.0f, &power) ||
        !pbrt_bool(imp, p, "twosided", false, &twosided))
        return false;
    if (pbrt_param(p, "filename"))
        pbrt_warn_once(imp, "area image", "AreaLightSource: an image \"filename\" is not imported (L used)");
    imp->state.area_light = true;
    for (int k = 0; k < 3; k++)
        imp->state.area_radiance[k] = (float)l[k];
    imp->state.area_power = power;
    imp->state.area_twosided = twosided;
    return true;
}

static bool spot(PbrtImport *imp, PbrtParams *p, cJSON *light)
{
    float cone, delta, power, from[3], to[3];
    if (!pbrt_float(imp, p, "coneangle", 30.0f, &cone) || !pbrt_float(imp, p, "conedelta", 5.0f, &delta) ||
        !pbrt_float(imp, p, "power", -1.0f, &power) ||
        !pbrt_vec3(imp, p, "from", (float[]){0, 0, 0}, from) || !pbrt_vec3(imp, p, "to", (float[]){0, 0, 1}, to))
        return false;
    if (!(cone > 0.0f && cone <= 180.0f) || delta < 0.0f)
        return pbrt_fail(imp, imp->line, "LightSource \"spot\": coneangle %g / conedelta %g out of range", cone, delta);
    double start = fmax(cone - delta, 0.0), k_e = 1.0;
    if (power > 0.0f) {
        double cs = cos(start * PI_D / 180.0), ce = cos(cone * PI_D / 180.0);
        k_e = power / (2.0 * PI_D * ((1.0 - cs) + (cs - ce) / 2.0));
    }
    double pos[3], target[3], intensity[3];
    to_pt(imp, from, true, pos);
    to_pt(imp, to, true, target);
    const double dir[3] = {target[0] - pos[0], target[1] - pos[1], target[2] - pos[2]};
    if (!light_colour(imp, p, "I", k_e, intensity))
        return false;
    cJSON_AddStringToObject(light, "type", "spot");
    cJSON_AddItemToObject(light, "position", vec_json(pos));
    cJSON_AddItemToObject(light, "direction", vec_json(dir));
    cJSON_AddItemToObject(light, "intensity", vec_json(intensity));
    cJSON_AddNumberToObject(light, "cone_angle", cone);
    cJSON_AddNumberToObject(light, "falloff_angle", start);
    return true;
}

bool pbrt_light(PbrtImport *imp, const char *type, PbrtParams *p)
{
    cJSON *light = cJSON_CreateObject();
    bool ok = true, add = true;
    if (strcmp(type, "point") == 0) {
        float from[3], power;
        double pos[3], intensity[3];
        ok = pbrt_vec3(imp, p, "from", (float[]){0, 0, 0}, from) && pbrt_float(imp, p, "power", -1.0f, &power) &&
             light_colour(imp, p, "I", power > 0.0f ? power / (4.0 * PI_D) : 1.0, intensity);
        to_pt(imp, from, true, pos);
        cJSON_AddStringToObject(light, "type", "point");
        cJSON_AddItemToObject(light, "position", vec_json(pos));
        cJSON_AddItemToObject(light, "intensity", vec_json(intensity));
    } else if (strcmp(type, "spot") == 0) {
        ok = spot(imp, p, light);
    } else if (strcmp(type, "distant") == 0) {
        float from[3], to[3];
        double a[3], b[3], irradiance[3];
        ok = pbrt_vec3(imp, p, "from", (float[]){0, 0, 0}, from) && pbrt_vec3(imp, p, "to", (float[]){0, 0, 1}, to) &&
             light_colour(imp, p, "L", 1.0, irradiance);
        if (pbrt_param(p, "illuminance"))
            pbrt_warn_once(imp, "illuminance", "LightSource \"distant\": \"illuminance\" is not imported (L x scale used)");
        to_pt(imp, from, true, a);
        to_pt(imp, to, true, b);
        const double dir[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
        if (ok && !(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2] > 0.0))
            ok = pbrt_fail(imp, imp->line, "LightSource \"distant\": \"from\" and \"to\" coincide");
        cJSON_AddStringToObject(light, "type", "directional");
        cJSON_AddItemToObject(light, "direction", vec_json(dir));
        cJSON_AddItemToObject(light, "irradiance", vec_json(irradiance));
    } else if (strcmp(type, "infinite") == 0) {
        add = false;
        ok = pbrt_infinite_light(imp, p);
    } else {
        add = false;
        char key[96];
        snprintf(key, sizeof key, "light %s", type);
        pbrt_warn_once(imp, key, "LightSource \"%s\": not imported", type);
        for (int i = 0; i < p->count; i++)
            p->items[i].used = true;
    }
    if (ok && add)
        cJSON_AddItemToArray(imp->lights, light);
    else
        cJSON_Delete(light);
    return ok;
}

bool pbrt_camera_json(PbrtImport *imp, cJSON *root)
{
    PbrtParams *p = &imp->camera_params;
    float fov, lens, focus;
    if (!pbrt_float(imp, p, "fov", 90.0f, &fov) || !pbrt_float(imp, p, "lensradius", 0.0f, &lens) ||
        !pbrt_float(imp, p, "focaldistance", 1e6f, &focus))
        return false;
    if (!(fov > 0.0f && fov < 180.0f) || lens < 0.0f || !(focus > 0.0f))
        return pbrt_fail(imp, p->line, "Camera: fov %g / lensradius %g / focaldistance %g out of range",
                         fov, lens, focus);
    int w = cJSON_GetObjectItemCaseSensitive(imp->film, "width")->valueint;
    int h = cJSON_GetObjectItemCaseSensitive(imp->film, "height")->valueint;
    /* fov spans the shorter axis: the vertical one unless the film is portrait. */
    double half = fov * PI_D / 360.0;
    double fov_y = w >= h ? fov : 360.0 / PI_D * atan(tan(half) * h / w);
    Affine world_from_camera;
    if (!affine_invert(&imp->camera_from_world, &world_from_camera))
        return pbrt_fail(imp, p->line, "Camera: singular camera transform");
    Affine m = affine_mul(&imp->pt_from_pbrt, &world_from_camera);
    double eye[3], target[3], up[3];
    affine_point(&m, (double[]){0, 0, 0}, eye);
    affine_point(&m, (double[]){0, 0, 1}, target);
    affine_vector(&m, (double[]){0, 1, 0}, up);
    cJSON *camera = cJSON_AddObjectToObject(root, "camera");
    cJSON_AddItemToObject(camera, "eye", vec_json(eye));
    cJSON_AddItemToObject(camera, "target", vec_json(target));
    cJSON_AddItemToObject(camera, "up", vec_json(up));
    cJSON_AddNumberToObject(camera, "fov_y", fov_y);
    if (lens > 0.0f) {
        cJSON_AddNumberToObject(camera, "aperture", 2.0 * lens);
        cJSON_AddNumberToObject(camera, "focus_distance", focus);
    }
    pbrt_warn_unused(imp, "Camera", "perspective", p);
    return true;
}
