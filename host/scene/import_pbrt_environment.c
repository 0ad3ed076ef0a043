// SPDX-License-Identifier: MIT
/* import_pbrt_environment.c: pbrt-v4's "infinite" light. A constant L x scale becomes pt's
 * "background". An image ("filename") in pbrt-v4 is an equal-area octahedral square map, which pt's
 * environment (a lat-long map, DESIGN.md "Environment") cannot read: it is left out with a warning
 * naming the file, and the rest of the scene renders ("portal" is ignored with a warning). */
#include <stdio.h>
#include <string.h>

#include "scene/import_pbrt_internal.h"

bool pbrt_infinite_light(PbrtImport *imp, PbrtParams *p)
{
    bool ok = true;
    const char *file = pbrt_string(imp, p, "filename", &ok);
    float scale;
    if (!ok || !pbrt_float(imp, p, "scale", 1.0f, &scale))
        return false;
    if (pbrt_param(p, "portal"))
        pbrt_warn_once(imp, "portal", "LightSource \"infinite\": \"portal\" is ignored");
    if (pbrt_param(p, "illuminance"))
        pbrt_warn_once(imp, "illuminance", "LightSource \"infinite\": \"illuminance\" is not imported (scale used)");
    if (file) {
        if (!pbrt_check_path(imp, file, "LightSource \"infinite\" \"filename\"", imp->line))
            return false;
        pbrt_warn_once(imp, "equal-area", "LightSource \"infinite\": \"%s\" is an equal-area "
                       "octahedral map, which pt does not convert yet: the environment is left out", file);
        return true;
    }
    float l[3] = {1.0f, 1.0f, 1.0f};
    PbrtParam *q = pbrt_param(p, "L");
    if (q && !pbrt_spectrum_rgb(imp, q, "illuminant", l))
        return false;
    cJSON *root = imp->out->root;
    cJSON_DeleteItemFromObject(root, "background");
    cJSON_AddItemToObject(root, "background",
                          cJSON_CreateDoubleArray((double[]){l[0] * scale, l[1] * scale, l[2] * scale}, 3));
    return true;
}
