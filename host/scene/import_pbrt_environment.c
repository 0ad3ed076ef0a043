// SPDX-License-Identifier: MIT
/* import_pbrt_environment.c: pbrt-v4's "infinite" light. A constant L x scale becomes pt's
 * "background". An image ("filename") is, in pbrt-v4, an equal-area octahedral square map (Clarberg
 * 2008) seen in the light's own space; pt's environment is a lat-long map in world space
 * (DESIGN.md "Environment"). So the map is resampled once into a lat-long EXR in pt's cache
 * ($XDG_CACHE_HOME/pt/pbrt-env/, else ~/.cache/pt/pbrt-env/), each texel looked up in the
 * direction pbrt would use: pt world -> pbrt world (pt_from_pbrt is its own inverse) -> light
 * space (the light's transform), then pbrt's equal-area square. Orientation is therefore exact
 * whatever the light's rotation; the resampling is bilinear at twice the source's width. The
 * file's name hashes the source path, its size and time, and the transform, so a changed map or
 * rotation converts again. Only EXR sources are read; others are left out with a warning. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "io/image_io.h"
#include "scene/import_pbrt_internal.h"

#define PI_D 3.14159265358979323846

/* pbrt-v4's EqualAreaSphereToSquare with the exact arctangent: unit d -> [0, 1]^2. */
static void equal_area_square(const double d[3], double *u_out, double *v_out)
{
    double x = fabs(d[0]), y = fabs(d[1]), z = fabs(d[2]);
    double r = sqrt(fmax(0.0, 1.0 - z));
    double a = fmax(x, y), b = fmin(x, y);
    double phi = a == 0.0 ? 0.0 : atan(b / a) * 2.0 / PI_D;
    if (x < y)
        phi = 1.0 - phi;
    double v = phi * r, u = r - v;
    if (d[2] < 0.0) {
        double t = u;
        u = 1.0 - v;
        v = 1.0 - t;
    }
    u = copysign(u, d[0]);
    v = copysign(v, d[1]);
    *u_out = 0.5 * (u + 1.0);
    *v_out = 0.5 * (v + 1.0);
}

static void bilinear(const float *rgb, int n, double u, double v, float out[3])
{
    double x = u * n - 0.5, y = v * n - 0.5;
    int x0 = (int)floor(x), y0 = (int)floor(y);
    double fx = x - x0, fy = y - y0;
    for (int k = 0; k < 3; k++)
        out[k] = 0.0f;
    for (int j = 0; j < 2; j++)
        for (int i = 0; i < 2; i++) {
            int xi = x0 + i < 0 ? 0 : x0 + i >= n ? n - 1 : x0 + i;
            int yj = y0 + j < 0 ? 0 : y0 + j >= n ? n - 1 : y0 + j;
            double w = (i ? fx : 1.0 - fx) * (j ? fy : 1.0 - fy);
            for (int k = 0; k < 3; k++)
                out[k] += (float)(w * rgb[3 * ((size_t)yj * (size_t)n + (size_t)xi) + k]);
        }
}

/* The lat-long map, width 2n, height n, in pt's convention. */
static float *to_lat_long(const float *square, int n, const Affine *light_from_pt)
{
    int w = 2 * n, h = n;
    float *out = malloc((size_t)w * (size_t)h * 3 * sizeof *out);
    if (!out)
        return NULL;
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++) {
            double theta = (j + 0.5) / h * PI_D, phi = ((i + 0.5) / w - 0.5) * 2.0 * PI_D;
            /* u = 0.5 + atan2(d.x, -d.z) / 2 pi, v = acos(d.y) / pi */
            const double d_pt[3] = {sin(theta) * sin(phi), cos(theta), -sin(theta) * cos(phi)};
            double d[3], u, v;
            affine_vector(light_from_pt, d_pt, d);
            double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            for (int k = 0; k < 3; k++)
                d[k] /= len;
            equal_area_square(d, &u, &v);
            bilinear(square, n, u, v, &out[3 * ((size_t)j * (size_t)w + (size_t)i)]);
        }
    return out;
}

/* The converted map's path in the cache, or false when there is no cache folder. */
static bool cache_path(const char *source, const Affine *m, char out[1024])
{
    const char *xdg = getenv("XDG_CACHE_HOME"), *home = getenv("HOME");
    char dir[900];
    if (xdg && *xdg)
        snprintf(dir, sizeof dir, "%s/pt/pbrt-env", xdg);
    else if (home && *home)
        snprintf(dir, sizeof dir, "%s/.cache/pt/pbrt-env", home);
    else
        return false;
    struct stat st;
    if (stat(source, &st) != 0 || !fs_make_dirs(dir))
        return false;
    /* FNV-1a over the conversion's version, the source's identity and the transform: a change to
     * any of them converts again. */
    uint64_t hash = 1469598103934665603ull;
    const unsigned char *bytes = (const unsigned char *)"pbrt-env v1";
    for (size_t i = 0; bytes[i]; i++)
        hash = (hash ^ bytes[i]) * 1099511628211ull;
    bytes = (const unsigned char *)source;
    for (size_t i = 0; bytes[i]; i++)
        hash = (hash ^ bytes[i]) * 1099511628211ull;
    const int64_t stamp[2] = {(int64_t)st.st_size, (int64_t)st.st_mtime};
    bytes = (const unsigned char *)stamp;
    for (size_t i = 0; i < sizeof stamp; i++)
        hash = (hash ^ bytes[i]) * 1099511628211ull;
    bytes = (const unsigned char *)m->m;
    for (size_t i = 0; i < sizeof m->m; i++)
        hash = (hash ^ bytes[i]) * 1099511628211ull;
    snprintf(out, 1024, "%s/%016llx.exr", dir, (unsigned long long)hash);
    return true;
}

/* The lat-long conversion of the equal-area map `file` (relative to the main file); "" in out
 * when it is left out (warned). False: err set. */
static bool convert_map(PbrtImport *imp, const char *file, char out[1024])
{
    out[0] = '\0';
    char source[1024];
    Error e = {0};
    if (!fs_resolve_inside(imp->path, file, "\"filename\"", source, sizeof source, &e))
        return pbrt_check_path(imp, file, "LightSource \"infinite\" \"filename\"", imp->line);
    Affine pt_from_light = affine_mul(&imp->pt_from_pbrt, &imp->state.ctm), light_from_pt;
    pt_from_light.m[0][3] = pt_from_light.m[1][3] = pt_from_light.m[2][3] = 0.0;
    if (!affine_invert(&pt_from_light, &light_from_pt))
        return pbrt_fail(imp, imp->line, "LightSource \"infinite\": singular transform");
    if (!fs_has_suffix(file, ".exr")) {
        pbrt_warn_once(imp, "env format", "LightSource \"infinite\": \"%s\": only EXR maps are "
                       "converted; the environment is left out", file);
        return true;
    }
    char cached[1024];
    if (!cache_path(source, &pt_from_light, cached)) {
        pbrt_warn_once(imp, "env cache", "LightSource \"infinite\": no cache folder for the converted "
                       "map (set XDG_CACHE_HOME or HOME); the environment is left out");
        return true;
    }
    if (!fs_exists(cached)) {
        float *square;
        int w, h;
        if (!image_read_exr(source, &square, &w, &h, &e)) {
            error_set(imp->err, e.code, imp->file, imp->line, "%s:%d: LightSource \"infinite\": %.900s",
                      imp->file, imp->line, e.message);
            return false;
        }
        if (w != h) {
            free(square);
            return pbrt_fail(imp, imp->line, "LightSource \"infinite\": \"%s\" is %d x %d; pbrt-v4's "
                             "maps are square (equal-area octahedral)", file, w, h);
        }
        float *lat_long = to_lat_long(square, w, &light_from_pt);
        free(square);
        if (!lat_long)
            return pbrt_fail(imp, imp->line, "LightSource \"infinite\": out of memory");
        bool ok = image_write_exr(cached, lat_long, 2 * w, w, &e);
        free(lat_long);
        if (!ok) {
            pbrt_warn_once(imp, "env write", "LightSource \"infinite\": the converted map could not "
                           "be written (%s); the environment is left out", e.message);
            return true;
        }
    }
    snprintf(out, 1024, "%s", cached);
    return true;
}

bool pbrt_infinite_light(PbrtImport *imp, PbrtParams *p)
{
    bool ok = true;
    const char *file = pbrt_string(imp, p, "filename", &ok);
    float scale;
    if (!ok || !pbrt_float(imp, p, "scale", 1.0f, &scale))
        return false;
    if (pbrt_param(p, "portal"))
        pbrt_warn_once(imp, "portal", "LightSource \"infinite\": \"portal\" is ignored");
    if (pbrt_param(p, "illuminance"))
        pbrt_warn_once(imp, "illuminance", "LightSource \"infinite\": \"illuminance\" is not imported (scale used)");
    cJSON *root = imp->out->root;
    if (file) {
        char map[1024];
        if (!convert_map(imp, file, map))
            return false;
        if (!map[0])
            return true;
        cJSON_DeleteItemFromObject(root, "environment");
        cJSON *env = cJSON_AddObjectToObject(root, "environment");
        cJSON_AddStringToObject(env, "file", map); /* absolute: in pt's cache */
        cJSON_AddNumberToObject(env, "scale", scale);
        return true;
    }
    float l[3] = {1.0f, 1.0f, 1.0f};
    PbrtParam *q = pbrt_param(p, "L");
    if (q && !pbrt_spectrum_rgb(imp, q, "illuminant", l))
        return false;
    cJSON_DeleteItemFromObject(root, "background");
    cJSON_AddItemToObject(root, "background",
                          cJSON_CreateDoubleArray((double[]){l[0] * scale, l[1] * scale, l[2] * scale}, 3));
    return true;
}
