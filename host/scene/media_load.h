/* SPDX-License-Identifier: MIT */
/* media_load.h: the description's media put into SceneData (shared/DESIGN.md "Media"): the "media"
 * block in its order (slot k is media[k - 1]; grid media read their files here), the world's and
 * the camera's medium, and the walk media of the JSON principled materials with subsurface. */
#ifndef PT_MEDIA_LOAD_H
#define PT_MEDIA_LOAD_H

#include <stdbool.h>

#include "base/error.h"
#include "scene/scene_types.h"

/* Call after the JSON materials are data's materials 0..d->num_materials - 1 and before any
 * other medium is added. Errors name d->path and the key ("scene.json: media.smoke.file: ..."). */
bool media_load(SceneData *data, const SceneDesc *d, Error *err);

#endif
