// SPDX-License-Identifier: MIT
/* The viewer's key state (host/viewer/input.h), replayed without a window: a fly key moves the
 * camera only while it is held from a press without Ctrl. */
#include <criterion/criterion.h>

#include "viewer/input.h"

static bool flies(const ViewerInput *in)
{
    float move[3];
    bool fast;
    return viewer_input_fly(in, move, &fast);
}

/* xdotool's 'key ctrl+s' releases Ctrl before S (as a person may): between the two releases S is
 * held alone, which must not fly (it moved the camera after a save, and emptied the film). */
Test(viewer_input, ctrl_s_saves_and_never_flies_whatever_the_release_order)
{
    ViewerInput in = {0};
    viewer_input_key(&in, GLFW_KEY_LEFT_CONTROL, GLFW_PRESS, 0);
    viewer_input_key(&in, GLFW_KEY_S, GLFW_PRESS, GLFW_MOD_CONTROL);
    cr_expect(in.actions & VIEWER_SAVE, "Ctrl+S saves");
    cr_expect(!flies(&in), "Ctrl+S held");
    viewer_input_key(&in, GLFW_KEY_LEFT_CONTROL, GLFW_RELEASE, GLFW_MOD_CONTROL);
    cr_expect(!flies(&in), "Ctrl let go before S");
    viewer_input_key(&in, GLFW_KEY_S, GLFW_RELEASE, 0);
    cr_expect(!flies(&in) && in.held == 0, "all let go: held %#x", in.held);
}

Test(viewer_input, a_fly_key_flies_while_held_and_shift_makes_it_fast)
{
    ViewerInput in = {0};
    float move[3];
    bool fast;
    viewer_input_key(&in, GLFW_KEY_S, GLFW_PRESS, 0);
    cr_expect(viewer_input_fly(&in, move, &fast) && move[2] == -1.0f && !fast, "S flies back");
    cr_expect(!(in.actions & VIEWER_SAVE), "plain S does not save");
    viewer_input_key(&in, GLFW_KEY_LEFT_SHIFT, GLFW_PRESS, 0);
    viewer_input_key(&in, GLFW_KEY_D, GLFW_PRESS, GLFW_MOD_SHIFT);
    cr_expect(viewer_input_fly(&in, move, &fast) && move[0] == 1.0f && move[2] == -1.0f && fast,
              "S and Shift+D: back, right, fast");
    viewer_input_key(&in, GLFW_KEY_RIGHT_CONTROL, GLFW_PRESS, GLFW_MOD_SHIFT);
    cr_expect(!flies(&in), "Ctrl held stops flying");
    viewer_input_key(&in, GLFW_KEY_RIGHT_CONTROL, GLFW_RELEASE, GLFW_MOD_SHIFT | GLFW_MOD_CONTROL);
    cr_expect(flies(&in), "keys still held fly again once Ctrl is let go");
    viewer_input_key(&in, GLFW_KEY_S, GLFW_RELEASE, GLFW_MOD_SHIFT);
    viewer_input_key(&in, GLFW_KEY_D, GLFW_RELEASE, GLFW_MOD_SHIFT);
    cr_expect(!flies(&in), "released");
}
