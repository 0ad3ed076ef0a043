/* SPDX-License-Identifier: MIT */
/* viewer_input.h: what the user asked for since the last frame. GLFW's callbacks only record
 * (drags, scroll, key presses, resizes); the frame loop reads and clears the record once a frame,
 * so no rendering state is touched from inside a callback. */
#ifndef PT_VIEWER_INPUT_H
#define PT_VIEWER_INPUT_H

#include <stdbool.h>
#include <stdio.h>

#include <GLFW/glfw3.h>

/* One-shot commands, as bits of ViewerInput.actions. */
enum {
    VIEWER_PAUSE = 1 << 0,        /* P: stop or resume adding samples */
    VIEWER_RESET = 1 << 1,        /* R: empty the film */
    VIEWER_FOCUS = 1 << 2,        /* F: focus on the point under the cursor */
    VIEWER_SAVE = 1 << 3,         /* Ctrl+S: PNG + EXR of the film */
    VIEWER_PRINT_CAMERA = 1 << 4, /* C: the camera as JSON on stdout */
    VIEWER_HELP = 1 << 5,         /* H: the key list */
};

typedef struct {
    unsigned actions;            /* VIEWER_* bits */
    int exposure_steps;          /* +/-: half stops */
    int aperture_steps;          /* ]/[: lens wider or narrower */
    double orbit_dx, orbit_dy;   /* left drag, window pixels */
    double pan_dx, pan_dy;       /* right drag, window pixels */
    double dolly_steps;          /* scroll, positive = closer */
    bool resized;                /* the framebuffer changed size */
    /* Drag state (kept across frames). */
    bool orbiting, panning;
    double cursor_x, cursor_y;
} ViewerInput;

/* Installs the callbacks; `input` must outlive the window. */
void viewer_input_attach(GLFWwindow *window, ViewerInput *input);
/* Clears what was consumed (keeps the drag state). */
void viewer_input_clear(ViewerInput *input);

/* Held fly keys: move = (right, up, forward) in {-1, 0, 1}; true when any is held. *fast when
 * Shift is held. Ignored while Ctrl is held (Ctrl+S saves). */
bool viewer_input_fly(GLFWwindow *window, float move[3], bool *fast);

void viewer_input_print_help(FILE *out);

#endif
