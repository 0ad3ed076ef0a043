/* SPDX-License-Identifier: MIT */
/* import_pbrt_internal.h: what the parts of the pbrt-v4 importer share (scene/import_pbrt.c the
 * directives and graphics state, import_pbrt_shapes.c, import_pbrt_materials.c,
 * import_pbrt_lights.c).
 *
 * Handedness. pbrt is left-handed: its LookAt makes image-right = cross(up, view direction), while
 * pt's camera (right-handed) has image-right = cross(view direction, up). Numbers copied across
 * would show the mirror image. So every point of the pbrt world is mapped into pt's world by
 * pt_from_pbrt, a mirror (x -> -x) when the camera's own transform is a rotation, or the identity
 * when the camera transform already mirrors (a "Scale -1 1 1" before LookAt, common in exported
 * scenes): either way the picture pt takes is pbrt's, pixel for pixel. Mirrored objects keep their
 * front (DESIGN.md "Objects": the front follows the inverse-transposed normal), which is pbrt's
 * rule too (a transform that swaps handedness flips the geometric normal back). */
#ifndef PT_IMPORT_PBRT_INTERNAL_H
#define PT_IMPORT_PBRT_INTERNAL_H

#include <stdbool.h>

#include "base/fs.h"
#include "base/transform.h"
#include "io/pbrt_parser.h"
#include "scene/scene_import.h"

/* The graphics state AttributeBegin/AttributeEnd save and restore. */
typedef struct {
    Affine ctm;       /* pbrt world (or camera) from object */
    bool reverse;     /* ReverseOrientation */
    char material[SCENE_NAME_LIMIT]; /* pt material name; "" = pbrt's default diffuse 0.5 */
    bool area_light;  /* AreaLightSource "diffuse" in effect */
    float area_radiance[3]; /* L x scale (power applied per shape) */
    float area_power;       /* > 0: radiance scaled so the shape emits this power */
    bool area_twosided;
} PbrtState;

/* A shape recorded inside ObjectBegin/ObjectEnd, placed by each ObjectInstance. */
typedef struct {
    bool is_ply;            /* "ply" object naming file, else "mesh" naming an in-memory mesh */
    char name[1024];        /* mesh name, or the PLY path relative to the main file */
    char material[SCENE_NAME_LIMIT];
    Affine ctm;             /* at the shape, in the definition */
} PbrtInstanceShape;

typedef struct {
    char name[SCENE_NAME_LIMIT];
    PbrtInstanceShape *shapes;
    int count;
} PbrtObjectDef;

/* A pbrt named texture as pt can use it: a constant, or a pt texture times a constant. */
typedef struct {
    char name[SCENE_NAME_LIMIT];
    bool is_float;          /* pbrt keeps float and spectrum textures apart */
    char pt_texture[SCENE_NAME_LIMIT]; /* "" when constant */
    float value[3];         /* the constant, or what the texture is multiplied by */
} PbrtTexture;

typedef struct {
    PbrtReader *reader;
    const char *path;       /* the main file */
    ImportedScene *out;
    Error *err;
    const char *file;       /* the current directive's file and line, for messages */
    int line;
    cJSON *objects, *materials, *textures, *lights, *camera, *film, *render;
    cJSON *variants; /* shape material variants: key -> material name (not part of the scene) */
    Affine pt_from_pbrt;
    PbrtState state;
    PbrtState stack[64];
    int depth;
    bool in_world;
    bool ignore_transforms; /* ActiveTransform EndTime: motion is not imported */
    Affine camera_from_world; /* the CTM at Camera */
    bool has_camera;
    PbrtParams camera_params;
    struct { char name[SCENE_NAME_LIMIT]; Affine ctm; } *coord_systems;
    int num_coord_systems;
    PbrtTexture *pbrt_textures;
    int num_pbrt_textures;
    PbrtObjectDef *defs;
    int num_defs;
    int current_def;        /* index in defs while inside ObjectBegin, else -1 */
    int num_meshes, num_materials, num_pt_textures;
    char (*warned)[160];    /* warn-once keys */
    int num_warned;
} PbrtImport;

/* Failure naming the current directive's file and line. Returns false. */
bool pbrt_fail(PbrtImport *imp, int line, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
/* One warning per key per import ("file:line: ..."). */
void pbrt_warn_once(PbrtImport *imp, const char *key, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
/* Warns once for each parameter no reader looked at. */
void pbrt_warn_unused(PbrtImport *imp, const char *directive, const char *type, PbrtParams *params);

/* Parameter readers: default when absent; false (err set) on a wrong type. */
bool pbrt_float(PbrtImport *imp, PbrtParams *p, const char *name, float fallback, float *out);
bool pbrt_int(PbrtImport *imp, PbrtParams *p, const char *name, int fallback, int *out);
bool pbrt_bool(PbrtImport *imp, PbrtParams *p, const char *name, bool fallback, bool *out);
/* A string parameter, or NULL. */
const char *pbrt_string(PbrtImport *imp, PbrtParams *p, const char *name, bool *ok);
/* A point3/vector3/normal (3 numbers), false when absent (ok stays true) or wrong. */
bool pbrt_vec3(PbrtImport *imp, PbrtParams *p, const char *name, const float fallback[3], float out[3]);
/* A spectrum-valued parameter (rgb, spectrum (named or sampled), blackbody, float grey) as RGB.
 * kind: "reflectance", "illuminant", "eta" or "k": named spectra are looked up accordingly. */
bool pbrt_spectrum_rgb(PbrtImport *imp, PbrtParam *param, const char *kind, float out[3]);
/* A relative path named in the file, checked to stay inside its folder; the JSON keeps it
 * relative (scene_import.h). */
bool pbrt_check_path(PbrtImport *imp, const char *name, const char *what, int line);

/* The object's matrix as pt's JSON transform: pt_from_pbrt ctm. */
cJSON *pbrt_matrix_json(const PbrtImport *imp, const Affine *ctm);

/* Shape "..." at the current state (import_pbrt_shapes.c). */
bool pbrt_shape(PbrtImport *imp, const char *type, PbrtParams *params);
/* ObjectInstance: each shape of the definition placed by ctm. */
bool pbrt_place_instance(PbrtImport *imp, const PbrtObjectDef *def, const Affine *ctm);

/* Material / MakeNamedMaterial / Texture (import_pbrt_materials.c). name: the pt material to
 * create (unique). */
bool pbrt_material(PbrtImport *imp, const char *name, const char *type, PbrtParams *params);
bool pbrt_texture(PbrtImport *imp, const char *name, const char *value_type, const char *type,
                  PbrtParams *params);
/* A pbrt texture by name, of the kind wanted (float or spectrum) if there is one, else of the
 * other; NULL when none (import_pbrt_textures.c). */
PbrtTexture *pbrt_find_texture(PbrtImport *imp, const char *name, bool want_float);
/* A file texture in the JSON (the file checked to stay in the folder); its name into out. */
bool pbrt_add_file_texture(PbrtImport *imp, const char *file, const char *encoding, int line,
                           char out[SCENE_NAME_LIMIT]);
/* The pt material a shape uses: the state's material with the shape's emission and opacity
 * (cached per combination). emission NULL: none. */
bool pbrt_shape_material(PbrtImport *imp, const float *emission, PbrtParams *shape_params,
                         char out[SCENE_NAME_LIMIT]);

/* LightSource and AreaLightSource (import_pbrt_lights.c), the camera at the end. */
bool pbrt_light(PbrtImport *imp, const char *type, PbrtParams *params);
bool pbrt_area_light(PbrtImport *imp, const char *type, PbrtParams *params);
bool pbrt_camera_json(PbrtImport *imp, cJSON *root);
/* LightSource "infinite" (import_pbrt_environment.c). */
bool pbrt_infinite_light(PbrtImport *imp, PbrtParams *params);

/* Transforms and the graphics state (import_pbrt_transforms.c). *handled: word was a transform
 * directive. coord_system: define (CoordinateSystem) or restore (CoordSysTransform) name. */
bool pbrt_transform_directive(PbrtImport *imp, const char *word, bool *handled);
bool pbrt_coord_system(PbrtImport *imp, const char *name, bool define);
bool pbrt_push_state(PbrtImport *imp, const char *directive);
bool pbrt_pop_state(PbrtImport *imp, const char *directive, bool transform_only);

#endif
