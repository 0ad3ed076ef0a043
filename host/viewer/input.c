// SPDX-License-Identifier: MIT
#include "viewer/input.h"

#include <string.h>

static ViewerInput *input_of(GLFWwindow *window) { return glfwGetWindowUserPointer(window); }

/* Letters by key position (GLFW names them after the US layout), so WASD stays under the left hand
 * on any layout; Ctrl+S saves because plain S is the fly-backward key. */
static void on_key(GLFWwindow *window, int key, int scancode, int action, int mods)
{
    (void)scancode;
    ViewerInput *in = input_of(window);
    if (action != GLFW_PRESS)
        return;
    switch (key) {
    case GLFW_KEY_ESCAPE: glfwSetWindowShouldClose(window, GLFW_TRUE); break;
    case GLFW_KEY_P: in->actions |= VIEWER_PAUSE; break;
    case GLFW_KEY_R: in->actions |= VIEWER_RESET; break;
    case GLFW_KEY_F: in->actions |= VIEWER_FOCUS; break;
    case GLFW_KEY_C: in->actions |= VIEWER_PRINT_CAMERA; break;
    case GLFW_KEY_H: in->actions |= VIEWER_HELP; break;
    case GLFW_KEY_S:
        if (mods & GLFW_MOD_CONTROL)
            in->actions |= VIEWER_SAVE;
        break;
    default: break;
    }
}

/* + - [ ] by the character typed (their keys move between layouts); auto-repeat applies. */
static void on_char(GLFWwindow *window, unsigned int codepoint)
{
    ViewerInput *in = input_of(window);
    switch (codepoint) {
    case '+': case '=': in->exposure_steps++; break;
    case '-': case '_': in->exposure_steps--; break;
    case ']': in->aperture_steps++; break;
    case '[': in->aperture_steps--; break;
    default: break;
    }
}

static void on_mouse_button(GLFWwindow *window, int button, int action, int mods)
{
    (void)mods;
    ViewerInput *in = input_of(window);
    bool pressed = action == GLFW_PRESS;
    if (button == GLFW_MOUSE_BUTTON_LEFT)
        in->orbiting = pressed;
    else if (button == GLFW_MOUSE_BUTTON_RIGHT)
        in->panning = pressed;
    glfwGetCursorPos(window, &in->cursor_x, &in->cursor_y);
}

static void on_cursor(GLFWwindow *window, double x, double y)
{
    ViewerInput *in = input_of(window);
    double dx = x - in->cursor_x, dy = y - in->cursor_y;
    in->cursor_x = x, in->cursor_y = y;
    if (in->orbiting)
        in->orbit_dx += dx, in->orbit_dy += dy;
    else if (in->panning)
        in->pan_dx += dx, in->pan_dy += dy;
}

static void on_scroll(GLFWwindow *window, double x_offset, double y_offset)
{
    (void)x_offset;
    input_of(window)->dolly_steps += y_offset;
}

static void on_framebuffer_size(GLFWwindow *window, int width, int height)
{
    (void)width, (void)height;
    input_of(window)->resized = true;
}

void viewer_input_attach(GLFWwindow *window, ViewerInput *input)
{
    memset(input, 0, sizeof *input);
    glfwSetWindowUserPointer(window, input);
    glfwSetKeyCallback(window, on_key);
    glfwSetCharCallback(window, on_char);
    glfwSetMouseButtonCallback(window, on_mouse_button);
    glfwSetCursorPosCallback(window, on_cursor);
    glfwSetScrollCallback(window, on_scroll);
    glfwSetFramebufferSizeCallback(window, on_framebuffer_size);
    glfwGetCursorPos(window, &input->cursor_x, &input->cursor_y);
}

void viewer_input_clear(ViewerInput *in)
{
    in->actions = 0;
    in->exposure_steps = in->aperture_steps = 0;
    in->orbit_dx = in->orbit_dy = in->pan_dx = in->pan_dy = in->dolly_steps = 0.0;
    in->resized = false;
}

bool viewer_input_fly(GLFWwindow *window, float move[3], bool *fast)
{
    bool ctrl = glfwGetKey(window, GLFW_KEY_LEFT_CONTROL) == GLFW_PRESS ||
                glfwGetKey(window, GLFW_KEY_RIGHT_CONTROL) == GLFW_PRESS;
    *fast = glfwGetKey(window, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS ||
            glfwGetKey(window, GLFW_KEY_RIGHT_SHIFT) == GLFW_PRESS;
    static const struct { int key, axis; float sign; } fly_keys[] = {
        {GLFW_KEY_D, 0, 1.0f}, {GLFW_KEY_A, 0, -1.0f}, {GLFW_KEY_E, 1, 1.0f},
        {GLFW_KEY_Q, 1, -1.0f}, {GLFW_KEY_W, 2, 1.0f}, {GLFW_KEY_S, 2, -1.0f},
    };
    move[0] = move[1] = move[2] = 0.0f;
    bool any = false;
    for (size_t i = 0; i < sizeof fly_keys / sizeof fly_keys[0] && !ctrl; i++)
        if (glfwGetKey(window, fly_keys[i].key) == GLFW_PRESS) {
            move[fly_keys[i].axis] += fly_keys[i].sign;
            any = true;
        }
    return any;
}

void viewer_input_print_help(FILE *out)
{
    fputs("pt view keys:\n"
          "  left drag       orbit around the target\n"
          "  right drag      pan\n"
          "  scroll          dolly toward / away from the target\n"
          "  W A S D, Q E    fly forward, left, back, right, down, up (Shift: 4x faster)\n"
          "  P               pause / resume sampling\n"
          "  R               reset the film\n"
          "  + / -           exposure up / down half a stop\n"
          "  F               focus on the point under the cursor (thin lens)\n"
          "  [ / ]           aperture smaller / larger (0 = pinhole)\n"
          "  Ctrl+S          save the film as PNG + EXR (out/<scene>-view-N, never overwriting)\n"
          "  C               print the camera as JSON to paste into a scene\n"
          "  H               this list\n"
          "  Esc             quit\n",
          out);
    fflush(out);
}
