// SPDX-License-Identifier: MIT
#include "viewer/input.h"

#include <stdarg.h>
#include <string.h>

static ViewerInput *input_of(GLFWwindow *window) { return glfwGetWindowUserPointer(window); }

static const char *action_name(int action)
{
    return action == GLFW_PRESS ? "press" : action == GLFW_RELEASE ? "release" : "repeat";
}

void viewer_print_event(const ViewerInput *in, const char *format, ...)
{
    if (!in->print_events)
        return;
    va_list ap;
    va_start(ap, format);
    fputs("event: ", stdout);
    vprintf(format, ap);
    fputc('\n', stdout);
    fflush(stdout);
    va_end(ap);
}

static const struct { int key; unsigned bit; } held_keys[] = {
    {GLFW_KEY_D, VIEWER_HELD_RIGHT},   {GLFW_KEY_A, VIEWER_HELD_LEFT},
    {GLFW_KEY_E, VIEWER_HELD_UP},      {GLFW_KEY_Q, VIEWER_HELD_DOWN},
    {GLFW_KEY_W, VIEWER_HELD_FORWARD}, {GLFW_KEY_S, VIEWER_HELD_BACK},
    {GLFW_KEY_LEFT_SHIFT, VIEWER_HELD_SHIFT}, {GLFW_KEY_RIGHT_SHIFT, VIEWER_HELD_SHIFT},
    {GLFW_KEY_LEFT_CONTROL, VIEWER_HELD_CTRL}, {GLFW_KEY_RIGHT_CONTROL, VIEWER_HELD_CTRL},
};

/* Letters by key position (GLFW names them after the US layout), so WASD stays under the left hand
 * on any layout; Ctrl+S saves and Ctrl+D toggles the denoised view because plain S and D fly. */
void viewer_input_key(ViewerInput *in, int key, int action, int mods)
{
    const unsigned modifiers = VIEWER_HELD_SHIFT | VIEWER_HELD_CTRL;
    for (size_t i = 0; i < sizeof held_keys / sizeof held_keys[0]; i++) {
        if (held_keys[i].key != key)
            continue;
        if (action == GLFW_RELEASE)
            in->held &= ~held_keys[i].bit;
        else if (action == GLFW_PRESS && /* a letter pressed with Ctrl is a command, not a move */
                 ((held_keys[i].bit & modifiers) || !(mods & GLFW_MOD_CONTROL)))
            in->held |= held_keys[i].bit;
    }
    if (action != GLFW_PRESS)
        return;
    switch (key) {
    case GLFW_KEY_P: in->actions |= VIEWER_PAUSE; break;
    case GLFW_KEY_R: in->actions |= VIEWER_RESET; break;
    case GLFW_KEY_F: in->actions |= VIEWER_FOCUS; break;
    case GLFW_KEY_C: in->actions |= VIEWER_PRINT_CAMERA; break;
    case GLFW_KEY_H: in->actions |= VIEWER_HELP; break;
    case GLFW_KEY_T: in->actions |= VIEWER_NEXT_TONEMAP; break;
    case GLFW_KEY_S:
        if (mods & GLFW_MOD_CONTROL)
            in->actions |= VIEWER_SAVE;
        break;
    case GLFW_KEY_D:
        if (mods & GLFW_MOD_CONTROL)
            in->actions |= VIEWER_DENOISE;
        break;
    default: break;
    }
}

static void on_key(GLFWwindow *window, int key, int scancode, int action, int mods)
{
    (void)scancode;
    ViewerInput *in = input_of(window);
    viewer_print_event(in, "key %d %s mods %d", key, action_name(action), mods);
    if (key == GLFW_KEY_ESCAPE && action == GLFW_PRESS)
        glfwSetWindowShouldClose(window, GLFW_TRUE);
    viewer_input_key(in, key, action, mods);
}

/* + - [ ] , . by the character typed (their keys move between layouts); auto-repeat applies. */
static void on_char(GLFWwindow *window, unsigned int codepoint)
{
    ViewerInput *in = input_of(window);
    viewer_print_event(in, "char %u", codepoint);
    switch (codepoint) {
    case '+': case '=': in->exposure_steps++; break;
    case '-': case '_': in->exposure_steps--; break;
    case ']': in->aperture_steps++; break;
    case '[': in->aperture_steps--; break;
    case '.': case '>': in->environment_steps++; break;
    case ',': case '<': in->environment_steps--; break;
    default: break;
    }
}

/* A drag starts where the last cursor event put the cursor: the button event comes after it in
 * the event stream, while asking the server where the cursor is now (glfwGetCursorPos) would
 * answer with where it went since, losing that part of the drag when frames are slow. */
static void on_mouse_button(GLFWwindow *window, int button, int action, int mods)
{
    ViewerInput *in = input_of(window);
    viewer_print_event(in, "button %d %s mods %d", button, action_name(action), mods);
    bool pressed = action == GLFW_PRESS;
    if (button == GLFW_MOUSE_BUTTON_LEFT)
        in->orbiting = pressed;
    else if (button == GLFW_MOUSE_BUTTON_RIGHT)
        in->panning = pressed;
}

static void on_cursor(GLFWwindow *window, double x, double y)
{
    ViewerInput *in = input_of(window);
    viewer_print_event(in, "cursor %g %g", x, y);
    double dx = x - in->cursor_x, dy = y - in->cursor_y;
    in->cursor_x = x, in->cursor_y = y;
    if (in->orbiting)
        in->orbit_dx += dx, in->orbit_dy += dy;
    else if (in->panning)
        in->pan_dx += dx, in->pan_dy += dy;
}

static void on_scroll(GLFWwindow *window, double x_offset, double y_offset)
{
    ViewerInput *in = input_of(window);
    viewer_print_event(in, "scroll %g %g", x_offset, y_offset);
    in->dolly_steps += y_offset;
}

static void on_framebuffer_size(GLFWwindow *window, int width, int height)
{
    ViewerInput *in = input_of(window);
    viewer_print_event(in, "framebuffer %dx%d", width, height);
    in->resized = true;
}

void viewer_input_attach(GLFWwindow *window, ViewerInput *input, bool print_events)
{
    memset(input, 0, sizeof *input);
    input->print_events = print_events;
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
    in->exposure_steps = in->aperture_steps = in->environment_steps = 0;
    in->orbit_dx = in->orbit_dy = in->pan_dx = in->pan_dy = in->dolly_steps = 0.0;
    in->resized = false;
}

bool viewer_input_fly(const ViewerInput *in, float move[3], bool *fast)
{
    static const struct { unsigned bit; int axis; float sign; } fly_keys[] = {
        {VIEWER_HELD_RIGHT, 0, 1.0f}, {VIEWER_HELD_LEFT, 0, -1.0f}, {VIEWER_HELD_UP, 1, 1.0f},
        {VIEWER_HELD_DOWN, 1, -1.0f}, {VIEWER_HELD_FORWARD, 2, 1.0f}, {VIEWER_HELD_BACK, 2, -1.0f},
    };
    *fast = (in->held & VIEWER_HELD_SHIFT) != 0;
    move[0] = move[1] = move[2] = 0.0f;
    bool any = false;
    if (in->held & VIEWER_HELD_CTRL)
        return false;
    for (size_t i = 0; i < sizeof fly_keys / sizeof fly_keys[0]; i++)
        if (in->held & fly_keys[i].bit) {
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
          "  T               the next tone-map curve (agx, aces, filmic, pbr-neutral, reinhard,\n"
          "                  clamp)\n"
          "  F               focus on the point under the cursor (thin lens)\n"
          "  [ / ]           aperture smaller / larger (0 = pinhole)\n"
          "  , / .           turn the environment map 15 degrees clockwise / counter-clockwise\n"
          "                  seen from above (its rotation -15 / +15)\n"
          "  Ctrl+S          save the film as PNG + EXR (out/<scene>-view-N, never overwriting)\n"
          "  Ctrl+D          denoised view on / off (Intel Open Image Denoise, on a thread of\n"
          "                  its own, each time the film has doubled its samples)\n"
          "  C               print the camera as JSON to paste into a scene\n"
          "  H               this list\n"
          "  Esc             quit\n",
          out);
    fflush(out);
}
