/* SPDX-License-Identifier: MIT */
/* session.h: what every command that renders needs: the scene loaded and flattened, a device with
 * the program built, the BVH, and the scene's buffers on the device. */
#ifndef PT_SESSION_H
#define PT_SESSION_H

#include "accel/scene_bvh.h"
#include "device/device.h"
#include "scene/scene.h"
#include "render/scene_upload.h"
#include "render/wavefront.h"

/* What to render and where: the scene file, the device, and overrides of the scene's settings
 * (zero keeps the scene's value). Commands fill it from their command line. */
typedef struct {
    const char *scene;  /* a .json scene, a bare .obj, or a folder holding scene.json */
    const char *device; /* gpu|cpu|P:D; NULL = the default device */
    int width, height, spp, max_depth;
    bool no_cache;      /* compile the kernels even if the kernel cache has them */
    bool no_default_light; /* leave a scene without any light dark (scene_add_default_light) */
    int instancing;     /* InstancingMode (scene/scene.h); 0 = INSTANCING_AUTO */
    const char *camera_json; /* pt render --camera: replaces the scene's camera; NULL = keep it */
    bool no_ground;     /* the default rig without its ground (--no-ground) */
    bool frame;         /* frame the model even when the file has a camera (--frame) */
    int up_axis;        /* UpAxis (scene/camera.h) of the framing and the rig (--up) */
} RenderDesc;

typedef struct {
    Scene scene;
    Device dev;
    SceneBvh bvh;
    SceneBuffers buffers;
    double load_seconds, bvh_seconds; /* dev.build_seconds has the kernel build */
} Session;

/* Loads desc->scene, applies the overrides (film, spp, depth), opens desc->device. */
bool session_open(Session *s, const RenderDesc *desc, Error *err);
void session_print_summary(const Session *s);
/* One more device for a render on several (dist/render_units.c): like the session's own, its
 * program built for the scene's features, the BVH in its layout and the scene's buffers on it. */
typedef struct {
    Device dev;
    SceneBvh bvh;
    SceneBuffers buffers;
} SessionDevice;
bool session_device_open(SessionDevice *d, const Scene *scene, const char *spec, bool no_cache,
                         Error *err);
void session_device_close(SessionDevice *d);
/* Material sorting (RenderSettings.sort_materials) for a request: SORT_MATERIALS_ON / _OFF as
 * asked, SORT_MATERIALS_AUTO when the scene uses any material feature beyond Lambert, smooth
 * mirrors and glass (scene/materials.h material_features) and its materials take more than one
 * way through shading (type and features; materials that scatter nothing, lamps, left out): on the H200 sorting
 * made such scenes 11% (env-lit rough gold) to 63% (rough gold, rough glass, normal maps) faster
 * and v1's plain Cornell box about a quarter slower (the textured scene about a tenth). */
enum { SORT_MATERIALS_AUTO = 0, SORT_MATERIALS_ON = 1, SORT_MATERIALS_OFF = 2 };
bool session_sorts_materials(const SceneData *data, int request);
/* The scene's part of settings asked for on the command line: spp 0 becomes the scene's (with
 * the session's override), max_depth the scene's, sort_materials session_sorts_materials of
 * sort_request. */
void session_settle_settings(const Session *s, RenderSettings *settings, int sort_request);
void session_close(Session *s);

#endif
