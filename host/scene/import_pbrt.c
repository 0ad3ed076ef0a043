// SPDX-License-Identifier: MIT
/* import_pbrt.c: the directives of a pbrt-v4 file: object instancing, the scene-wide ones
 * (Camera, Film, Sampler, Integrator) and the dispatch of the others; transforms, named
 * coordinate systems and the graphics state stack are in import_pbrt_transforms.c, shapes,
 * materials and lights are mapped in import_pbrt_*.c. */
#include "scene/import_pbrt.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene/import_pbrt_internal.h"

/* ---- Directives ----------------------------------------------------------------------------- */

/* The quoted string arguments a directive takes before its parameters. */
static bool read_strings(PbrtImport *imp, const char *directive, char out[][SCENE_NAME_LIMIT], int n)
{
    for (int i = 0; i < n; i++) {
        PbrtToken t;
        if (!pbrt_next(imp->reader, &t, imp->err))
            return false;
        if (t.kind != PBRT_TOKEN_STRING)
            return pbrt_fail(imp, t.line, "%s: expected a quoted %s", directive,
                             i == 0 ? "name or type" : "argument");
        if (strlen(t.text) >= SCENE_NAME_LIMIT)
            return pbrt_fail(imp, t.line, "%s: \"%.40s...\" is too long", directive, t.text);
        snprintf(out[i], SCENE_NAME_LIMIT, "%s", t.text);
    }
    return true;
}

static bool object_begin(PbrtImport *imp, const char *name)
{
    if (imp->current_def >= 0)
        return pbrt_fail(imp, imp->line, "ObjectBegin: inside the definition of \"%s\"",
                         imp->defs[imp->current_def].name);
    for (int i = 0; i < imp->num_defs; i++)
        if (strcmp(imp->defs[i].name, name) == 0)
            return pbrt_fail(imp, imp->line, "ObjectBegin: \"%s\" is defined twice", name);
    PbrtObjectDef *grown = realloc(imp->defs, (size_t)(imp->num_defs + 1) * sizeof *grown);
    if (!grown)
        return pbrt_fail(imp, imp->line, "ObjectBegin: out of memory");
    imp->defs = grown;
    memset(&imp->defs[imp->num_defs], 0, sizeof *grown);
    snprintf(imp->defs[imp->num_defs].name, SCENE_NAME_LIMIT, "%s", name);
    imp->current_def = imp->num_defs++;
    return true;
}

static bool object_instance(PbrtImport *imp, const char *name)
{
    if (imp->current_def >= 0)
        return pbrt_fail(imp, imp->line, "ObjectInstance: inside an ObjectBegin (nested instances)");
    for (int i = 0; i < imp->num_defs; i++)
        if (strcmp(imp->defs[i].name, name) == 0)
            return pbrt_place_instance(imp, &imp->defs[i], &imp->state.ctm);
    return pbrt_fail(imp, imp->line, "ObjectInstance: no object \"%s\" (ObjectBegin)", name);
}


/* Camera (its parameters kept until the film's size is known), Film, Sampler, Integrator. */
static bool render_setting(PbrtImport *imp, const char *word, const char *type, PbrtParams *params)
{
    bool ok = true;
    if (strcmp(word, "Camera") == 0) {
        if (imp->in_world)
            ok = pbrt_fail(imp, imp->line, "Camera: inside the world block (after WorldBegin)");
        else {
            pbrt_params_free(&imp->camera_params);
            imp->camera_params = *params;
            memset(params, 0, sizeof *params);
            imp->camera_from_world = imp->state.ctm;
            imp->has_camera = true;
            Affine world_from_camera;
            if (!affine_invert(&imp->state.ctm, &world_from_camera))
                return pbrt_fail(imp, imp->line, "Camera: the camera transform is singular");
            pbrt_coord_system(imp, "camera", true);
            imp->coord_systems[imp->num_coord_systems - 1].ctm = world_from_camera;
            /* A mirroring camera transform already flips the picture (file header comment). */
            imp->pt_from_pbrt = affine_det(&imp->state.ctm) < 0.0 ? affine_identity()
                                                                    : affine_scale(-1.0, 1.0, 1.0);
            if (strcmp(type, "perspective") != 0)
                pbrt_warn_once(imp, "camera", "Camera \"%s\": imported as \"perspective\"", type);
        }
    } else if (strcmp(word, "Film") == 0) {
        int w, h;
        ok = pbrt_int(imp, params, "xresolution", 1280, &w) && pbrt_int(imp, params, "yresolution", 720, &h);
        if (ok && (w < 1 || h < 1 || w > 65536 || h > 65536))
            ok = pbrt_fail(imp, imp->line, "Film: resolution %d x %d is out of range [1, 65536]", w, h);
        bool ignored = true;
        (void)pbrt_string(imp, params, "filename", &ignored);
        if (ok) {
            cJSON_DeleteItemFromObject(imp->film, "width");
            cJSON_DeleteItemFromObject(imp->film, "height");
            cJSON_AddNumberToObject(imp->film, "width", w);
            cJSON_AddNumberToObject(imp->film, "height", h);
        }
        if (strcmp(type, "rgb") != 0 && strcmp(type, "gbuffer") != 0)
            pbrt_warn_once(imp, "film", "Film \"%s\": imported as \"rgb\"", type);
    } else if (strcmp(word, "Sampler") == 0) {
        int spp;
        ok = pbrt_int(imp, params, "pixelsamples", 16, &spp);
        if (ok && spp < 1)
            ok = pbrt_fail(imp, imp->line, "Sampler: pixelsamples %d must be >= 1", spp);
        if (ok) {
            cJSON_DeleteItemFromObject(imp->render, "spp");
            cJSON_AddNumberToObject(imp->render, "spp", spp);
        }
    } else if (strcmp(word, "Integrator") == 0) {
        /* pbrt's maxdepth counts bounces (0: emitters seen directly, 1: direct light); pt's
         * max_depth counts path segments from the camera (1: emitters, 2: direct light). */
        int depth;
        ok = pbrt_int(imp, params, "maxdepth", 5, &depth);
        if (ok && (depth < 0 || depth > 1023))
            ok = pbrt_fail(imp, imp->line, "Integrator: maxdepth %d is out of range [0, 1023]", depth);
        if (ok) {
            cJSON_DeleteItemFromObject(imp->render, "max_depth");
            cJSON_AddNumberToObject(imp->render, "max_depth", depth + 1);
        }
        if (strcmp(type, "path") != 0 && strcmp(type, "volpath") != 0)
            pbrt_warn_once(imp, "integrator", "Integrator \"%s\": pt renders with its path tracer", type);
    }
    return ok;
}

/* Directives with one string argument and a parameter list that belong to the scene. */
static bool typed_directive(PbrtImport *imp, const char *word, bool *handled)
{
    static const char *const names[] = {"Shape", "Material", "LightSource", "AreaLightSource",
                                        "Camera", "Film", "Sampler", "Integrator", "MakeNamedMaterial",
                                        "Texture", "PixelFilter", "Accelerator", "ColorSpace",
                                        "MakeNamedMedium", "Option", NULL};
    int k = 0;
    while (names[k] && strcmp(names[k], word) != 0)
        k++;
    *handled = names[k] != NULL;
    if (!*handled)
        return true;
    char args[3][SCENE_NAME_LIMIT];
    /* Option's one string is its parameter's declaration ("bool disablepixeljitter" true). */
    int nargs = strcmp(word, "Texture") == 0 ? 3 : strcmp(word, "Option") == 0 ? 0 : 1;
    snprintf(args[0], sizeof args[0], "%s", "");
    PbrtParams params;
    if (!read_strings(imp, word, args, nargs))
        return false;
    if (!pbrt_read_params(imp->reader, word, &params, imp->err))
        return pbrt_params_free(&params), false;
    bool ok = true;
    if (strcmp(word, "Shape") == 0)
        ok = pbrt_shape(imp, args[0], &params);
    else if (strcmp(word, "Material") == 0) {
        char name[SCENE_NAME_LIMIT];
        for (int i = imp->num_materials;; i++) { /* a name no MakeNamedMaterial took */
            snprintf(name, sizeof name, "material%d", i);
            if (!cJSON_GetObjectItemCaseSensitive(imp->materials, name))
                break;
        }
        ok = pbrt_material(imp, name, args[0], &params);
        if (ok)
            snprintf(imp->state.material, sizeof imp->state.material, "%s", name);
    } else if (strcmp(word, "MakeNamedMaterial") == 0) {
        bool found = true;
        const char *type = pbrt_string(imp, &params, "type", &ok);
        found = type != NULL;
        ok = ok && (found ? pbrt_material(imp, args[0], type, &params)
                          : pbrt_fail(imp, imp->line, "MakeNamedMaterial \"%s\": no \"string type\"", args[0]));
    } else if (strcmp(word, "Texture") == 0)
        ok = pbrt_texture(imp, args[0], args[1], args[2], &params);
    else if (strcmp(word, "LightSource") == 0)
        ok = pbrt_light(imp, args[0], &params);
    else if (strcmp(word, "AreaLightSource") == 0)
        ok = pbrt_area_light(imp, args[0], &params);
    else if (strcmp(word, "Camera") == 0 || strcmp(word, "Film") == 0 || strcmp(word, "Sampler") == 0 ||
             strcmp(word, "Integrator") == 0) {
        ok = render_setting(imp, word, args[0], &params);
    } else {
        pbrt_warn_once(imp, word, "%s \"%s\": not imported (ignored)", word, args[0]);
        for (int i = 0; i < params.count; i++)
            params.items[i].used = true;
    }
    if (ok && strcmp(word, "Camera") != 0 && strcmp(word, "MakeNamedMaterial") != 0 &&
        strcmp(word, "Material") != 0 && strcmp(word, "Texture") != 0)
        pbrt_warn_unused(imp, word, args[0], &params);
    pbrt_params_free(&params);
    return ok;
}

/* The directives without a parameter list. */
static bool plain_directive(PbrtImport *imp, const char *word)
{
    char arg[1][SCENE_NAME_LIMIT];
    if (strcmp(word, "AttributeBegin") == 0 || strcmp(word, "TransformBegin") == 0)
        return pbrt_push_state(imp, word);
    if (strcmp(word, "AttributeEnd") == 0 || strcmp(word, "TransformEnd") == 0)
        return pbrt_pop_state(imp, word, strcmp(word, "TransformEnd") == 0);
    if (strcmp(word, "Identity") == 0) {
        imp->state.ctm = affine_identity();
        return true;
    }
    if (strcmp(word, "ReverseOrientation") == 0) {
        imp->state.reverse = !imp->state.reverse;
        return true;
    }
    if (strcmp(word, "WorldBegin") == 0) {
        imp->in_world = true;
        imp->state.ctm = affine_identity();
        pbrt_coord_system(imp, "world", true);
        return true;
    }
    if (strcmp(word, "ObjectEnd") == 0) {
        if (imp->current_def < 0)
            return pbrt_fail(imp, imp->line, "ObjectEnd without ObjectBegin");
        imp->current_def = -1;
        return pbrt_pop_state(imp, word, false);
    }
    if (strcmp(word, "WorldEnd") == 0)
        return true; /* pbrt-v3's; the file's end ends the world in pbrt-v4 */
    static const char *const with_name[] = {"NamedMaterial", "ObjectBegin", "ObjectInstance",
                                            "CoordinateSystem", "CoordSysTransform",
                                            "ActiveTransform", "MediumInterface", "Attribute", NULL};
    int k = 0;
    while (with_name[k] && strcmp(with_name[k], word) != 0)
        k++;
    if (!with_name[k])
        return pbrt_fail(imp, imp->line, "unknown directive \"%s\"", word);
    if (!read_strings(imp, word, arg, 1))
        return false;
    switch (k) {
    case 0:
        snprintf(imp->state.material, sizeof imp->state.material, "%s", arg[0]);
        if (!cJSON_GetObjectItemCaseSensitive(imp->materials, arg[0]))
            return pbrt_fail(imp, imp->line, "NamedMaterial: no material \"%s\" (MakeNamedMaterial)", arg[0]);
        return true;
    case 1: return pbrt_push_state(imp, word) && object_begin(imp, arg[0]);
    case 2: return object_instance(imp, arg[0]);
    case 3: return pbrt_coord_system(imp, arg[0], true);
    case 4: return pbrt_coord_system(imp, arg[0], false);
    case 5:
        imp->ignore_transforms = strcmp(arg[0], "EndTime") == 0;
        if (strcmp(arg[0], "All") != 0)
            pbrt_warn_once(imp, "motion", "ActiveTransform %s: motion blur is not imported (the "
                           "start time's transforms are used)", arg[0]);
        return true;
    default: { /* MediumInterface takes one or two names; Attribute a parameter list */
        PbrtToken t;
        PbrtParams params;
        if (!pbrt_peek(imp->reader, &t, imp->err))
            return false;
        if (k == 6 && t.kind == PBRT_TOKEN_STRING && !strchr(t.text, ' '))
            pbrt_next(imp->reader, &t, imp->err);
        if (k == 7 && (!pbrt_read_params(imp->reader, word, &params, imp->err) || (pbrt_params_free(&params), false)))
            return false;
        pbrt_warn_once(imp, word, "%s: not imported (ignored; pt has no media yet)", word);
        return true;
    }
    }
}

static bool directive(PbrtImport *imp, const char *word)
{
    bool handled;
    if (!pbrt_transform_directive(imp, word, &handled))
        return false;
    if (handled)
        return true;
    if (!typed_directive(imp, word, &handled))
        return false;
    return handled || plain_directive(imp, word);
}

static bool parse(PbrtImport *imp)
{
    for (;;) {
        PbrtToken t;
        if (!pbrt_next(imp->reader, &t, imp->err))
            return false;
        imp->file = t.file;
        imp->line = t.line;
        if (t.kind == PBRT_TOKEN_END)
            return imp->current_def < 0 || pbrt_fail(imp, t.line, "ObjectBegin \"%s\" without ObjectEnd",
                                                     imp->defs[imp->current_def].name);
        if (t.kind != PBRT_TOKEN_WORD)
            return pbrt_fail(imp, t.line, "expected a directive, found %s",
                             t.kind == PBRT_TOKEN_NUMBER ? "a number" :
                             t.kind == PBRT_TOKEN_STRING ? "a quoted string" : "a bracket");
        char word[64];
        if (strlen(t.text) >= sizeof word)
            return pbrt_fail(imp, t.line, "unknown directive \"%.40s...\"", t.text);
        snprintf(word, sizeof word, "%s", t.text);
        if (!directive(imp, word))
            return false;
    }
}

static void free_import(PbrtImport *imp)
{
    pbrt_reader_close(imp->reader);
    pbrt_params_free(&imp->camera_params);
    free(imp->coord_systems);
    free(imp->pbrt_textures);
    for (int i = 0; i < imp->num_defs; i++)
        free(imp->defs[i].shapes);
    free(imp->defs);
    free(imp->warned);
    cJSON_Delete(imp->variants);
}

bool import_pbrt(const char *path, ImportedScene *out, Error *err)
{
    PbrtImport imp = {.path = path, .out = out, .err = err, .file = path, .line = 0, .current_def = -1};
    imp.state.ctm = imp.camera_from_world = affine_identity();
    imp.pt_from_pbrt = affine_scale(-1.0, 1.0, 1.0);
    imp.reader = pbrt_reader_open(path, err);
    if (!imp.reader)
        return false;
    out->root = cJSON_CreateObject();
    imp.variants = cJSON_CreateObject();
    imp.objects = cJSON_AddArrayToObject(out->root, "objects");
    imp.materials = cJSON_AddObjectToObject(out->root, "materials");
    imp.textures = cJSON_AddObjectToObject(out->root, "textures");
    imp.lights = cJSON_AddArrayToObject(out->root, "lights");
    imp.film = cJSON_AddObjectToObject(out->root, "film");
    imp.render = cJSON_AddObjectToObject(out->root, "render");
    cJSON_AddNumberToObject(imp.film, "width", 1280); /* pbrt's defaults */
    cJSON_AddNumberToObject(imp.film, "height", 720);
    cJSON_AddNumberToObject(imp.render, "spp", 16);
    cJSON_AddNumberToObject(imp.render, "max_depth", 6);
    bool ok = parse(&imp) && pbrt_camera_json(&imp, out->root);
    if (ok && cJSON_GetArraySize(imp.objects) == 0)
        ok = pbrt_fail(&imp, imp.line, "no shapes (pt needs at least one)");
    free_import(&imp);
    return ok;
}
