// SPDX-License-Identifier: MIT
/* The viewer's pacing (host/viewer/pacing.h): a window, the step that cannot be interrupted, takes
 * at most a third of the frame budget at the measured rate, on a slow CPU as on a GPU. */
#include <criterion/criterion.h>

#include "viewer/pacing.h"

static void expect_paced(double rate)
{
    uint32_t window = viewer_window_for_rate(rate);
    double limit = rate * FRAME_BUDGET_S / WINDOWS_PER_FRAME;
    cr_expect(window >= VIEWER_MIN_WINDOW && window <= VIEWER_MAX_WINDOW, "window %u", window);
    cr_expect((window & (window - 1)) == 0, "window %u is not a power of two", window);
    if (window > VIEWER_MIN_WINDOW)
        cr_expect(window <= limit, "%u samples take longer than a third of a frame at %g/s", window,
                  rate);
    if (window < VIEWER_MAX_WINDOW)
        cr_expect(2.0 * window > limit, "%u samples: the next power of two fits too (%g/s)", window,
                  rate);
}

Test(viewer_pacing, a_window_is_a_third_of_a_frame_at_any_rate)
{
    const double rates[] = {0.0, 1e4, 3e5, 1.26e6, 4e7, 8.2e8, 1e12};
    for (size_t i = 0; i < sizeof rates / sizeof rates[0]; i++)
        expect_paced(rates[i]);
    /* PoCL here (about 1.3 M paths/s): 16384 samples, 13 ms; an H100 (820 M/s): 8M samples. */
    cr_expect_eq(viewer_window_for_rate(1.26e6), 16384u);
    cr_expect_eq(viewer_window_for_rate(8.2e8), 1u << 23);
}
