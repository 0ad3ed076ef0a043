/* SPDX-License-Identifier: MIT */
/* image_write.h: what the EXR and PNG writers share: the argument check and the last guard
 * against non-finite values before a file. */
#ifndef PT_IMAGE_WRITE_H
#define PT_IMAGE_WRITE_H

#include <math.h>
#include <stdbool.h>

#include "base/error.h"

static inline float image_finite_or_zero(float value) { return isfinite(value) ? value : 0.0f; }

static inline bool image_check_args(const char *path, const float *rgb, int width, int height,
                                    Error *err)
{
    if (!rgb || width <= 0 || height <= 0) {
        error_set(err, ERR_OUTPUT, path, 0, "%s: cannot write an empty image (%dx%d)",
                  path ? path : "(null)", width, height);
        return false;
    }
    return true;
}

#endif
