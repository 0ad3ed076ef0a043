/* SPDX-License-Identifier: MIT */
/* mitsuba_internal.h: what the parts of the Mitsuba 3 importer share: the import's state, the
 * property readers (mitsuba_values.c, mitsuba_transform.c), textures and parameters
 * (mitsuba_texture.c), BSDFs (mitsuba_bsdf.c), shapes and emitters (mitsuba_shapes.c), the
 * sensor and integrator (mitsuba_sensor.c). Private to scene/import_mitsuba*.c and
 * scene/mitsuba_*.c. */
#ifndef PT_MITSUBA_INTERNAL_H
#define PT_MITSUBA_INTERNAL_H

#include <stdbool.h>

#include "base/transform.h"
#include "io/xml_tree.h"
#include "scene/scene_import.h"

/* An element with an id (or a bsdf/texture already mapped): what it became. */
typedef struct {
    const XmlElement *element;
    const char *file; /* the document it is in */
    char name[SCENE_NAME_LIMIT]; /* the pt material or texture; "" until mapped */
} MitsubaNamed;

typedef struct {
    const char *path;  /* the imported file */
    const char *file;  /* the document being read (the imported file or an <include>d one) */
    Error *err;
    ImportedScene *out;
    cJSON *materials, *textures, *objects, *lights;
    XmlElement **documents; /* the main document and the included ones, freed at the end */
    int num_documents;
    const char **document_paths;
    MitsubaNamed *ids; /* elements with an id attribute (refs) */
    int num_ids;
    MitsubaNamed *mapped; /* bsdfs and textures already mapped, by element */
    int num_mapped;
    char (*warned)[64]; /* each dropped thing is warned about once */
    int num_warned;
    int next_name; /* generated names: "bsdf_3", "texture_7" */
    char **define_names, **define_values; /* -D first, then <default>s (the first one counts) */
    int num_defines;
    bool old_version; /* version < 2: camelCase property names (Mitsuba upgrades them) */
    int include_depth;
    int width, height; /* the film (for fov_axis) */
    bool has_sensor, has_emitter_background, has_environment;
} Mitsuba;

/* ---- mitsuba_values.c ---- */
/* One line: "file:line: <tag type=...>: message"; returns false. */
bool mi_fail(Mitsuba *m, const XmlElement *e, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
/* One warning per distinct key (a plugin name, a property) with the element's file:line. */
void mi_warn_once(Mitsuba *m, const XmlElement *e, const char *key, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
/* The child property element called name (marked used), or NULL. */
XmlElement *mi_prop(Mitsuba *m, const XmlElement *e, const char *name);
bool mi_float(Mitsuba *m, const XmlElement *e, const char *name, double fallback, double *out);
bool mi_int(Mitsuba *m, const XmlElement *e, const char *name, int fallback, int *out);
bool mi_bool(Mitsuba *m, const XmlElement *e, const char *name, bool fallback, bool *out);
/* NULL when absent (fallback returned) */
const char *mi_string(Mitsuba *m, const XmlElement *e, const char *name, const char *fallback);
bool mi_parse_number(Mitsuba *m, const XmlElement *e, const char *attribute, double *out);
/* text "a, b, c" or "a b c": exactly n numbers (e is for messages). */
bool mi_parse_list(Mitsuba *m, const XmlElement *e, const char *text, double *out, int n);
/* A <rgb>, <spectrum>, <float> element's colour. */
bool mi_spectrum_rgb(Mitsuba *m, const XmlElement *e, double rgb[3]);
/* A <point>/<vector> property (x y z attributes or value="x, y, z"). */
bool mi_point(Mitsuba *m, const XmlElement *e, const char *name, const double fallback[3], double out[3]);
/* A <transform name=...> property (mitsuba_transform.c): its operations composed as Mitsuba
 * does (each one left-multiplies what came before); identity when absent. */
bool mi_transform(Mitsuba *m, const XmlElement *e, const char *name, Affine *out);
/* Warns about the properties of e nobody read. */
void mi_warn_unused(Mitsuba *m, const XmlElement *e);
/* The element an <ref id=...> names (and its document in *file), or NULL after mi_fail. */
const MitsubaNamed *mi_find_id(Mitsuba *m, const XmlElement *ref);
/* A fresh name "prefix_N" (or the element's id when it has one and it is free). */
void mi_new_name(Mitsuba *m, const XmlElement *e, const char *prefix, char out[SCENE_NAME_LIMIT]);
/* file (named inside the current document) as a path relative to the imported file's folder,
 * checked by fs_resolve_inside. */
bool mi_file(Mitsuba *m, const XmlElement *e, const char *file, char *out, size_t size);
cJSON *mi_rgb_json(const double rgb[3]);
cJSON *mi_matrix_transform(const Affine *a); /* [{"matrix": [...]}] */

/* ---- mitsuba_texture.c ---- */
/* What element e (a bsdf or texture) was mapped to, or NULL; mi_remember records it. */
const MitsubaNamed *mi_find_mapped(const Mitsuba *m, const XmlElement *e);
bool mi_remember(Mitsuba *m, const XmlElement *e, const char *name);
/* The start of every element mapper (mi_bsdf, mi_medium): a <ref> is followed to its element,
 * which must be a <tag>, and mapped there by map (*done, false on error); an element already
 * mapped gives its name (*done). Otherwise *done is false and the caller maps e. */
bool mi_follow(Mitsuba *m, const XmlElement *e, const char *tag,
               bool (*map)(Mitsuba *, const XmlElement *, char[SCENE_NAME_LIMIT]),
               char out[SCENE_NAME_LIMIT], bool *done);
/* A colour parameter: rgb/spectrum/float (a JSON array) or a texture (its JSON name); the
 * fallback grey when absent. *out NULL after a failure. */
bool mi_colour(Mitsuba *m, const XmlElement *e, const char *name, double fallback, cJSON **out);
/* A scalar parameter: a number or a texture name. */
bool mi_scalar(Mitsuba *m, const XmlElement *e, const char *name, double fallback, cJSON **out);
/* A texture element (or ref) as a pt texture named out (*is_texture), or, for one pt cannot read,
 * the colour to use instead (mean); linear: raw texels (normal maps). */
bool mi_texture(Mitsuba *m, const XmlElement *e, bool linear, char out[SCENE_NAME_LIMIT], double mean[3],
                bool *is_texture);

/* ---- mitsuba_bsdf.c ---- */
/* A <bsdf> (or a <ref> to one) as a pt material; its name in out. */
bool mi_bsdf(Mitsuba *m, const XmlElement *e, char out[SCENE_NAME_LIMIT]);

/* ---- mitsuba_sensor.c ---- */
bool mi_sensor(Mitsuba *m, const XmlElement *e, cJSON *root, cJSON *render);
bool mi_integrator(Mitsuba *m, const XmlElement *e, cJSON *render);

/* ---- mitsuba_shapes.c ---- */
bool mi_shape(Mitsuba *m, const XmlElement *e, const Affine *parent);
bool mi_emitter(Mitsuba *m, const XmlElement *e);

/* ---- mitsuba_media.c ---- */
/* Whether child c is a <medium>, a <ref> to one, or a <ref name="interior|exterior">. */
bool mi_is_medium(const Mitsuba *m, const XmlElement *c);
/* A <medium> (or a <ref> to one) as a pt medium in the tree's "media"; its name in out. */
bool mi_medium(Mitsuba *m, const XmlElement *e, char out[SCENE_NAME_LIMIT]);
/* The shape's interior / exterior media as the pt object's keys. */
bool mi_shape_media(Mitsuba *m, const XmlElement *shape, cJSON *object);
/* The sensor's medium as camera.medium. */
bool mi_sensor_medium(Mitsuba *m, const XmlElement *sensor, cJSON *camera);

#endif
