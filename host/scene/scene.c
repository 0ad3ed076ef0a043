// SPDX-License-Identifier: MIT
/* scene.c: what a scene path stands for (a .json scene, a bare .obj, a folder holding scene.json)
 * and scene_load, which reads the description, its OBJ files and flattens them; scene_view.c frames
 * and lights what was loaded. */
#include "scene/scene.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "base/fs.h"
#include "io/input_file.h"
#include "scene/camera.h"
#include "scene/gltf_scene.h"
#include "scene/import_assimp.h"
#include "scene/import_collada.h"
#include "scene/import_mitsuba.h"
#include "scene/import_pbrt.h"
#include "scene/json.h"
#include "scene/load_objects.h"
#include "scene/media_load.h"
#include "scene/scene_json.h"
#include "scene/scene_media.h"

#define SCENE_FILE_LIMIT ((size_t)64 << 20) /* a scene description is small; refuse anything huge */

/* ---- Files ---------------------------------------------------------------------------------- */

/* The scene file as text: a regular file of at most SCENE_FILE_LIMIT bytes (io/input_file.h: a
 * FIFO or device is refused by name, never read), without NUL bytes (cJSON would stop there). */
static char *read_text(const char *path, Error *err)
{
    char *text;
    size_t size;
    if (!input_file_read(path, "a scene file", SCENE_FILE_LIMIT, &text, &size, err))
        return NULL;
    if (strlen(text) != size) {
        int line = json_line_at(text, strlen(text));
        error_set(err, ERR_JSON_SYNTAX, path, line, "%s:%d: NUL byte in the scene file", path, line);
        free(text);
        return NULL;
    }
    return text;
}

static bool parse_json_file(SceneDesc *d, Error *err)
{
    char *text = read_text(d->path, err);
    if (!text)
        return false;
    cJSON *root = json_parse_text(d->path, text, err);
    if (!root) {
        free(text);
        return false;
    }
    JsonParser p = {.file = d->path, .text = text, .err = err};
    bool ok = scene_json_read(&p, root, d);
    cJSON_Delete(root);
    free(text);
    return ok;
}

static void set_defaults(SceneDesc *d)
{
    memset(d, 0, sizeof *d);
    d->camera = (CameraDesc){.up = {0.0f, 1.0f, 0.0f}, .fov_y = 40.0f};
    d->width = d->height = 512;
    d->spp = 64;
    d->max_depth = 8;
    d->environment_scale = 1.0f;
}

/* The importers' declarations (scene/scene_import.h SCENE_IMPORTERS). */

typedef struct {
    const char *extension;
    SceneImporter import;
    const char *name;
} ForeignFormat;

#define FOREIGN_FORMAT(ext, importer, format_name) {ext, importer, format_name},
static const ForeignFormat foreign_formats[] = {SCENE_IMPORTERS(FOREIGN_FORMAT)};
#undef FOREIGN_FORMAT

static const ForeignFormat *foreign_format(const char *path)
{
    for (size_t i = 0; i < sizeof foreign_formats / sizeof foreign_formats[0]; i++)
        if (fs_has_suffix(path, foreign_formats[i].extension))
            return &foreign_formats[i];
    return NULL;
}

/* The formats pt reads, for the message that refuses one it does not. */
static void list_read_formats(char *out, size_t size)
{
    int n = snprintf(out, size, ".json scenes, .obj, .ply, .gltf, .glb");
    for (size_t i = 0; i < sizeof foreign_formats / sizeof foreign_formats[0]; i++)
        if (foreign_formats[i].import && n >= 0 && (size_t)n < size)
            n += snprintf(out + n, size - (size_t)n, ", %s", foreign_formats[i].extension);
}

/* A scene file of another tool: read by its importer into a pt JSON tree and in-memory meshes
 * (scene/scene_import.h), then read as any JSON scene; refused by name when pt does not read it. */
static bool refuse_format(const char *path, const ForeignFormat *f, Error *err)
{
    char formats[512];
    list_read_formats(formats, sizeof formats);
    error_set(err, ERR_FILE_READ, path, 0,
              "%s: pt does not read %s (%s) files; pt reads %s (export to one of them, e.g. glTF "
              "from Blender)", path, f->name, f->extension, formats);
    return false;
}

static bool load_foreign(SceneDesc *d, const ForeignFormat *f, Error *err)
{
    if (!f->import)
        return refuse_format(d->path, f, err);
    if (!f->import(d->path, &d->imported, err))
        return false;
    if (!d->imported.root) {
        error_set(err, ERR_FILE_READ, d->path, 0, "%s: the %s reader made no scene", d->path, f->name);
        return false;
    }
    JsonParser p = {.file = d->path, .text = NULL, .err = err};
    bool ok = scene_json_read(&p, d->imported.root, d);
    cJSON_Delete(d->imported.root);
    d->imported.root = NULL;
    return ok;
}

/* A bare glTF: its objects, lights and materials; its own camera when it has one, else framed
 * on the bounds like a bare OBJ. */
static bool load_bare_gltf(SceneDesc *d, Error *err)
{
    ObjectOptions options = {.material = NO_MATERIAL};
    ObjectTransform identity = {.transform = affine_identity(), .transform_end = affine_identity()};
    return gltf_scene_add(d, d->path, &options, &identity, -1, err);
}

/* An image given as SCENE (a render's EXR, an HDR map) is refused by name with what to do with
 * it, rather than parsed as JSON ("malformed JSON", "NUL byte"). */
static bool refuse_image(const char *path, Error *err)
{
    static const char *const images[] = {".exr", ".hdr", ".png", ".jpg", ".jpeg", ".tga", ".bmp",
                                         ".tif", ".tiff", ".webp", ".gif", ".psd", ".pic"};
    for (size_t i = 0; i < sizeof images / sizeof images[0]; i++)
        if (fs_has_suffix(path, images[i])) {
            error_set(err, ERR_FILE_READ, path, 0,
                      "%s: that is an image, not a scene: pt tonemap %s -o OUT.png displays an EXR "
                      "again; as a sky, name it in a scene's \"environment\": {\"file\": ...}",
                      path, path);
            return true;
        }
    return false;
}

bool scene_desc_load(const char *path, SceneDesc *out, Error *err)
{
    set_defaults(out);
    if (refuse_image(path, err))
        return false;
    const ForeignFormat *named = foreign_format(path);
    if (named && !named->import) /* refused by name, whether or not the file is there */
        return refuse_format(path, named, err);
    struct stat st;
    if (stat(path, &st) != 0) {
        ErrorCode code = errno == ENOENT ? ERR_FILE_MISSING : ERR_FILE_READ;
        error_set(err, code, path, 0, "%s: %s", path, strerror(errno));
        return false;
    }
    /* A folder stands for the scene.json inside it. */
    size_t len = strlen(path);
    while (len > 1 && path[len - 1] == '/')
        len--;
    int n = S_ISDIR(st.st_mode) ? snprintf(out->path, sizeof out->path, "%.*s/scene.json", (int)len, path)
                                : snprintf(out->path, sizeof out->path, "%s", path);
    if (n < 0 || (size_t)n >= sizeof out->path) {
        error_set(err, ERR_TOO_LARGE, path, 0, "%s: path too long", path);
        return false;
    }
    const ForeignFormat *foreign = foreign_format(out->path);
    if (foreign)
        return load_foreign(out, foreign, err) || (scene_desc_free(out), false);
    bool ply = fs_has_suffix(out->path, ".ply");
    if (fs_has_suffix(out->path, ".gltf") || fs_has_suffix(out->path, ".glb"))
        return load_bare_gltf(out, err) || (scene_desc_free(out), false);
    if (!ply && !fs_has_suffix(out->path, ".obj"))
        return parse_json_file(out, err) || (scene_desc_free(out), false);
    /* A bare OBJ or PLY: one object, default settings, camera framed later on the bounds. */
    out->objects = calloc(1, sizeof *out->objects);
    out->object_formats = calloc(1, sizeof *out->object_formats);
    out->object_options = calloc(1, sizeof *out->object_options);
    out->object_transforms = calloc(1, sizeof *out->object_transforms);
    if (!out->objects || !out->object_formats || !out->object_options || !out->object_transforms) {
        error_set(err, ERR_TOO_LARGE, path, 0, "%s: out of memory", path);
        scene_desc_free(out);
        return false;
    }
    out->object_formats[0] = ply ? MESH_PLY : MESH_OBJ;
    snprintf(out->objects[0], sizeof out->objects[0], "%s", out->path);
    out->object_options[0] = (ObjectOptions){.material = NO_MATERIAL};
    out->object_transforms[0].transform = out->object_transforms[0].transform_end = affine_identity();
    out->num_objects = 1;
    return true;
}

void scene_desc_free(SceneDesc *desc)
{
    free(desc->objects);
    desc->objects = NULL;
    free(desc->object_formats);
    desc->object_formats = NULL;
    free(desc->object_options);
    desc->object_options = NULL;
    free(desc->object_transforms);
    desc->object_transforms = NULL;
    free(desc->object_meshes);
    desc->object_meshes = NULL;
    for (int i = 0; i < desc->num_gltf_files; i++) {
        gltf_free(&desc->gltf_files[i].file);
        free(desc->gltf_files[i].images);
    }
    free(desc->gltf_files);
    desc->gltf_files = NULL;
    desc->num_gltf_files = 0;
    imported_scene_free(&desc->imported);
    free(desc->textures);
    desc->textures = NULL;
    desc->num_textures = 0;
    free(desc->materials);
    desc->materials = NULL;
    desc->num_materials = 0;
    free(desc->media);
    desc->media = NULL;
    desc->num_media = 0;
    free(desc->lights);
    desc->lights = NULL;
    desc->num_lights = 0;
    free(desc->black_holes);
    desc->black_holes = NULL;
    desc->num_black_holes = 0;
    desc->num_objects = 0;
}

/* The JSON textures and materials, which become the scene's first materials (0..n-1: a mix's
 * indices and objects' "material" need no remapping); *names lists them for MTL replacement. */
static bool load_json_materials(Scene *s, const char ***names, Error *err)
{
    const SceneDesc *d = &s->desc;
    int nt = d->num_textures, nm = d->num_materials;
    uint32_t *indices = malloc((nt ? (size_t)nt : 1) * sizeof *indices);
    *names = malloc((nm ? (size_t)nm : 1) * sizeof **names);
    s->data.materials = malloc((nm ? (size_t)nm : 1) * sizeof *s->data.materials);
    bool ok = indices && *names && s->data.materials;
    if (!ok)
        error_set(err, ERR_TOO_LARGE, d->path, 0, "%s: out of memory for materials", d->path);
    ok = ok && textures_load(d->textures, nt, &s->data.textures, indices, d->path, err) &&
         materials_load(d->materials, nm, d->textures, &s->data.textures, indices, 0,
                        s->data.materials, d->path, err);
    if (ok) {
        for (int i = 0; i < nm; i++)
            (*names)[i] = d->materials[i].name;
        s->data.num_materials = (uint32_t)nm;
    }
    free(indices);
    return ok;
}

/* A scene of sky alone (scene_json.c) still needs one triangle for the BVH and the buffers: a
 * degenerate one at the origin, which no ray hits (zero area) and which emits nothing. */
static bool add_sky_placeholder(SceneData *data, Error *err)
{
    float positions[9] = {0};
    int32_t corners[9] = {0, -1, -1, 1, -1, -1, 2, -1, -1}, material = -1;
    Mesh mesh = {.positions = positions, .num_positions = 3, .corners = corners,
                 .material_ids = &material, .num_triangles = 1, .num_faces = 1};
    return scene_data_append_mesh(data, &mesh, "the sky's placeholder", err);
}

bool scene_load(const char *path, Scene *out, Error *err)
{
    return scene_load_with(path, INSTANCING_AUTO, out, err);
}

bool scene_load_with(const char *path, InstancingMode instancing, Scene *out, Error *err)
{
    memset(out, 0, sizeof *out);
    scene_data_init(&out->data);
    if (!scene_desc_load(path, &out->desc, err))
        return false;
    const char **names = NULL;
    /* Media right after the JSON materials: the "media" block takes slots 1..n, subsurface
     * materials get their walk media before objects copy them (scene/object_media.h). */
    if (!load_json_materials(out, &names, err) || !media_load(&out->data, &out->desc, err)) {
        free(names);
        scene_free(out);
        return false;
    }
    NamedMaterials named = {names, out->data.num_materials};
    if (out->desc.num_objects == 0 ? !add_sky_placeholder(&out->data, err)
                                   : !scene_load_objects(&out->data, &out->desc, instancing, &named, err)) {
        free(names);
        scene_free(out);
        return false;
    }
    free(names);
    if (!scene_data_finish(&out->data, out->desc.path, err) ||
        !scene_data_media_from_absorption(&out->data, err)) {
        scene_free(out);
        return false;
    }
    if (out->desc.num_lights > 0) {
        size_t bytes = (size_t)out->desc.num_lights * sizeof(AnalyticLight);
        out->data.analytic_lights = malloc(bytes);
        if (!out->data.analytic_lights) {
            error_set(err, ERR_TOO_LARGE, path, 0, "%s: out of memory", path);
            scene_free(out);
            return false;
        }
        memcpy(out->data.analytic_lights, out->desc.lights, bytes);
        out->data.num_analytic = (uint32_t)out->desc.num_lights;
    }
    Error env_err = {0}; /* named by its key, as a texture's file is (textures.NAME.file) */
    if (out->desc.environment[0] &&
        !environment_load(&out->data.environment, out->desc.environment, out->desc.environment_scale,
                          out->desc.environment_rotation, &env_err)) {
        error_set(err, env_err.code, out->desc.path, 0, "%s: environment.file: %s", out->desc.path,
                  env_err.message);
        scene_free(out);
        return false;
    }
    if (!out->desc.camera_given)
        scene_frame_camera(out, UP_AXIS_Y);
    return true;
}

bool scene_is_bare_model(const char *path)
{
    static const char *const bare[] = {".obj", ".ply", ".gltf", ".glb"};
    for (size_t i = 0; i < sizeof bare / sizeof bare[0]; i++)
        if (fs_has_suffix(path, bare[i]))
            return true;
    return false;
}

void scene_free(Scene *scene)
{
    scene_desc_free(&scene->desc);
    scene_data_free(&scene->data);
}
