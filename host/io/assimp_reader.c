// SPDX-License-Identifier: MIT
/* assimp_reader.c: other tools' formats through Assimp's C API (io/assimp_reader.h). */
#include "io/assimp_reader.h"

#include <assimp/cimport.h>
#include <assimp/light.h>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/fs.h"
#include "base/transform.h"
#include "io/input_file.h"

#define ASSIMP_FILE_LIMIT ((size_t)2 << 30)
#define NODE_DEPTH_LIMIT 256
#define PI 3.14159265358979323846

typedef struct {
    const char *path;
    const struct aiScene *ai;
    AssimpScene *out;
    Error *err;
    bool warned_embedded, warned_points;
} Reader;

static bool oom(Reader *r)
{
    error_set(r->err, ERR_OUT_OF_MEMORY, r->path, 0, "%s: out of memory", r->path);
    return false;
}

static void matrix_of(const struct aiMatrix4x4 *m, double out[16])
{
    const ai_real v[16] = {m->a1, m->a2, m->a3, m->a4, m->b1, m->b2, m->b3, m->b4,
                           m->c1, m->c2, m->c3, m->c4, m->d1, m->d2, m->d3, m->d4};
    for (int i = 0; i < 16; i++)
        out[i] = v[i];
}

static void apply(const double m[16], const double p[3], double w, double out[3])
{
    for (int i = 0; i < 3; i++)
        out[i] = m[4 * i] * p[0] + m[4 * i + 1] * p[1] + m[4 * i + 2] * p[2] + m[4 * i + 3] * w;
}

/* ---------------------------------------------------------------- materials */

/* Whether a texture reference names one of the file's embedded textures ("*N", or FBX's
 * original file name of an embedded one). */
static bool embedded(const struct aiScene *ai, const char *ref)
{
    if (ref[0] == '*')
        return true;
    for (unsigned i = 0; i < ai->mNumTextures; i++)
        if (strcmp(ai->mTextures[i]->mFilename.data, ref) == 0)
            return true;
    return false;
}

static bool material_of(Reader *r, const struct aiMaterial *am, int index, ObjMaterial *o)
{
    memset(o, 0, sizeof *o);
    struct aiString name;
    if (aiGetMaterialString(am, AI_MATKEY_NAME, &name) == AI_SUCCESS && name.length > 0)
        snprintf(o->name, sizeof o->name, "%d:%.100s", index, name.data);
    else
        snprintf(o->name, sizeof o->name, "material%d", index);
    o->kd[0] = o->kd[1] = o->kd[2] = 0.8f;
    o->tf[0] = o->tf[1] = o->tf[2] = 1.0f;
    o->ni = 1.0f, o->d = 1.0f, o->illum = -1, o->bump_scale = 1.0f;
    struct aiColor4D c;
    if (aiGetMaterialColor(am, AI_MATKEY_BASE_COLOR, &c) == AI_SUCCESS ||
        aiGetMaterialColor(am, AI_MATKEY_COLOR_DIFFUSE, &c) == AI_SUCCESS)
        o->kd[0] = c.r, o->kd[1] = c.g, o->kd[2] = c.b;
    if (aiGetMaterialColor(am, AI_MATKEY_COLOR_EMISSIVE, &c) == AI_SUCCESS) {
        float strength = 1.0f;
        aiGetMaterialFloatArray(am, AI_MATKEY_EMISSIVE_INTENSITY, &strength, NULL);
        o->ke[0] = c.r * strength, o->ke[1] = c.g * strength, o->ke[2] = c.b * strength;
    }
    float v;
    if (aiGetMaterialFloatArray(am, AI_MATKEY_OPACITY, &v, NULL) == AI_SUCCESS && v >= 0 && v < 1)
        o->d = v;
    if (aiGetMaterialFloatArray(am, AI_MATKEY_METALLIC_FACTOR, &v, NULL) == AI_SUCCESS)
        o->pm = fminf(1.0f, fmaxf(0.0f, v)), o->has_pm = true;
    if (aiGetMaterialFloatArray(am, AI_MATKEY_ROUGHNESS_FACTOR, &v, NULL) == AI_SUCCESS)
        o->pr = fminf(1.0f, fmaxf(0.0f, v)), o->has_pr = true;
    if (o->has_pm && !o->has_pr)
        o->pr = 0.5f, o->has_pr = true; /* principled needs both; glTF's default is 1, FBX's 0.5 */
    if (o->has_pr && !o->has_pm)
        o->has_pm = true;
    struct aiString file;
    enum aiTextureType kinds[2] = {aiTextureType_BASE_COLOR, aiTextureType_DIFFUSE};
    for (int k = 0; k < 2; k++) {
        if (aiGetMaterialTextureCount(am, kinds[k]) == 0 ||
            aiGetMaterialTexture(am, kinds[k], 0, &file, NULL, NULL, NULL, NULL, NULL, NULL) != AI_SUCCESS)
            continue;
        if (embedded(r->ai, file.data)) {
            if (!r->warned_embedded)
                warn("%s: embedded textures dropped (first in material \"%s\"): pt reads texture "
                     "files", r->path, o->name);
            r->warned_embedded = true;
            break;
        }
        char what[160];
        snprintf(what, sizeof what, "material \"%.100s\" texture", o->name);
        if (!fs_resolve_inside(r->path, file.data, what, o->map_kd, sizeof o->map_kd, r->err))
            return false;
        o->kd[0] = o->kd[1] = o->kd[2] = 1.0f;
        break;
    }
    return true;
}

/* ---------------------------------------------------------------- meshes */

static bool mesh_of(Reader *r, const struct aiMesh *am, Mesh *m)
{
    memset(m, 0, sizeof *m);
    size_t n = am->mNumVertices, faces = 0;
    for (unsigned f = 0; f < am->mNumFaces; f++)
        faces += am->mFaces[f].mNumIndices == 3;
    if (faces < am->mNumFaces && !r->warned_points) {
        warn("%s: points and lines dropped (pt renders surfaces)", r->path);
        r->warned_points = true;
    }
    m->positions = malloc((3 * n + 1) * sizeof(float));
    m->normals = am->mNormals ? malloc((3 * n + 1) * sizeof(float)) : NULL;
    m->texcoords = am->mTextureCoords[0] ? malloc((2 * n + 1) * sizeof(float)) : NULL;
    m->corners = malloc((9 * faces + 1) * sizeof(int32_t));
    m->material_ids = malloc((faces + 1) * sizeof(int32_t));
    if (!m->positions || (am->mNormals && !m->normals) || (am->mTextureCoords[0] && !m->texcoords) ||
        !m->corners || !m->material_ids) {
        mesh_free(m);
        return oom(r);
    }
    for (size_t i = 0; i < n; i++) {
        const struct aiVector3D p = am->mVertices[i];
        m->positions[3 * i] = p.x, m->positions[3 * i + 1] = p.y, m->positions[3 * i + 2] = p.z;
        if (m->normals) {
            const struct aiVector3D q = am->mNormals[i];
            m->normals[3 * i] = q.x, m->normals[3 * i + 1] = q.y, m->normals[3 * i + 2] = q.z;
        }
        if (m->texcoords) {
            const struct aiVector3D t = am->mTextureCoords[0][i];
            m->texcoords[2 * i] = t.x, m->texcoords[2 * i + 1] = t.y;
        }
    }
    m->num_positions = n;
    m->num_normals = m->normals ? n : 0;
    m->num_texcoords = m->texcoords ? n : 0;
    for (unsigned f = 0; f < am->mNumFaces; f++) {
        const struct aiFace *face = &am->mFaces[f];
        if (face->mNumIndices != 3)
            continue;
        int32_t *k = m->corners + 9 * m->num_triangles;
        for (int c = 0; c < 3; c++) {
            int32_t v = (int32_t)face->mIndices[c];
            if ((size_t)face->mIndices[c] >= n) {
                mesh_free(m);
                error_set(r->err, ERR_OBJ_INDEX, r->path, 0, "%s: mesh \"%s\": face index %u out of range",
                          r->path, am->mName.data, face->mIndices[c]);
                return false;
            }
            k[3 * c] = v, k[3 * c + 1] = m->texcoords ? v : -1, k[3 * c + 2] = m->normals ? v : -1;
        }
        m->material_ids[m->num_triangles++] = 0;
    }
    m->num_faces = m->num_triangles;
    m->materials = calloc(1, sizeof *m->materials);
    if (!m->materials) {
        mesh_free(m);
        return oom(r);
    }
    m->num_materials = 1;
    unsigned mi = am->mMaterialIndex;
    if (mi < r->ai->mNumMaterials) {
        if (!material_of(r, r->ai->mMaterials[mi], (int)mi, &m->materials[0])) {
            mesh_free(m);
            return false;
        }
    } else {
        ObjMaterial grey = {0};
        snprintf(grey.name, sizeof grey.name, "default");
        grey.kd[0] = grey.kd[1] = grey.kd[2] = 0.8f;
        grey.tf[0] = grey.tf[1] = grey.tf[2] = 1.0f;
        grey.ni = grey.d = grey.bump_scale = 1.0f, grey.illum = -1;
        m->materials[0] = grey;
    }
    return true;
}

/* ---------------------------------------------------------------- nodes */

static bool visit(Reader *r, const struct aiNode *node, const double parent[16], int depth)
{
    if (depth > NODE_DEPTH_LIMIT) {
        error_set(r->err, ERR_TOO_LARGE, r->path, 0, "%s: node \"%s\": nodes nested deeper than %d",
                  r->path, node->mName.data, NODE_DEPTH_LIMIT);
        return false;
    }
    double local[16], world[16];
    matrix_of(&node->mTransformation, local);
    rows16_mul(parent, local, world);
    AssimpScene *s = r->out;
    for (unsigned i = 0; i < node->mNumMeshes; i++) {
        if (node->mMeshes[i] >= r->ai->mNumMeshes)
            continue;
        AssimpInstance *grown = realloc(s->instances, (size_t)(s->num_instances + 1) * sizeof *grown);
        if (!grown)
            return oom(r);
        s->instances = grown;
        s->instances[s->num_instances].mesh = (int)node->mMeshes[i];
        memcpy(s->instances[s->num_instances].world, world, sizeof world);
        s->num_instances++;
    }
    for (unsigned i = 0; i < r->ai->mNumLights; i++) {
        const struct aiLight *l = r->ai->mLights[i];
        if (strcmp(l->mName.data, node->mName.data) != 0)
            continue;
        if (l->mType != aiLightSource_POINT && l->mType != aiLightSource_SPOT &&
            l->mType != aiLightSource_DIRECTIONAL) {
            warn("%s: light \"%s\" dropped (ambient and area lights: pt has neither; use "
                 "emissive geometry)", r->path, l->mName.data);
            continue;
        }
        AssimpLight *grown = realloc(s->lights, (size_t)(s->num_lights + 1) * sizeof *grown);
        if (!grown)
            return oom(r);
        s->lights = grown;
        AssimpLight *o = &s->lights[s->num_lights++];
        memset(o, 0, sizeof *o);
        o->type = l->mType == aiLightSource_SPOT ? ASSIMP_LIGHT_SPOT :
                  l->mType == aiLightSource_DIRECTIONAL ? ASSIMP_LIGHT_DIRECTIONAL : ASSIMP_LIGHT_POINT;
        double p[3] = {l->mPosition.x, l->mPosition.y, l->mPosition.z};
        double d[3] = {l->mDirection.x, l->mDirection.y, l->mDirection.z};
        if (d[0] == 0 && d[1] == 0 && d[2] == 0)
            d[2] = -1;
        apply(world, p, 1, o->position);
        apply(world, d, 0, o->direction);
        o->color[0] = l->mColorDiffuse.r, o->color[1] = l->mColorDiffuse.g, o->color[2] = l->mColorDiffuse.b;
        /* Assimp's cone angles are measured from the axis (its glTF importer stores glTF's
         * outerConeAngle unchanged). */
        double outer = l->mAngleOuterCone * 180.0 / PI, inner = l->mAngleInnerCone * 180.0 / PI;
        o->cone_angle = (float)fmin(180.0, fmax(0.01, outer));
        o->falloff_angle = (float)fmin(o->cone_angle, fmax(0.0, inner));
    }
    if (!s->has_camera)
        for (unsigned i = 0; i < r->ai->mNumCameras; i++) {
            const struct aiCamera *c = r->ai->mCameras[i];
            if (strcmp(c->mName.data, node->mName.data) != 0)
                continue;
            double p[3] = {c->mPosition.x, c->mPosition.y, c->mPosition.z};
            double look[3] = {c->mLookAt.x, c->mLookAt.y, c->mLookAt.z};
            double up[3] = {c->mUp.x, c->mUp.y, c->mUp.z}, dir[3];
            apply(world, p, 1, s->camera.eye);
            apply(world, look, 0, dir);
            apply(world, up, 0, s->camera.up);
            for (int k = 0; k < 3; k++)
                s->camera.target[k] = s->camera.eye[k] + dir[k];
            /* mHorizontalFOV is half the horizontal angle, radians. */
            double aspect = c->mAspect > 0 ? c->mAspect : 4.0 / 3.0;
            double half = fmin(1.5, fmax(1e-3, c->mHorizontalFOV));
            s->camera.fov_y = (float)(2.0 * atan(tan(half) / aspect) * 180.0 / PI);
            s->camera.aspect = c->mAspect > 0 ? c->mAspect : 0;
            s->has_camera = true;
            break;
        }
    for (unsigned i = 0; i < node->mNumChildren; i++)
        if (!visit(r, node->mChildren[i], world, depth + 1))
            return false;
    return true;
}

bool assimp_read_memory(const char *path, const char *hint, const void *data, size_t size,
                        AssimpScene *out, Error *err)
{
    memset(out, 0, sizeof *out);
    if (size > 0xFFFFFFFFu) {
        error_set(err, ERR_TOO_LARGE, path, 0, "%s: larger than 4 GiB", path);
        return false;
    }
    if (size == 0) { /* Assimp asserts (aborts) on an empty buffer */
        error_set(err, ERR_OBJ_PARSE, path, 0, "%s: the file is empty", path);
        return false;
    }
    /* Triangulate (n-gons), sort by primitive type (points and lines apart), drop degenerate
     * triangles; validation refuses inconsistent structures instead of handing them on. */
    const struct aiScene *ai = aiImportFileFromMemory(
        data, (unsigned)size,
        aiProcess_Triangulate | aiProcess_SortByPType | aiProcess_ValidateDataStructure |
            aiProcess_FindInvalidData,
        hint);
    if (!ai || !ai->mRootNode) {
        char reason[400];
        snprintf(reason, sizeof reason, "%s", aiGetErrorString());
        reason[strcspn(reason, "\r\n")] = '\0';
        error_set(err, ERR_OBJ_PARSE, path, 0, "%s: Assimp cannot read it: %s", path,
                  reason[0] ? reason : "no reason given");
        if (ai)
            aiReleaseImport(ai);
        return false;
    }
    Reader r = {.path = path, .ai = ai, .out = out, .err = err};
    bool ok = true;
    out->meshes = calloc(ai->mNumMeshes + 1, sizeof *out->meshes);
    if (!out->meshes)
        ok = oom(&r);
    for (unsigned i = 0; ok && i < ai->mNumMeshes; i++) {
        ok = mesh_of(&r, ai->mMeshes[i], &out->meshes[i]);
        out->num_meshes += ok;
    }
    double identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    ok = ok && visit(&r, ai->mRootNode, identity, 0);
    aiReleaseImport(ai);
    if (!ok)
        assimp_scene_free(out);
    return ok;
}

bool assimp_read(const char *path, const char *format_name, AssimpScene *out, Error *err)
{
    char kind[64], *data;
    size_t size;
    snprintf(kind, sizeof kind, "a %s file", format_name);
    memset(out, 0, sizeof *out);
    if (!input_file_read(path, kind, ASSIMP_FILE_LIMIT, &data, &size, err))
        return false;
    const char *dot = strrchr(path, '.');
    bool ok = assimp_read_memory(path, dot ? dot + 1 : "", data, size, out, err);
    free(data);
    return ok;
}

void assimp_scene_free(AssimpScene *s)
{
    for (int i = 0; i < s->num_meshes; i++)
        mesh_free(&s->meshes[i]);
    free(s->meshes);
    free(s->instances);
    free(s->lights);
    memset(s, 0, sizeof *s);
}
