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
    VIEWER_NEXT_TONEMAP = 1 << 6, /* T: the next tone-map curve */
    VIEWER_DENOISE = 1 << 7,      /* Ctrl+D: the denoised view on or off */
};

typedef struct {
    unsigned actions;            /* VIEWER_* bits */
    int exposure_steps;          /* +/-: half stops */
    int aperture_steps;          /* ]/[: lens wider or narrower */
    int environment_steps;       /* . / ,: the environment map turned by 15 degrees */
    double orbit_dx, orbit_dy;   /* left drag, window pixels */
    double pan_dx, pan_dy;       /* right drag, window pixels */
    double dolly_steps;          /* scroll, positive = closer */
    bool resized;                /* the framebuffer changed size */
    /* Drag and key state (kept across frames). */
    bool orbiting, panning;
    double cursor_x, cursor_y;   /* from the last cursor event, in window coordinates */
    unsigned held;               /* VIEWER_HELD_* bits: fly keys, Shift, Ctrl, by their events */
    bool print_events;           /* --events: a line on stdout per event read (scripts, tests) */
} ViewerInput;

/* Keys held down, as bits of ViewerInput.held. A fly key counts only when it was pressed without
 * Ctrl: Ctrl+S saves, and Ctrl may be let go before S (xdotool does), which must not fly. */
enum {
    VIEWER_HELD_RIGHT = 1 << 0, VIEWER_HELD_LEFT = 1 << 1, VIEWER_HELD_UP = 1 << 2,
    VIEWER_HELD_DOWN = 1 << 3, VIEWER_HELD_FORWARD = 1 << 4, VIEWER_HELD_BACK = 1 << 5,
    VIEWER_HELD_SHIFT = 1 << 6, VIEWER_HELD_CTRL = 1 << 7,
};

/* Installs the callbacks; `input` must outlive the window. print_events: --events. */
void viewer_input_attach(GLFWwindow *window, ViewerInput *input, bool print_events);
/* Clears what was consumed (keeps the drag and key state). */
void viewer_input_clear(ViewerInput *input);

/* Records a key event (GLFW key, action and mods) as the key callback does; Esc is the
 * callback's (it closes the window). Separate from the window so that tests can replay events. */
void viewer_input_key(ViewerInput *input, int key, int action, int mods);

/* Held fly keys: move = (right, up, forward) in {-1, 0, 1}; true when any is held. *fast when
 * Shift is held. Ignored while Ctrl is held (Ctrl+S saves). */
bool viewer_input_fly(const ViewerInput *input, float move[3], bool *fast);

void viewer_input_print_help(FILE *out);

/* --events: "event: " and the formatted text as a line on stdout, flushed, when input asks for
 * them. Input events are printed as they are read; their effect is applied (apply_input in
 * viewer.c) before the next is read, so a script that waits for the line may send the next. */
void viewer_print_event(const ViewerInput *input, const char *format, ...)
    __attribute__((format(printf, 2, 3)));

#endif
