/* SPDX-License-Identifier: MIT */
/* collada_reader.h: a COLLADA 1.4/1.5 (.dae) file read over libxml2 into plain data: its
 * geometries (triangles, polylist, polygons; n-gons by io/triangulate.h), the visual scene's
 * node hierarchy flattened to instances with world matrices (matrix, translate, rotate, scale,
 * lookat; instance_node followed), its cameras, lights and common-profile materials, and the
 * renderer data the UC Berkeley CS184 / CMU 15-462 scenes keep in
 * <extra><technique profile="CGL"> (or "CMU462"): BSDFs, emission, area lights and analytic
 * spheres. Our own reader rather than Assimp: Assimp drops the <extra> blocks, which carry the
 * CS184 scenes' materials, lights and spheres (see the report in scene/import_collada.h).
 * Mapping to pt's scene is scene/import_collada.c's business; nothing here knows pt's JSON. */
#ifndef PT_COLLADA_READER_H
#define PT_COLLADA_READER_H

#include <stdbool.h>

#include "base/error.h"
#include "io/mesh.h"

#define COLLADA_ID_LIMIT 128

/* The CGL technique of an effect, when it has one: what CS184's renderer draws. */
typedef enum {
    CGL_NONE,
    CGL_DIFFUSE,    /* reflectance */
    CGL_MIRROR,     /* reflectance */
    CGL_GLASS,      /* ior, roughness, reflectance, transmittance */
    CGL_MICROFACET, /* alpha, eta, k */
    CGL_EMISSION    /* radiance */
} CglBsdf;

typedef struct {
    char id[COLLADA_ID_LIMIT];  /* the <material>'s id */
    ObjMaterial common;         /* the common profile (constant/lambert/phong/blinn) as MTL terms */
    CglBsdf cgl;
    float reflectance[3], transmittance[3], eta[3], k[3], radiance[3];
    float ior, roughness, alpha;
} ColladaMaterial;

typedef struct {
    char id[COLLADA_ID_LIMIT];
    bool is_sphere;   /* a CGL analytic sphere: radius, no mesh */
    float radius;
    Mesh mesh;        /* material_ids index `symbols`; materials empty */
    char (*symbols)[COLLADA_ID_LIMIT]; /* the primitives' material symbols */
    int num_symbols;
} ColladaGeometry;

typedef enum { COLLADA_LIGHT_POINT, COLLADA_LIGHT_SPOT, COLLADA_LIGHT_DIRECTIONAL,
               COLLADA_LIGHT_AMBIENT, COLLADA_LIGHT_AREA } ColladaLightType;

typedef struct {
    char id[COLLADA_ID_LIMIT];
    ColladaLightType type; /* AREA: the CGL <area> technique (a 1 x 1 square facing local -z) */
    float color[3];
    float falloff_angle;   /* spot: the cone's full angle, degrees (COLLADA default 180) */
    bool attenuated;       /* linear or quadratic attenuation given non-zero */
} ColladaLight;

typedef struct {
    char id[COLLADA_ID_LIMIT];
    bool orthographic;
    float xfov, yfov, aspect; /* degrees; 0 where the file gives none */
} ColladaCamera;

typedef enum { COLLADA_GEOMETRY, COLLADA_CAMERA, COLLADA_LIGHT } ColladaInstanceKind;

typedef struct {
    ColladaInstanceKind kind;
    int index;        /* into geometries, cameras or lights */
    double world[16]; /* row-major, column vectors, in the file's axes (see up_axis) */
    int *bindings;    /* geometry: per symbol, the bound material's index, -1 when unbound */
    char node[COLLADA_ID_LIMIT]; /* the node's id or name, for messages */
} ColladaInstance;

typedef enum { COLLADA_Y_UP, COLLADA_Z_UP, COLLADA_X_UP } ColladaUpAxis;

typedef struct {
    ColladaUpAxis up_axis;
    double meter; /* <unit meter>, 1 when absent */
    bool has_cgl; /* some <technique profile="CGL"|"CMU462">: a CS184 scene */
    ColladaMaterial *materials;
    int num_materials;
    ColladaGeometry *geometries;
    int num_geometries;
    ColladaCamera *cameras;
    int num_cameras;
    ColladaLight *lights;
    int num_lights;
    ColladaInstance *instances;
    int num_instances;
} ColladaDoc;

/* Reads path (a regular file, io/input_file.h). Errors: one line naming the file, the element
 * and its line. Warns once per kind of thing it drops (controllers, textures it cannot follow,
 * unknown CGL techniques...). Texture paths in `common.map_kd` are resolved inside the file's
 * folder (base/fs.h fs_resolve_inside). */
bool collada_read(const char *path, ColladaDoc *doc, Error *err);
/* Reads COLLADA text already in memory; `path` names it in messages and anchors texture paths. */
bool collada_read_memory(const char *path, const char *text, size_t size, ColladaDoc *doc,
                         Error *err);
void collada_free(ColladaDoc *doc);

#endif
