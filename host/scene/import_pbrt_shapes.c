// SPDX-License-Identifier: MIT
/* import_pbrt_shapes.c: pbrt-v4 shapes as pt objects: trianglemesh, bilinearmesh (two triangles a
 * patch), sphere and disk (io/mesh_shapes.h tessellations) become in-memory meshes named by the
 * object's "mesh" key; plymesh becomes a "ply" object. Each object carries its full transform
 * (pt_from_pbrt ctm) as a matrix, so a mesh is stored once in its own space and instancing shares
 * it. Orientation follows pbrt: with normals N a triangle's front faces them (pbrt's FaceForward),
 * and ReverseOrientation flips the front (and N). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/mesh_shapes.h"
#include "scene/import_pbrt_internal.h"

#define PI_D 3.14159265358979323846

/* A float array of `per` numbers an element, copied from a parameter; NULL count 0 when absent. */
static bool copy_floats(PbrtImport *imp, PbrtParams *p, const char *name, int per, float **out,
                        size_t *count)
{
    PbrtParam *q = pbrt_param(p, name);
    *out = NULL;
    *count = 0;
    if (!q)
        return true;
    if (!q->numbers || q->type == PBRT_INTEGER || q->type == PBRT_BOOL || q->type == PBRT_SPECTRUM ||
        q->count % per != 0)
        return pbrt_fail(imp, q->line, "Shape: \"%s\": expected %d numbers per element", name, per);
    *out = malloc((size_t)q->count * sizeof **out);
    if (!*out)
        return pbrt_fail(imp, q->line, "Shape: \"%s\": out of memory", name);
    for (int i = 0; i < q->count; i++) {
        (*out)[i] = (float)q->numbers[i];
        if (!isfinite((*out)[i]))
            return pbrt_fail(imp, q->line, "Shape: \"%s\": value %d is not finite", name, i);
    }
    *count = (size_t)q->count / (size_t)per;
    return true;
}

/* trianglemesh (per_face 3) and bilinearmesh (per_face 4: p00 p10 p01 p11 -> two triangles). */
static bool polygon_mesh(PbrtImport *imp, PbrtParams *p, int per_face, Mesh *m)
{
    const char *type = per_face == 3 ? "trianglemesh" : "bilinearmesh";
    size_t n_uv, n_n;
    if (!copy_floats(imp, p, "P", 3, &m->positions, &m->num_positions) ||
        !copy_floats(imp, p, "N", 3, &m->normals, &n_n) || !copy_floats(imp, p, "uv", 2, &m->texcoords, &n_uv))
        return false;
    if (m->num_positions == 0)
        return pbrt_fail(imp, imp->line, "Shape \"%s\": no \"point3 P\"", type);
    if ((n_n && n_n != m->num_positions) || (n_uv && n_uv != m->num_positions))
        return pbrt_fail(imp, imp->line, "Shape \"%s\": \"N\" / \"uv\" need one value per point "
                         "(%zu points)", type, m->num_positions);
    m->num_normals = n_n;
    m->num_texcoords = n_uv;
    PbrtParam *indices = pbrt_param(p, "indices");
    size_t n_index = indices ? (size_t)indices->count : (size_t)per_face;
    if (indices && indices->type != PBRT_INTEGER)
        return pbrt_fail(imp, indices->line, "Shape \"%s\": \"indices\" must be integer", type);
    if (!indices && m->num_positions != (size_t)per_face)
        return pbrt_fail(imp, imp->line, "Shape \"%s\": no \"integer indices\" (needed unless there "
                         "are exactly %d points)", type, per_face);
    if (n_index % (size_t)per_face != 0)
        return pbrt_fail(imp, indices->line, "Shape \"%s\": %zu indices is not a multiple of %d",
                         type, n_index, per_face);
    size_t faces = n_index / (size_t)per_face;
    m->num_faces = faces;
    m->num_triangles = faces * (size_t)(per_face - 2);
    m->corners = malloc(m->num_triangles * 9 * sizeof *m->corners);
    m->material_ids = malloc(m->num_triangles * sizeof *m->material_ids);
    if (!m->corners || !m->material_ids)
        return pbrt_fail(imp, imp->line, "Shape \"%s\": out of memory", type);
    static const int split[2][2][3] = {{{0, 1, 2}, {0, 1, 2}}, {{0, 1, 3}, {0, 3, 2}}};
    size_t t = 0;
    for (size_t f = 0; f < faces; f++)
        for (int k = 0; k < per_face - 2; k++, t++)
            for (int c = 0; c < 3; c++) {
                size_t at = f * (size_t)per_face + (size_t)split[per_face - 3][k][c];
                double v = indices ? indices->numbers[at] : (double)at;
                if (v < 0 || v >= (double)m->num_positions)
                    return pbrt_fail(imp, indices->line, "Shape \"%s\": index %.0f is out of range "
                                     "[0, %zu)", type, v, m->num_positions);
                int32_t i = (int32_t)v;
                m->material_ids[t] = -1; /* the object's material */
                m->corners[9 * t + 3 * c] = i;
                m->corners[9 * t + 3 * c + 1] = n_uv ? i : -1;
                m->corners[9 * t + 3 * c + 2] = n_n ? i : -1;
            }
    return true;
}

static void swap_corners(Mesh *m, size_t t)
{
    for (int k = 0; k < 3; k++) {
        int32_t x = m->corners[9 * t + 3 + k];
        m->corners[9 * t + 3 + k] = m->corners[9 * t + 6 + k];
        m->corners[9 * t + 6 + k] = x;
    }
}

/* pbrt's orientation: N flipped by ReverseOrientation; a triangle with normals faces them;
 * without normals ReverseOrientation flips the winding. */
static void orient(Mesh *m, bool reverse)
{
    if (reverse)
        for (size_t i = 0; i < 3 * m->num_normals; i++)
            m->normals[i] = -m->normals[i];
    for (size_t t = 0; t < m->num_triangles; t++) {
        const int32_t *c = &m->corners[9 * t];
        bool flip = reverse && m->num_normals == 0;
        if (m->num_normals && c[2] >= 0) {
            const float *p0 = &m->positions[3 * c[0]], *p1 = &m->positions[3 * c[3]], *p2 = &m->positions[3 * c[6]];
            double e1[3], e2[3], ns = 0.0;
            for (int k = 0; k < 3; k++)
                e1[k] = p1[k] - p0[k], e2[k] = p2[k] - p0[k];
            double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
            for (int k = 0; k < 3; k++)
                ns += n[k] * (m->normals[3 * c[2] + k] + m->normals[3 * c[5] + k] + m->normals[3 * c[8] + k]);
            flip = ns < 0.0;
        }
        if (flip)
            swap_corners(m, t);
    }
}

/* The pbrt sphere: radius around the object origin, uv as pbrt's (u = phi / 2 pi, v = 0 at -z). */
static bool sphere(PbrtImport *imp, PbrtParams *p, Mesh *m)
{
    float radius, zmin, zmax, phimax;
    if (!pbrt_float(imp, p, "radius", 1.0f, &radius) || !pbrt_float(imp, p, "zmin", -radius, &zmin) ||
        !pbrt_float(imp, p, "zmax", radius, &zmax) || !pbrt_float(imp, p, "phimax", 360.0f, &phimax))
        return false;
    if (!(radius > 0.0f))
        return pbrt_fail(imp, imp->line, "Shape \"sphere\": radius %g must be > 0", radius);
    if (zmin > -radius || zmax < radius || phimax < 360.0f)
        pbrt_warn_once(imp, "partial sphere", "Shape \"sphere\": zmin / zmax / phimax (a partial "
                       "sphere) are not imported: rendered whole");
    const float center[3] = {0.0f, 0.0f, 0.0f};
    if (!mesh_sphere(m, center, radius, MESH_SPHERE_SEGMENTS))
        return pbrt_fail(imp, imp->line, "Shape \"sphere\": out of memory");
    for (size_t i = 0; i < m->num_texcoords; i++) /* mesh_sphere's v grows from +z */
        m->texcoords[2 * i + 1] = 1.0f - m->texcoords[2 * i + 1];
    return true;
}

/* The pbrt disk: at z = height, facing +z, uv (phi / 2 pi, 1 - r / radius). */
static bool disk(PbrtImport *imp, PbrtParams *p, Mesh *m)
{
    float height, radius, inner, phimax;
    if (!pbrt_float(imp, p, "height", 0.0f, &height) || !pbrt_float(imp, p, "radius", 1.0f, &radius) ||
        !pbrt_float(imp, p, "innerradius", 0.0f, &inner) || !pbrt_float(imp, p, "phimax", 360.0f, &phimax))
        return false;
    if (!(radius > 0.0f))
        return pbrt_fail(imp, imp->line, "Shape \"disk\": radius %g must be > 0", radius);
    if (inner > 0.0f || phimax < 360.0f)
        pbrt_warn_once(imp, "partial disk", "Shape \"disk\": innerradius / phimax are not imported: "
                       "rendered as a whole disk");
    if (!mesh_disk(m, MESH_SPHERE_SEGMENTS))
        return pbrt_fail(imp, imp->line, "Shape \"disk\": out of memory");
    for (size_t i = 0; i < m->num_positions; i++) {
        m->positions[3 * i] *= radius;
        m->positions[3 * i + 1] *= radius;
        m->positions[3 * i + 2] = height;
    }
    for (size_t i = 0; i < m->num_texcoords; i++) {
        float r = m->texcoords[2 * i], phi_u = m->texcoords[2 * i + 1];
        m->texcoords[2 * i] = phi_u;
        m->texcoords[2 * i + 1] = 1.0f - r;
    }
    return true;
}

/* The world-space area of a mesh placed by ctm (for an area light's "power"). */
static double world_area(const Mesh *m, const Affine *ctm)
{
    double area = 0.0;
    for (size_t t = 0; t < m->num_triangles; t++) {
        double p[3][3];
        for (int c = 0; c < 3; c++) {
            const float *q = &m->positions[3 * m->corners[9 * t + 3 * c]];
            const double v[3] = {q[0], q[1], q[2]};
            affine_point(ctm, v, p[c]);
        }
        double e1[3], e2[3];
        for (int k = 0; k < 3; k++)
            e1[k] = p[1][k] - p[0][k], e2[k] = p[2][k] - p[0][k];
        double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        area += 0.5 * sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    }
    return area;
}

/* Moves each point of a (flipped) mesh a hair along its front normal (the face normals around it,
 * area-weighted): 1e-4 of the mesh's size. A copy exactly on top of the original would tie with
 * it on every ray, and ties go to the lower triangle index (tests/test_accel_hit_ties.c), so one
 * copy would hide the other from both sides. */
static void offset_behind(Mesh *m)
{
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    double *n = calloc(3 * m->num_positions, sizeof *n);
    if (!n)
        return;
    for (size_t i = 0; i < m->num_positions; i++)
        for (int k = 0; k < 3; k++)
            lo[k] = fmin(lo[k], m->positions[3 * i + k]), hi[k] = fmax(hi[k], m->positions[3 * i + k]);
    double size = sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                       (hi[2] - lo[2]) * (hi[2] - lo[2]));
    for (size_t t = 0; t < m->num_triangles; t++) {
        const int32_t *c = &m->corners[9 * t];
        const float *p0 = &m->positions[3 * c[0]], *p1 = &m->positions[3 * c[3]], *p2 = &m->positions[3 * c[6]];
        double e1[3], e2[3];
        for (int k = 0; k < 3; k++)
            e1[k] = p1[k] - p0[k], e2[k] = p2[k] - p0[k];
        double f[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        for (int v = 0; v < 3; v++)
            for (int k = 0; k < 3; k++)
                n[3 * c[3 * v] + k] += f[k];
    }
    for (size_t i = 0; i < m->num_positions; i++) {
        double len = sqrt(n[3 * i] * n[3 * i] + n[3 * i + 1] * n[3 * i + 1] + n[3 * i + 2] * n[3 * i + 2]);
        for (int k = 0; k < 3 && len > 0.0; k++)
            m->positions[3 * i + k] += (float)(1e-4 * size * n[3 * i + k] / len);
    }
    free(n);
}

/* The same mesh facing the other way (an emitter's back side for "twosided"), a hair behind it. */
static bool flipped_copy(const Mesh *m, Mesh *out)
{
    memset(out, 0, sizeof *out);
    out->positions = malloc(3 * m->num_positions * sizeof(float));
    out->normals = m->num_normals ? malloc(3 * m->num_normals * sizeof(float)) : NULL;
    out->texcoords = m->num_texcoords ? malloc(2 * m->num_texcoords * sizeof(float)) : NULL;
    out->corners = malloc(9 * m->num_triangles * sizeof(int32_t));
    out->material_ids = malloc(m->num_triangles * sizeof(int32_t));
    if (!out->positions || !out->corners || !out->material_ids || (m->num_normals && !out->normals) ||
        (m->num_texcoords && !out->texcoords)) {
        mesh_free(out);
        return false;
    }
    memcpy(out->positions, m->positions, 3 * m->num_positions * sizeof(float));
    for (size_t i = 0; i < 3 * m->num_normals; i++)
        out->normals[i] = -m->normals[i];
    if (m->num_texcoords)
        memcpy(out->texcoords, m->texcoords, 2 * m->num_texcoords * sizeof(float));
    memcpy(out->corners, m->corners, 9 * m->num_triangles * sizeof(int32_t));
    memcpy(out->material_ids, m->material_ids, m->num_triangles * sizeof(int32_t));
    out->num_positions = m->num_positions;
    out->num_normals = m->num_normals;
    out->num_texcoords = m->num_texcoords;
    out->num_triangles = out->num_faces = m->num_triangles;
    for (size_t t = 0; t < m->num_triangles; t++)
        swap_corners(out, t);
    offset_behind(out);
    return true;
}

static bool add_object(PbrtImport *imp, bool is_ply, const char *name, const char *material, const Affine *ctm)
{
    if (imp->current_def >= 0) {
        PbrtObjectDef *d = &imp->defs[imp->current_def];
        PbrtInstanceShape *grown = realloc(d->shapes, (size_t)(d->count + 1) * sizeof *grown);
        if (!grown)
            return pbrt_fail(imp, imp->line, "ObjectBegin \"%s\": out of memory", d->name);
        d->shapes = grown;
        PbrtInstanceShape *s = &d->shapes[d->count++];
        s->is_ply = is_ply;
        snprintf(s->name, sizeof s->name, "%s", name);
        snprintf(s->material, sizeof s->material, "%s", material);
        s->ctm = *ctm;
        return true;
    }
    cJSON *o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, is_ply ? "ply" : "mesh", name);
    cJSON_AddStringToObject(o, "material", material);
    cJSON_AddItemToObject(o, "transform", pbrt_matrix_json(imp, ctm));
    cJSON_AddItemToArray(imp->objects, o);
    return true;
}

bool pbrt_place_instance(PbrtImport *imp, const PbrtObjectDef *def, const Affine *ctm)
{
    for (int i = 0; i < def->count; i++) {
        Affine m = affine_mul(ctm, &def->shapes[i].ctm);
        if (!add_object(imp, def->shapes[i].is_ply, def->shapes[i].name, def->shapes[i].material, &m))
            return false;
    }
    return true;
}

/* The emission of a shape under AreaLightSource, power applied; false: none. */
static bool shape_emission(PbrtImport *imp, const Mesh *m, float out[3])
{
    if (!imp->state.area_light)
        return false;
    if (imp->current_def >= 0) {
        pbrt_warn_once(imp, "instanced light", "AreaLightSource inside ObjectBegin: instanced "
                       "shapes do not emit (as in pbrt-v4)");
        return false;
    }
    double scale = 1.0;
    if (imp->state.area_power > 0.0f && m) {
        double area = world_area(m, &imp->state.ctm) * (imp->state.area_twosided ? 2.0 : 1.0);
        scale = area > 0.0 ? imp->state.area_power / (PI_D * area) : 0.0;
    }
    for (int k = 0; k < 3; k++)
        out[k] = (float)(imp->state.area_radiance[k] * scale);
    return true;
}

static bool plymesh(PbrtImport *imp, PbrtParams *p)
{
    bool ok = true;
    const char *file = pbrt_string(imp, p, "filename", &ok);
    if (!ok)
        return false;
    if (!file)
        return pbrt_fail(imp, imp->line, "Shape \"plymesh\": no \"string filename\"");
    if (!pbrt_check_path(imp, file, "Shape \"plymesh\" \"filename\"", imp->line))
        return false;
    if (pbrt_param(p, "displacement"))
        pbrt_warn_once(imp, "displacement", "Shape \"plymesh\": \"displacement\" is not imported "
                       "(rendered undisplaced)");
    (void)pbrt_param(p, "edgelength");
    if (imp->state.reverse)
        pbrt_warn_once(imp, "ply reverse", "Shape \"plymesh\": ReverseOrientation is not applied to "
                       "PLY files (their front stays as in the file)");
    float emission[3];
    bool emits = shape_emission(imp, NULL, emission);
    if (emits && (imp->state.area_power > 0.0f || imp->state.area_twosided))
        pbrt_warn_once(imp, "ply light", "Shape \"plymesh\" under AreaLightSource: \"power\" and "
                       "\"twosided\" are not applied to PLY files");
    char material[SCENE_NAME_LIMIT];
    return pbrt_shape_material(imp, emits ? emission : NULL, p, material) &&
           add_object(imp, true, file, material, &imp->state.ctm);
}

/* Stores *m as a new mesh and adds the object naming it. */
static bool add_mesh_object(PbrtImport *imp, Mesh *m, const char *material)
{
    char name[64];
    snprintf(name, sizeof name, "shape%d", imp->num_meshes++);
    if (!imported_scene_add_mesh(imp->out, name, m, imp->err))
        return false;
    return add_object(imp, false, name, material, &imp->state.ctm);
}

bool pbrt_shape(PbrtImport *imp, const char *type, PbrtParams *p)
{
    if (strcmp(type, "plymesh") == 0)
        return plymesh(imp, p);
    Mesh m = {0};
    bool ok;
    if (strcmp(type, "trianglemesh") == 0 || strcmp(type, "bilinearmesh") == 0) {
        ok = polygon_mesh(imp, p, type[0] == 't' ? 3 : 4, &m);
        if (pbrt_param(p, "S"))
            pbrt_warn_once(imp, "S", "Shape \"%s\": \"S\" (tangents) is not imported: pt takes its "
                           "tangents from the uvs", type);
        (void)pbrt_param(p, "faceIndices");
    } else if (strcmp(type, "loopsubdiv") == 0) {
        /* Its control mesh: coarser than pbrt's limit surface, but the shape is there. */
        pbrt_warn_once(imp, type, "Shape \"loopsubdiv\": rendered as its control mesh (not subdivided)");
        ok = polygon_mesh(imp, p, 3, &m);
        (void)pbrt_param(p, "levels");
    } else if (strcmp(type, "sphere") == 0) {
        ok = sphere(imp, p, &m);
    } else if (strcmp(type, "disk") == 0) {
        ok = disk(imp, p, &m);
    } else {
        pbrt_warn_once(imp, type, "Shape \"%s\": not imported (pt reads trianglemesh, plymesh, "
                       "bilinearmesh, loopsubdiv, sphere, disk)", type);
        for (int i = 0; i < p->count; i++)
            p->items[i].used = true;
        return true;
    }
    if (!ok) {
        mesh_free(&m);
        return false;
    }
    orient(&m, imp->state.reverse);
    float emission[3];
    bool emits = shape_emission(imp, &m, emission);
    char material[SCENE_NAME_LIMIT];
    if (!pbrt_shape_material(imp, emits ? emission : NULL, p, material)) {
        mesh_free(&m);
        return false;
    }
    Mesh back;
    bool twosided = emits && imp->state.area_twosided;
    if (twosided && !flipped_copy(&m, &back)) {
        mesh_free(&m);
        return pbrt_fail(imp, imp->line, "Shape \"%s\": out of memory", type);
    }
    /* pt's emitters are one-sided: a two-sided pbrt light is its shape twice, back to back. */
    if (!add_mesh_object(imp, &m, material)) {
        if (twosided)
            mesh_free(&back);
        return false;
    }
    return !twosided || add_mesh_object(imp, &back, material);
}
