/* SPDX-License-Identifier: MIT */
/* collada_internal.h: what the parts of the COLLADA reader share: the reader's state and its id
 * table, the XML and number helpers (collada_xml.c), geometry (collada_geometry.c), materials,
 * effects, the CGL extras, cameras and lights (collada_materials.c). Private to
 * io/collada_*.c. */
#ifndef PT_COLLADA_INTERNAL_H
#define PT_COLLADA_INTERNAL_H

#include <libxml/tree.h>
#include <stdbool.h>
#include <stddef.h>

#include "io/collada_reader.h"

#define COLLADA_FILE_LIMIT ((size_t)2 << 30)
#define NODE_DEPTH_LIMIT 64 /* nested nodes and instance_node chains; also stops cycles */
#define POLYGON_CORNER_LIMIT 4096
#define PI 3.14159265358979323846

typedef struct {
    const char *id;
    xmlNode *node;
} IdEntry;

typedef struct {
    const char *path;
    Error *err;
    ColladaDoc *doc;
    IdEntry *ids;
    size_t num_ids, cap_ids;
    unsigned warned; /* one bit per Drop: each kind of dropped thing is warned about once */
} Reader;

typedef enum { DROP_CONTROLLER, DROP_SKEW, DROP_HOLES, DROP_PRIMITIVE, DROP_GEOMETRY, DROP_CGL,
               DROP_TEXTURE, DROP_ORTHO, DROP_LINES, DROP_REFRACTION } Drop;

/* collada_xml.c */
void collada_warn_once(Reader *r, Drop what, const char *fmt, const char *detail);
bool collada_fail(Reader *r, const xmlNode *at, ErrorCode code, const char *fmt, const char *a,
                  const char *b);
bool collada_is(const xmlNode *n, const char *name);
xmlNode *collada_child(const xmlNode *n, const char *name);
xmlNode *collada_next_named(xmlNode *c, const char *name);
xmlNode *collada_path_child(const xmlNode *n, const char *path);
const char *collada_attr(const xmlNode *n, const char *name);
const char *collada_text(const xmlNode *n);
bool collada_collect_ids(Reader *r, xmlNode *n);
xmlNode *collada_lookup(const Reader *r, const char *url);
size_t collada_read_numbers(const char *s, double *out, size_t n, bool *bad);
bool collada_read_exact(Reader *r, const xmlNode *n, double *out, size_t count);
void collada_color_of(const xmlNode *n, float rgb[3], float *alpha);

/* collada_geometry.c */
xmlNode *collada_cgl_technique(Reader *r, const xmlNode *n, int depth);
bool collada_read_geometry(Reader *r, const xmlNode *geo, ColladaGeometry *g);

/* collada_materials.c */
bool collada_read_material(Reader *r, const xmlNode *mat, ColladaMaterial *m);
void collada_read_camera(Reader *r, const xmlNode *cam, ColladaCamera *c);
void collada_read_light(Reader *r, const xmlNode *light, ColladaLight *l);

#endif
