/* SPDX-License-Identifier: MIT */
/* sampler.h: the samplers' names (render.sampler in the scene, --sampler on the command line),
 * from the SAMPLERS list of cl/shared/render.h. */
#ifndef PT_SAMPLER_H
#define PT_SAMPLER_H

#include <stdbool.h>
#include <string.h>

#include "base/shared_types.h"

/* "sobol", "independent"; NULL for SAMPLER_DEFAULT or out of range. */
static inline const char *sampler_name(int sampler)
{
#define PT_SAMPLER_WORD(name, word) word,
    static const char *const words[] = {NULL, SAMPLERS(PT_SAMPLER_WORD)};
#undef PT_SAMPLER_WORD
    return sampler > 0 && sampler < SAMPLER_COUNT ? words[sampler] : NULL;
}

static inline bool sampler_from_name(const char *name, int *out)
{
    for (int s = 1; s < SAMPLER_COUNT; s++)
        if (!strcmp(name, sampler_name(s))) {
            *out = s;
            return true;
        }
    return false;
}

/* What a render with `asked` (a setting, 0 = not given) and the scene's `scene_sampler` uses:
 * the setting, else the scene's, else Sobol (it cuts the error at equal time: bench/README.md). */
static inline int sampler_resolve(int asked, int scene_sampler)
{
    return asked ? asked : scene_sampler ? scene_sampler : SAMPLER_SOBOL;
}

#endif
