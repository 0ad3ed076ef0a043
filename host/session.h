/* SPDX-License-Identifier: MIT */
/* session.h: what every command that renders needs: the scene loaded and flattened, a device with
 * the program built, the BVH, and the scene's buffers on the device. */
#ifndef PT_SESSION_H
#define PT_SESSION_H

#include "bvh.h"
#include "cli.h"
#include "device.h"
#include "scene.h"
#include "scene_gpu.h"

typedef struct {
    Scene scene;
    Device dev;
    Bvh bvh;
    SceneBuffers buffers;
    double load_seconds, bvh_seconds; /* dev.build_seconds has the kernel build */
} Session;

/* Loads o->scene, applies the command-line overrides (film, spp, depth), opens o->device. */
bool session_open(Session *s, const Options *o, Error *err);
void session_print_summary(const Session *s);
void session_close(Session *s);

#endif
