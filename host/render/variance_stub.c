// SPDX-License-Identifier: MIT
/* variance_stub.c: STUB, to be deleted when the adaptive-sampling branch (issue 19 item 3) lands:
 * its wavefront_read_variance reads the film's sums of squares. Until then the variance AOV is
 * zeros and the call says so (false). */
#include "render/aov.h"

#include <string.h>

bool wavefront_read_variance(Wavefront *w, float *rgb)
{
    const Film *film = wavefront_film(w);
    memset(rgb, 0, (size_t)film->num_pixels * 3 * sizeof *rgb);
    return false;
}
