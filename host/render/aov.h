/* SPDX-License-Identifier: MIT */
/* aov.h: first-hit AOVs (albedo, normal, depth) through the render_aov kernel. */
#ifndef PT_AOV_H
#define PT_AOV_H

#include "device/device.h"
#include "scene/scene.h"
#include "render/scene_upload.h"

/* aov: AOV_*; rgb: width * height * 3 floats, row 0 at the top. */
void aov_render(Device *dev, const Scene *scene, const SceneBuffers *buffers, unsigned aov, int spp,
                unsigned seed, float *rgb);

#endif
