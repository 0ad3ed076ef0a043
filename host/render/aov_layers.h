/* SPDX-License-Identifier: MIT */
/* aov_layers.h: the AOV layers `--aov LIST` can add to the EXR beside the beauty R, G, B
 * (shared/DESIGN.md, "Film and outputs"). The list is written once: the command line, the EXR
 * writer's channel names and `pt help` all read it. */
#ifndef PT_AOV_LAYERS_H
#define PT_AOV_LAYERS_H

#include <stdbool.h>
#include <stdio.h>
#include <string.h>

#include "base/error.h"

/* X(ENUM, "layer", "channel suffixes", channel count) */
#define AOV_LAYERS(X)                                                                           \
    X(ALBEDO, "albedo", "RGB", 3)                                                               \
    X(NORMAL, "normal", "XYZ", 3)                                                               \
    X(DEPTH, "depth", "Z", 1)                                                                   \
    X(VARIANCE, "variance", "RGB", 3)                                                           \
    X(SPP, "spp", "Y", 1)

typedef enum {
#define AOV_LAYER_ENUM(e, name, channels, n) AOV_LAYER_##e,
    AOV_LAYERS(AOV_LAYER_ENUM)
#undef AOV_LAYER_ENUM
    AOV_LAYER_COUNT
} AovLayer;

#define AOV_MASK(layer) (1u << (layer))
#define AOV_MASK_ALL ((1u << AOV_LAYER_COUNT) - 1u)

static inline const char *aov_layer_name(AovLayer layer)
{
    static const char *const names[] = {
#define AOV_LAYER_NAME(e, name, channels, n) name,
        AOV_LAYERS(AOV_LAYER_NAME)
#undef AOV_LAYER_NAME
    };
    return (unsigned)layer < AOV_LAYER_COUNT ? names[layer] : "?";
}

/* "albedo,normal" or "all" into a mask of AOV_MASK(layer) bits; false with ERR_USAGE naming the
 * unknown name and listing the known ones. */
static inline bool aov_parse_list(const char *text, unsigned *mask, Error *err)
{
    *mask = 0;
    if (!strcmp(text, "all")) {
        *mask = AOV_MASK_ALL;
        return true;
    }
    const char *p = text;
    for (;;) {
        size_t len = strcspn(p, ",");
        int found = -1;
        for (int l = 0; l < AOV_LAYER_COUNT; l++)
            if (strlen(aov_layer_name((AovLayer)l)) == len &&
                !strncmp(p, aov_layer_name((AovLayer)l), len))
                found = l;
        if (found < 0) {
            char known[128] = "";
            for (int l = 0; l < AOV_LAYER_COUNT; l++)
                snprintf(known + strlen(known), sizeof known - strlen(known), "%s, ",
                         aov_layer_name((AovLayer)l));
            error_set(err, ERR_USAGE, NULL, 0, "--aov: '%.*s' is not an AOV (%sor all)", (int)len,
                      p, known);
            return false;
        }
        *mask |= AOV_MASK(found);
        if (!p[len])
            return true;
        p += len + 1;
    }
}

#endif
