// SPDX-License-Identifier: MIT
/* program_features.c: a program's feature set (cl/shared/features.h) as the build options that
 * specialise it and as words for people. Both walk the one list, so a new feature needs no code
 * here. */
#include "device/device.h"

#include <stdio.h>
#include <string.h>

void program_features_options(ProgramFeatures features, char out[PROGRAM_FEATURE_OPTIONS_SIZE])
{
    /* Every feature is named, on or off: kernels then fail to compile on a misspelt name rather
     * than take a default (features.h PT_FEATURE). */
    const size_t size = PROGRAM_FEATURE_OPTIONS_SIZE; /* (the list cannot expand inside itself) */
    size_t used = (size_t)snprintf(out, size, " -DPT_FEATURES_GIVEN");
#define PT_FEATURE_OPTION(name, word)                                                              \
    used += (size_t)snprintf(out + used, size - used, " -DPT_FEATURE_" #name "=%d",               \
                             (features & FEATURE_##name) != 0);
    PROGRAM_FEATURES(PT_FEATURE_OPTION)
#undef PT_FEATURE_OPTION
}

void program_features_summary(ProgramFeatures features, char out[PROGRAM_FEATURE_SUMMARY_SIZE])
{
    features &= PROGRAM_FEATURES_ALL;
    if (features == PROGRAM_FEATURES_ALL || features == 0) {
        strcpy(out, features ? "all" : "none");
        return;
    }
    const size_t size = PROGRAM_FEATURE_SUMMARY_SIZE; /* (the list cannot expand inside itself) */
    size_t used = 0;
    out[0] = '\0';
#define PT_FEATURE_WORD(name, word)                                                                \
    if (features & FEATURE_##name)                                                                 \
        used += (size_t)snprintf(out + used, size - used, "%s%s", used ? ", " : "", word);
    PROGRAM_FEATURES(PT_FEATURE_WORD)
#undef PT_FEATURE_WORD
}
