// SPDX-License-Identifier: MIT
/* mitsuba_shapes.c: Mitsuba shapes as pt objects (obj and ply files by name, the analytic shapes
 * as in-memory meshes of io/mesh_shapes.h that every object using them shares) and emitters as
 * pt's emission, lights, environment and background. */
#include "scene/mitsuba_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/mesh_shapes.h"
#include "io/obj_loader.h"
#include "io/ply_reader.h"

#define PI 3.14159265358979323846

/* Mitsuba puts v = 0 on an image's top row, pt on its bottom row: the uvs of Mitsuba's own shapes
 * are flipped so that a bitmap lands as Mitsuba shows it, and those of files whose v Mitsuba
 * keeps (flip_tex_coords false: a PLY's default; an OBJ's is true, which flips v as pt reads it). */
static void flip_v(Mesh *mesh)
{
    for (size_t i = 0; i < mesh->num_texcoords; i++)
        mesh->texcoords[2 * i + 1] = 1.0f - mesh->texcoords[2 * i + 1];
}

/* flip_normals: the other side becomes the front (winding and normals reversed); face_normals:
 * the file's normals dropped (flat shading). */
static void reshape(Mesh *mesh, bool flip, bool flat)
{
    for (size_t t = 0; flip && t < mesh->num_triangles; t++) {
        int32_t *c = mesh->corners + 9 * t, swap[3];
        memcpy(swap, c + 3, sizeof swap);
        memcpy(c + 3, c + 6, sizeof swap);
        memcpy(c + 6, swap, sizeof swap);
    }
    for (size_t i = 0; flip && i < 3 * mesh->num_normals; i++)
        mesh->normals[i] = -mesh->normals[i];
    if (flat) {
        for (size_t t = 0; t < 3 * mesh->num_triangles; t++)
            mesh->corners[3 * t + 2] = -1;
        free(mesh->normals);
        mesh->normals = NULL;
        mesh->num_normals = 0;
    }
}

/* The mesh called name, made once: an analytic shape (type) or a file (path, loaded). */
static bool shared_mesh(Mitsuba *m, const XmlElement *e, const char *name, const char *type,
                        const char *path, bool flip, bool flat, bool flip_uv)
{
    if (imported_scene_find_mesh(m->out, name) >= 0)
        return true;
    Mesh mesh = {0};
    static const float origin[3] = {0.0f, 0.0f, 0.0f};
    bool ok;
    Error inner = {0};
    if (path)
        ok = strcmp(type, "obj") == 0 ? obj_load(path, &mesh, &inner) : ply_load(path, &mesh, &inner);
    else if (strcmp(type, "sphere") == 0)
        ok = mesh_sphere(&mesh, origin, 1.0f, MESH_SPHERE_SEGMENTS);
    else if (strcmp(type, "disk") == 0)
        ok = mesh_disk(&mesh, MESH_SPHERE_SEGMENTS);
    else if (strcmp(type, "rectangle") == 0)
        ok = mesh_rectangle(&mesh);
    else
        ok = mesh_cube(&mesh);
    if (!ok) {
        mesh_free(&mesh);
        if (path) {
            *m->err = inner;
            return false;
        }
        return mi_fail(m, e, "out of memory");
    }
    if (flip_uv)
        flip_v(&mesh);
    reshape(&mesh, flip, flat);
    if (!imported_scene_add_mesh(m->out, name, &mesh, &inner))
        return mi_fail(m, e, "%s", inner.message);
    return true;
}

/* The shape's material: its bsdf (default: diffuse 0.5, Mitsuba's), with the emission of an
 * area emitter on it (a material of its own). */
static bool shape_material(Mitsuba *m, const XmlElement *e, char out[SCENE_NAME_LIMIT])
{
    const XmlElement *bsdf = NULL, *emitter = NULL;
    for (int i = 0; i < e->num_children; i++) {
        const XmlElement *c = e->children[i];
        if (!bsdf && (strcmp(c->name, "bsdf") == 0 || strcmp(c->name, "ref") == 0) && !mi_is_medium(m, c))
            bsdf = c;
        else if (strcmp(c->name, "emitter") == 0)
            emitter = c;
    }
    if (bsdf) {
        ((XmlElement *)bsdf)->used = true;
        if (!mi_bsdf(m, bsdf, out))
            return false;
    } else if (!cJSON_GetObjectItemCaseSensitive(m->materials, "mitsuba_default")) {
        snprintf(out, SCENE_NAME_LIMIT, "mitsuba_default");
        cJSON *d = cJSON_AddObjectToObject(m->materials, out);
        cJSON_AddStringToObject(d, "type", "diffuse");
        cJSON_AddNumberToObject(d, "albedo", 0.5);
    } else {
        snprintf(out, SCENE_NAME_LIMIT, "mitsuba_default");
    }
    if (!emitter)
        return true;
    const MitsubaNamed *lit = mi_find_mapped(m, emitter); /* a shapegroup's shape, instanced again */
    if (lit) {
        snprintf(out, SCENE_NAME_LIMIT, "%s", lit->name);
        return true;
    }
    const char *type = xml_attribute(emitter, "type");
    if (!type || strcmp(type, "area")) {
        mi_warn_once(m, emitter, "shape-emitter", "only area emitters attach to shapes: ignored");
        return true;
    }
    cJSON *radiance;
    if (!mi_colour(m, emitter, "radiance", 1.0, &radiance))
        return false;
    mi_warn_unused(m, emitter);
    cJSON *lamp = cJSON_Duplicate(cJSON_GetObjectItemCaseSensitive(m->materials, out), true);
    if (!lamp) {
        cJSON_Delete(radiance);
        return mi_fail(m, e, "out of memory");
    }
    cJSON_DeleteItemFromObjectCaseSensitive(lamp, "emission");
    const cJSON *lamp_type = cJSON_GetObjectItemCaseSensitive(lamp, "type");
    if (cJSON_IsString(lamp_type) && strcmp(lamp_type->valuestring, "interface") == 0) {
        /* pt's interface has no parameters: an emitting null bsdf becomes a black emitter. */
        mi_warn_once(m, emitter, "null-emitter", "an area emitter on a null bsdf: pt makes it a "
                                                 "black diffuse emitter (no longer a medium interface)");
        cJSON_Delete(lamp);
        lamp = cJSON_CreateObject();
        cJSON_AddStringToObject(lamp, "type", "diffuse");
        cJSON_AddNumberToObject(lamp, "albedo", 0);
    }
    cJSON_AddItemToObject(lamp, "emission", radiance);
    char base[SCENE_NAME_LIMIT];
    snprintf(base, sizeof base, "%.100s_emitter", out);
    mi_new_name(m, NULL, base, out);
    cJSON_AddItemToObject(m->materials, out, lamp);
    return mi_remember(m, emitter, out);
}

static bool add_object(Mitsuba *m, const XmlElement *e, const char *key, const char *value,
                       const char *material, const Affine *to_world, bool smooth)
{
    cJSON *o = cJSON_CreateObject();
    cJSON_AddItemToArray(m->objects, o);
    if (!mi_shape_media(m, e, o))
        return false;
    cJSON_AddStringToObject(o, key, value);
    cJSON_AddStringToObject(o, "material", material);
    if (smooth)
        cJSON_AddBoolToObject(o, "smooth", true);
    if (!affine_is_identity(to_world))
        cJSON_AddItemToObject(o, "transform", mi_matrix_transform(to_world));
    return true;
}

static bool file_shape(Mitsuba *m, const XmlElement *e, const char *type, const char *material,
                       const Affine *to_world, bool flip, bool flat)
{
    char file[1024];
    bool flip_tex_coords;
    if (!mi_file(m, e, mi_string(m, e, "filename", NULL), file, sizeof file) ||
        !mi_bool(m, e, "flip_tex_coords", strcmp(type, "obj") == 0, &flip_tex_coords))
        return false;
    if (!flip && !flat && flip_tex_coords) /* pt reads the file itself; objects naming one file share it */
        return add_object(m, e, type, file, material, to_world, true);
    /* The file read here to be changed: the tree's paths are relative to the imported file. */
    char path[2048], name[SCENE_NAME_LIMIT];
    const char *slash = file[0] == '/' ? NULL : strrchr(m->path, '/');
    snprintf(path, sizeof path, "%.*s%s", slash ? (int)(slash - m->path) + 1 : 0, m->path, file);
    if (snprintf(name, sizeof name, "%.100s#%s%s%s", file, flip ? "flip" : "", flat ? "flat" : "",
                 flip_tex_coords ? "" : "v") >= (int)sizeof name)
        return mi_fail(m, e, "file name too long");
    return shared_mesh(m, e, name, type, path, flip, flat, !flip_tex_coords) &&
           add_object(m, e, "mesh", name, material, to_world, !flat);
}

bool mi_shape(Mitsuba *m, const XmlElement *e, const Affine *parent)
{
    const char *type = xml_attribute(e, "type");
    if (!type)
        return mi_fail(m, e, "missing type=\"...\"");
    Affine local, to_world;
    if (!mi_transform(m, e, "to_world", &local))
        return false;
    to_world = affine_mul(parent, &local);
    if (strcmp(type, "instance") == 0) {
        const XmlElement *ref = NULL;
        for (int i = 0; i < e->num_children && !ref; i++)
            if (strcmp(e->children[i]->name, "ref") == 0)
                ref = e->children[i];
        if (!ref)
            return mi_fail(m, e, "needs a <ref id=...> to a shapegroup");
        const MitsubaNamed *group = mi_find_id(m, ref);
        if (!group)
            return false;
        if (strcmp(group->element->name, "shape") || !xml_attribute(group->element, "type") ||
            strcmp(xml_attribute(group->element, "type"), "shapegroup"))
            return mi_fail(m, ref, "does not name a shapegroup");
        const char *saved = m->file;
        m->file = group->file;
        bool ok = true;
        for (int i = 0; ok && i < group->element->num_children; i++)
            if (strcmp(group->element->children[i]->name, "shape") == 0)
                ok = mi_shape(m, group->element->children[i], &to_world);
        m->file = saved;
        return ok;
    }
    static const char *const known[] = {"obj", "ply", "rectangle", "disk", "cube", "sphere"};
    size_t k = 0;
    while (k < sizeof known / sizeof known[0] && strcmp(type, known[k]))
        k++;
    if (k == sizeof known / sizeof known[0]) {
        char key[64];
        snprintf(key, sizeof key, "shape.%.40s", type);
        mi_warn_once(m, e, key, "shape type not read by pt: skipped");
        return true;
    }
    bool flip, flat;
    char material[SCENE_NAME_LIMIT];
    if (!mi_bool(m, e, "flip_normals", false, &flip) || !mi_bool(m, e, "face_normals", false, &flat) ||
        !shape_material(m, e, material))
        return false;
    if (k < 2) {
        if (!file_shape(m, e, type, material, &to_world, flip, flat))
            return false;
    } else {
        if (strcmp(type, "sphere") == 0) {
            static const double zero[3] = {0, 0, 0};
            double center[3], radius;
            if (!mi_point(m, e, "center", zero, center) || !mi_float(m, e, "radius", 1.0, &radius))
                return false;
            if (!(radius > 0.0))
                return mi_fail(m, e, "radius %g must be > 0", radius);
            Affine placed = affine_translate(center[0], center[1], center[2]);
            Affine scaled = affine_scale(radius, radius, radius);
            placed = affine_mul(&placed, &scaled);
            to_world = affine_mul(&to_world, &placed);
        }
        char name[64];
        snprintf(name, sizeof name, "%s%s%s", type, flip ? "#flip" : "", flat ? "#flat" : "");
        if (!shared_mesh(m, e, name, type, NULL, flip, flat, true) || !add_object(m, e, "mesh", name, material, &to_world, false))
            return false;
    }
    mi_warn_unused(m, e);
    return true;
}

/* ---- Emitters -------------------------------------------------------------------------------- */

static void add_vec3(cJSON *o, const char *key, const double v[3])
{
    cJSON_AddItemToObject(o, key, cJSON_CreateDoubleArray(v, 3));
}

static bool colour_only(Mitsuba *m, const XmlElement *e, const char *name, double fallback, double rgb[3])
{
    const XmlElement *p = mi_prop(m, e, name);
    rgb[0] = rgb[1] = rgb[2] = fallback;
    if (p && (strcmp(p->name, "texture") == 0 || strcmp(p->name, "ref") == 0)) {
        mi_warn_once(m, p, "emitter-texture", "textured %s: pt takes a colour here; 1 instead", name);
        rgb[0] = rgb[1] = rgb[2] = 1.0;
        return true;
    }
    return !p || mi_spectrum_rgb(m, p, rgb);
}

/* envmap's to_world: a rotation by theta about +y becomes pt's rotation theta - 180 (Mitsuba puts
 * u = 0 looking along -z, pt u = 0.5; tools/mitsuba_materials.py maps it the other way). */
static bool environment(Mitsuba *m, const XmlElement *e, cJSON *root)
{
    char file[1024];
    double scale;
    Affine a;
    if (!mi_file(m, e, mi_string(m, e, "filename", NULL), file, sizeof file) ||
        !mi_float(m, e, "scale", 1.0, &scale) || !mi_transform(m, e, "to_world", &a))
        return false;
    if (m->has_environment) {
        mi_warn_once(m, e, "envmap2", "a second environment: ignored");
        return true;
    }
    m->has_environment = true;
    double theta = atan2(a.m[0][2], a.m[0][0]), c = cos(theta), s = sin(theta);
    double expected[3][3] = {{c, 0, s}, {0, 1, 0}, {-s, 0, c}}, error = 0.0;
    for (int r = 0; r < 3; r++)
        for (int col = 0; col < 3; col++)
            error = fmax(error, fabs(a.m[r][col] - expected[r][col]));
    if (error > 1e-4)
        mi_warn_once(m, e, "envmap-to_world", "to_world is not a rotation about +y: pt keeps its "
                                              "turn about +y (%g degrees) only", theta * 180.0 / PI);
    cJSON *env = cJSON_AddObjectToObject(root, "environment");
    cJSON_AddStringToObject(env, "file", file);
    cJSON_AddNumberToObject(env, "scale", scale);
    double rotation = fmod(theta * 180.0 / PI - 180.0 + 720.0, 360.0);
    cJSON_AddNumberToObject(env, "rotation", rotation);
    mi_warn_unused(m, e);
    return true;
}

static bool light(Mitsuba *m, const XmlElement *e, const char *type)
{
    Affine a;
    double origin[3] = {0, 0, 0}, z[3] = {0, 0, 1}, position[3], direction[3], rgb[3];
    if (!mi_transform(m, e, "to_world", &a))
        return false;
    affine_point(&a, origin, position);
    affine_vector(&a, z, direction);
    cJSON *l = cJSON_CreateObject();
    cJSON_AddItemToArray(m->lights, l);
    cJSON_AddStringToObject(l, "type", type);
    if (strcmp(type, "directional") == 0) {
        if (!mi_point(m, e, "direction", direction, direction) || !colour_only(m, e, "irradiance", 1.0, rgb))
            return false;
        add_vec3(l, "direction", direction);
        add_vec3(l, "irradiance", rgb);
        return true;
    }
    if (!mi_point(m, e, "position", position, position) || !colour_only(m, e, "intensity", 1.0, rgb))
        return false;
    add_vec3(l, "position", position);
    add_vec3(l, "intensity", rgb);
    if (strcmp(type, "spot") == 0) {
        double cutoff, beam;
        if (!mi_float(m, e, "cutoff_angle", 20.0, &cutoff) || !mi_float(m, e, "beam_width", cutoff * 0.75, &beam))
            return false;
        add_vec3(l, "direction", direction);
        cJSON_AddNumberToObject(l, "cone_angle", cutoff);
        cJSON_AddNumberToObject(l, "falloff_angle", fmin(beam, cutoff));
    }
    return true;
}

bool mi_emitter(Mitsuba *m, const XmlElement *e)
{
    const char *type = xml_attribute(e, "type");
    if (!type)
        return mi_fail(m, e, "missing type=\"...\"");
    cJSON *root = m->out->root;
    bool ok = true;
    if (strcmp(type, "point") == 0 || strcmp(type, "spot") == 0)
        ok = light(m, e, type);
    else if (strcmp(type, "directional") == 0)
        ok = light(m, e, "directional");
    else if (strcmp(type, "envmap") == 0)
        return environment(m, e, root);
    else if (strcmp(type, "constant") == 0) {
        double rgb[3];
        if (!colour_only(m, e, "radiance", 1.0, rgb))
            return false;
        cJSON_DeleteItemFromObjectCaseSensitive(root, "background");
        cJSON_AddItemToObject(root, "background", mi_rgb_json(rgb));
    } else {
        char key[64];
        snprintf(key, sizeof key, "emitter.%.40s", type);
        mi_warn_once(m, e, key, "emitter type not read by pt%s: skipped",
                     strcmp(type, "area") == 0 ? " outside a shape" : "");
        return true;
    }
    if (ok)
        mi_warn_unused(m, e);
    return ok;
}
