// SPDX-License-Identifier: MIT
#include "viewer/pacing.h"

uint32_t viewer_window_for_rate(double paths_per_second)
{
    double wanted = paths_per_second * FRAME_BUDGET_S / WINDOWS_PER_FRAME;
    uint32_t window = VIEWER_MIN_WINDOW;
    while (window < VIEWER_MAX_WINDOW && 2.0 * window <= wanted)
        window *= 2;
    return window;
}
