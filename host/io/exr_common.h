/* SPDX-License-Identifier: MIT */
/* exr_common.h: what the EXR reader and writer share: OpenEXR errors turned into Errors, and
 * which of our R, G, B planes a channel name is. */
#ifndef PT_EXR_COMMON_H
#define PT_EXR_COMMON_H

#include <openexr.h>
#include <stdbool.h>

#include "base/error.h"

/* A context initializer whose error callback keeps OpenEXR's detail for exr_ok (instead of
 * printing it to stderr). */
exr_context_initializer_t exr_quiet_initializer(void);

/* Turns a failed exr_* call into an Error naming the file, the step, the error code and detail. */
bool exr_ok(exr_result_t result, const char *step, const char *path, ErrorCode code, Error *err);

/* 0, 1, 2 for the channels "R", "G", "B"; -1 for any other. */
int exr_rgb_index(const char *channel_name);

#endif
