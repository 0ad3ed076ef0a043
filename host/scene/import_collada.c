// SPDX-License-Identifier: MIT
/* import_collada.c: a COLLADA document as a pt JSON scene plus meshes (scene/import_collada.h). */
#include "scene/import_collada.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/transform.h"
#include "io/collada_reader.h"
#include "io/mesh_shapes.h"
#include "scene/import_json.h"

#define FILM_WIDTH 640
#define PI 3.14159265358979323846
#define AREA_LIGHT_MESH "cgl_area_light"

typedef struct {
    const char *path;
    const ColladaDoc *doc;
    ImportedScene *out;
    Error *err;
    cJSON *materials, *objects, *lights;
    double up[16]; /* the up-axis conversion */
    /* Per geometry, the bindings that have a mesh already: meshes[g][k] is binding k's. */
    int **made_bindings; /* per geometry: made * num_symbols material indices */
    int *made;
    ImportBounds bounds;
    bool has_area_lights;
    bool warned_emitter, warned_attenuation;
} Importer;

/* M (x, y, z, w). */
static void apply(const double m[16], const double p[4], double out[3])
{
    for (int i = 0; i < 3; i++)
        out[i] = m[4 * i] * p[0] + m[4 * i + 1] * p[1] + m[4 * i + 2] * p[2] + m[4 * i + 3] * p[3];
}

static void up_axis_matrix(ColladaUpAxis axis, double m[16])
{
    static const double z_up[16] = {1, 0, 0, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 0, 0, 1};
    static const double x_up[16] = {0, -1, 0, 0, 1, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    static const double y_up[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    memcpy(m, axis == COLLADA_Z_UP ? z_up : axis == COLLADA_X_UP ? x_up : y_up, 16 * sizeof *m);
}

static bool oom(Importer *im)
{
    error_set(im->err, ERR_OUT_OF_MEMORY, im->path, 0, "%s: out of memory", im->path);
    return false;
}

/* ---------------------------------------------------------------- materials */

/* The JSON material replacing the mesh material `m` (NULL: the mesh's MTL-like one stands). */
static cJSON *json_material(const ColladaDoc *doc, const ColladaMaterial *m)
{
    cJSON *j = cJSON_CreateObject();
    if (!j)
        return NULL;
    switch (m->cgl) {
    case CGL_DIFFUSE:
        cJSON_AddStringToObject(j, "type", "diffuse");
        cJSON_AddItemToObject(j, "albedo", import_json_colour(m->reflectance));
        break;
    case CGL_MIRROR:
        cJSON_AddStringToObject(j, "type", "conductor");
        cJSON_AddItemToObject(j, "reflectance", import_json_colour(m->reflectance));
        break;
    case CGL_MICROFACET:
        cJSON_AddStringToObject(j, "type", "conductor");
        cJSON_AddItemToObject(j, "eta", import_json_colour(m->eta));
        cJSON_AddItemToObject(j, "k", import_json_colour(m->k));
        cJSON_AddNumberToObject(j, "roughness", fmin(1.0, sqrt(m->alpha)));
        break;
    case CGL_GLASS:
        cJSON_AddStringToObject(j, "type", "dielectric");
        cJSON_AddNumberToObject(j, "ior", m->ior);
        cJSON_AddNumberToObject(j, "roughness", fmin(1.0, sqrt(m->roughness)));
        cJSON_AddItemToObject(j, "tint", import_json_colour(m->transmittance));
        break;
    case CGL_EMISSION: {
        float black[3] = {0, 0, 0};
        cJSON_AddStringToObject(j, "type", "diffuse");
        cJSON_AddItemToObject(j, "albedo", import_json_colour(black));
        cJSON_AddItemToObject(j, "emission", import_json_colour(m->radiance));
        break;
    }
    case CGL_NONE:
        if (!doc->has_cgl || m->common.map_kd[0]) {
            cJSON_Delete(j);
            return NULL;
        }
        /* CS184 renders a material without a CGL technique as Lambert with its diffuse colour. */
        cJSON_AddStringToObject(j, "type", "diffuse");
        cJSON_AddItemToObject(j, "albedo", import_json_colour(m->common.kd));
        break;
    }
    return j;
}

static bool add_materials(Importer *im)
{
    for (int i = 0; i < im->doc->num_materials; i++) {
        const ColladaMaterial *m = &im->doc->materials[i];
        if (m->cgl == CGL_GLASS && (m->reflectance[0] != 1 || m->reflectance[1] != 1 || m->reflectance[2] != 1))
            warn("%s: material \"%s\": glass reflectance other than 1 dropped (pt's dielectric "
                 "reflects by Fresnel)", im->path, m->id);
        if (cJSON_GetObjectItemCaseSensitive(im->materials, m->id))
            continue;
        cJSON *j = json_material(im->doc, m);
        if (j)
            cJSON_AddItemToObject(im->materials, m->id, j);
    }
    return true;
}

/* ---------------------------------------------------------------- meshes and objects */

static bool copy_floats(float **dst, const float *src, size_t n)
{
    *dst = NULL;
    if (!n)
        return true;
    *dst = malloc(n * sizeof **dst);
    if (!*dst)
        return false;
    memcpy(*dst, src, n * sizeof **dst);
    return true;
}

/* The geometry's mesh with its materials bound by `bindings`. */
static bool bound_mesh(Importer *im, const ColladaGeometry *g, const int *bindings, Mesh *m)
{
    memset(m, 0, sizeof *m);
    int symbols = g->num_symbols > 0 ? g->num_symbols : 1;
    if (g->is_sphere) {
        float centre[3] = {0, 0, 0};
        if (!mesh_sphere(m, centre, g->radius, MESH_SPHERE_SEGMENTS))
            return oom(im);
        for (size_t t = 0; t < m->num_triangles; t++)
            m->material_ids[t] = 0;
    } else {
        const Mesh *s = &g->mesh;
        if (!copy_floats(&m->positions, s->positions, 3 * s->num_positions) ||
            !copy_floats(&m->normals, s->normals, 3 * s->num_normals) ||
            !copy_floats(&m->texcoords, s->texcoords, 2 * s->num_texcoords))
            return mesh_free(m), oom(im);
        m->num_positions = s->num_positions, m->num_normals = s->num_normals;
        m->num_texcoords = s->num_texcoords;
        m->num_triangles = s->num_triangles, m->num_faces = s->num_faces;
        m->corners = malloc((9 * s->num_triangles + 1) * sizeof *m->corners);
        m->material_ids = malloc((s->num_triangles + 1) * sizeof *m->material_ids);
        if (!m->corners || !m->material_ids)
            return mesh_free(m), oom(im);
        memcpy(m->corners, s->corners, 9 * s->num_triangles * sizeof *m->corners);
        for (size_t t = 0; t < s->num_triangles; t++)
            m->material_ids[t] = s->material_ids[t] < 0 ? 0 : s->material_ids[t];
    }
    m->materials = calloc((size_t)symbols, sizeof *m->materials);
    if (!m->materials)
        return mesh_free(m), oom(im);
    m->num_materials = (size_t)symbols;
    for (int k = 0; k < symbols; k++) {
        ObjMaterial *o = &m->materials[k];
        if (bindings[k] >= 0) {
            *o = im->doc->materials[bindings[k]].common;
        } else { /* unbound: COLLADA's default grey, named after the symbol */
            ColladaMaterial grey = {0};
            *o = grey.common;
            o->kd[0] = o->kd[1] = o->kd[2] = 0.8f;
            o->tf[0] = o->tf[1] = o->tf[2] = 1.0f;
            o->ni = o->d = o->bump_scale = 1.0f, o->illum = -1;
            const char *symbol = g->num_symbols ? g->symbols[k] : g->id;
            snprintf(o->name, sizeof o->name, "%.100s#unbound", symbol);
        }
    }
    return true;
}

/* The name of the mesh for geometry g under `bindings`, made the first time. */
static bool mesh_for(Importer *im, int g, const int *bindings, char name[SCENE_NAME_LIMIT])
{
    const ColladaGeometry *geo = &im->doc->geometries[g];
    int symbols = geo->num_symbols > 0 ? geo->num_symbols : 1;
    int k = 0;
    for (; k < im->made[g]; k++)
        if (memcmp(im->made_bindings[g] + k * symbols, bindings, (size_t)symbols * sizeof *bindings) == 0)
            break;
    if (k == 0)
        snprintf(name, SCENE_NAME_LIMIT, "%s", geo->id);
    else
        snprintf(name, SCENE_NAME_LIMIT, "%.100s#%d", geo->id, k);
    if (k < im->made[g])
        return true;
    int *grown = realloc(im->made_bindings[g], (size_t)(k + 1) * (size_t)symbols * sizeof *grown);
    if (!grown)
        return oom(im);
    im->made_bindings[g] = grown;
    memcpy(grown + k * symbols, bindings, (size_t)symbols * sizeof *bindings);
    im->made[g]++;
    Mesh mesh;
    return bound_mesh(im, geo, bindings, &mesh) &&
           imported_scene_add_mesh(im->out, name, &mesh, im->err);
}

static bool is_cgl_emitter(const Importer *im, const ColladaInstance *inst)
{
    const ColladaGeometry *g = &im->doc->geometries[inst->index];
    int symbols = g->num_symbols > 0 ? g->num_symbols : 1;
    for (int k = 0; k < symbols; k++)
        if (inst->bindings[k] >= 0 && im->doc->materials[inst->bindings[k]].cgl == CGL_EMISSION)
            return true;
    return false;
}

static bool add_geometry(Importer *im, const ColladaInstance *inst)
{
    const ColladaGeometry *g = &im->doc->geometries[inst->index];
    if (!g->is_sphere && g->mesh.num_triangles == 0)
        return true;
    if (im->has_area_lights && is_cgl_emitter(im, inst)) {
        if (!im->warned_emitter)
            warn("%s: node \"%s\": an emissive CGL mesh dropped: the scene's CGL area lights are "
                 "its lamps (CS184 shows such meshes only to camera rays)", im->path, inst->node);
        im->warned_emitter = true;
        return true;
    }
    char name[SCENE_NAME_LIMIT];
    if (!mesh_for(im, inst->index, inst->bindings, name))
        return false;
    double world[16];
    rows16_mul(im->up, inst->world, world);
    cJSON *o = cJSON_CreateObject();
    if (!o)
        return oom(im);
    cJSON_AddStringToObject(o, "mesh", name);
    cJSON_AddItemToObject(o, "transform", import_json_matrix_transform(world));
    cJSON_AddItemToArray(im->objects, o);
    import_bounds_add_mesh(&im->bounds, &im->out->meshes[imported_scene_find_mesh(im->out, name)].mesh,
                           world);
    return true;
}

/* ---------------------------------------------------------------- lights */

static bool add_area_light(Importer *im, const ColladaInstance *inst, const ColladaLight *l)
{
    if (imported_scene_find_mesh(im->out, AREA_LIGHT_MESH) < 0) {
        Mesh square;
        if (!mesh_rectangle(&square))
            return oom(im);
        if (!imported_scene_add_mesh(im->out, AREA_LIGHT_MESH, &square, im->err))
            return false;
    }
    char material[SCENE_NAME_LIMIT];
    snprintf(material, sizeof material, "%.100s#area", l->id);
    if (!cJSON_GetObjectItemCaseSensitive(im->materials, material)) {
        float black[3] = {0, 0, 0};
        cJSON *j = cJSON_CreateObject();
        cJSON_AddStringToObject(j, "type", "diffuse");
        cJSON_AddItemToObject(j, "albedo", import_json_colour(black));
        cJSON_AddItemToObject(j, "emission", import_json_colour(l->color));
        cJSON_AddItemToObject(im->materials, material, j);
    }
    /* CS184's AreaLight: the square [-1/2, 1/2]^2 of the node's xy plane, emitting toward -z.
     * mesh_rectangle is [-1, 1]^2 facing +z: halve it and turn it over about x. */
    static const double turn[16] = {0.5, 0, 0, 0, 0, -0.5, 0, 0, 0, 0, -0.5, 0, 0, 0, 0, 1};
    double world[16];
    rows16_mul(im->up, inst->world, world);
    rows16_mul(world, turn, world);
    cJSON *o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, "mesh", AREA_LIGHT_MESH);
    cJSON_AddStringToObject(o, "material", material);
    cJSON_AddItemToObject(o, "transform", import_json_matrix_transform(world));
    cJSON_AddItemToArray(im->objects, o);
    return true;
}

static bool add_light(Importer *im, const ColladaInstance *inst)
{
    const ColladaLight *l = &im->doc->lights[inst->index];
    if (l->type == COLLADA_LIGHT_AREA)
        return add_area_light(im, inst, l);
    if (l->type == COLLADA_LIGHT_AMBIENT) {
        warn("%s: ambient light \"%s\" dropped (pt has no ambient light; use \"background\")",
             im->path, l->id);
        return true;
    }
    if (l->attenuated && !im->warned_attenuation) {
        im->warned_attenuation = true;
        warn("%s: light \"%s\": linear/quadratic attenuation dropped (pt's lights fall off with "
             "the inverse square of the distance)", im->path, l->id);
    }
    double world[16], origin[4] = {0, 0, 0, 1}, ahead[4] = {0, 0, -1, 0}, p[3], d[3];
    rows16_mul(im->up, inst->world, world);
    apply(world, origin, p);
    apply(world, ahead, d);
    cJSON *j = cJSON_CreateObject();
    if (!j)
        return oom(im);
    if (l->type == COLLADA_LIGHT_DIRECTIONAL) {
        cJSON_AddStringToObject(j, "type", "directional");
        cJSON_AddItemToObject(j, "direction", import_json_vec3(d));
        cJSON_AddItemToObject(j, "irradiance", import_json_colour(l->color));
    } else {
        cJSON_AddStringToObject(j, "type", l->type == COLLADA_LIGHT_SPOT ? "spot" : "point");
        cJSON_AddItemToObject(j, "position", import_json_vec3(p));
        cJSON_AddItemToObject(j, "intensity", import_json_colour(l->color));
        if (l->type == COLLADA_LIGHT_SPOT) {
            cJSON_AddItemToObject(j, "direction", import_json_vec3(d));
            cJSON_AddNumberToObject(j, "cone_angle", fmin(180.0, l->falloff_angle / 2.0));
        }
    }
    cJSON_AddItemToArray(im->lights, j);
    return true;
}

/* ---------------------------------------------------------------- camera */

static bool add_camera(Importer *im, cJSON *root)
{
    const ColladaInstance *inst = NULL;
    for (int i = 0; i < im->doc->num_instances && !inst; i++)
        if (im->doc->instances[i].kind == COLLADA_CAMERA)
            inst = &im->doc->instances[i];
    double eye[3], target[3], up[3] = {0, 1, 0};
    double fov_y = 40.0;
    cJSON *camera = cJSON_CreateObject(), *film = NULL;
    if (!camera)
        return oom(im);
    double centre[3], diagonal = import_bounds_centre(&im->bounds, centre);
    if (inst) {
        const ColladaCamera *c = &im->doc->cameras[inst->index];
        double world[16], o[4] = {0, 0, 0, 1}, f[4] = {0, 0, -1, 0}, u[4] = {0, 1, 0, 0}, fwd[3];
        rows16_mul(im->up, inst->world, world);
        apply(world, o, eye);
        apply(world, f, fwd);
        apply(world, u, up);
        double tan_half = 0;
        if (c->yfov > 0)
            tan_half = tan(c->yfov * PI / 360.0);
        else if (c->xfov > 0)
            tan_half = tan(c->xfov * PI / 360.0) / (c->aspect > 0 ? c->aspect : 4.0 / 3.0);
        if (tan_half > 0)
            fov_y = 2.0 * atan(tan_half) * 180.0 / PI;
        double aspect = c->aspect > 0 ? c->aspect : (c->xfov > 0 && c->yfov > 0)
                                                        ? tan(c->xfov * PI / 360.0) / tan(c->yfov * PI / 360.0)
                                                        : 0;
        if (aspect > 0) {
            film = cJSON_CreateObject();
            cJSON_AddNumberToObject(film, "width", FILM_WIDTH);
            cJSON_AddNumberToObject(film, "height", fmax(1.0, round(FILM_WIDTH / aspect)));
        }
        if (im->doc->has_cgl && im->bounds.any) {
            /* CS184 (Application::load): the camera looks at the bounds' centre from 1.5 x
             * their diagonal, along the direction of the point one unit ahead of the file's
             * camera seen from the origin, +y up. */
            double ahead[4] = {0, 0, -1, 1}, dir[3];
            apply(world, ahead, dir);
            double len = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
            if (len > 0) {
                for (int k = 0; k < 3; k++)
                    eye[k] = centre[k] + 1.5 * diagonal * dir[k] / len;
                memcpy(target, centre, sizeof target);
                up[0] = 0, up[1] = 1, up[2] = 0;
            } else {
                for (int k = 0; k < 3; k++)
                    target[k] = eye[k] + fwd[k];
            }
        } else {
            for (int k = 0; k < 3; k++)
                target[k] = eye[k] + fwd[k];
        }
    } else {
        memcpy(target, centre, sizeof target);
        for (int k = 0; k < 3; k++)
            eye[k] = centre[k] + (k == 2 ? 1.5 * diagonal : 0);
    }
    cJSON_AddItemToObject(camera, "eye", import_json_vec3(eye));
    cJSON_AddItemToObject(camera, "target", import_json_vec3(target));
    cJSON_AddItemToObject(camera, "up", import_json_vec3(up));
    cJSON_AddNumberToObject(camera, "fov_y", (float)fov_y);
    cJSON_AddItemToObject(root, "camera", camera);
    if (film)
        cJSON_AddItemToObject(root, "film", film);
    return true;
}

bool import_collada(const char *path, ImportedScene *out, Error *err)
{
    ColladaDoc doc;
    if (!collada_read(path, &doc, err))
        return false;
    Importer im = {.path = path, .doc = &doc, .out = out, .err = err};
    up_axis_matrix(doc.up_axis, im.up);
    out->root = cJSON_CreateObject();
    im.materials = cJSON_CreateObject();
    im.objects = cJSON_CreateArray();
    im.lights = cJSON_CreateArray();
    im.made = calloc((size_t)doc.num_geometries + 1, sizeof *im.made);
    im.made_bindings = calloc((size_t)doc.num_geometries + 1, sizeof *im.made_bindings);
    bool ok = out->root && im.materials && im.objects && im.lights && im.made && im.made_bindings;
    if (!ok)
        oom(&im);
    for (int i = 0; ok && i < doc.num_instances; i++)
        if (doc.instances[i].kind == COLLADA_LIGHT &&
            doc.lights[doc.instances[i].index].type == COLLADA_LIGHT_AREA)
            im.has_area_lights = true;
    ok = ok && add_materials(&im);
    for (int i = 0; ok && i < doc.num_instances; i++)
        if (doc.instances[i].kind == COLLADA_GEOMETRY)
            ok = add_geometry(&im, &doc.instances[i]);
    for (int i = 0; ok && i < doc.num_instances; i++)
        if (doc.instances[i].kind == COLLADA_LIGHT)
            ok = add_light(&im, &doc.instances[i]);
    ok = ok && add_camera(&im, out->root);
    if (ok) {
        cJSON_AddItemToObject(out->root, "materials", im.materials);
        cJSON_AddItemToObject(out->root, "objects", im.objects);
        if (cJSON_GetArraySize(im.lights) > 0)
            cJSON_AddItemToObject(out->root, "lights", im.lights);
        else
            cJSON_Delete(im.lights);
    } else {
        cJSON_Delete(im.materials);
        cJSON_Delete(im.objects);
        cJSON_Delete(im.lights);
    }
    for (int g = 0; g < doc.num_geometries; g++)
        free(im.made_bindings[g]);
    free(im.made_bindings);
    free(im.made);
    collada_free(&doc);
    return ok;
}
