// SPDX-License-Identifier: MIT
#define GL_GLEXT_PROTOTYPES /* libGL exports the GL 2.1 entry points on Linux (GLVND, Mesa) */
#include "viewer/display.h"

#include <GL/gl.h>
#include <GL/glext.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <stb_image_write.h>

#include "io/display_curve.h"

/* GLSL 1.10 (GL 2.0): the fixed-function quad's texture coordinates pass through. */
static const char *const vertex_source =
    "#version 110\n"
    "varying vec2 film_uv;\n"
    "void main() { film_uv = gl_MultiTexCoord0.xy; gl_Position = gl_Vertex; }\n";

/* The fragment shader: exposure, then io/display_curve.h's pipeline (the PNG writer's, the same
 * text), the curve picked by the uniform `tonemap` (a Tonemap). The framebuffer's float-to-8-bit
 * conversion rounds to nearest like the writer's lrintf. */
static const char *const fragment_head =
    "#version 110\n"
    "uniform sampler2D film;\n"
    "uniform float exposure_scale;\n"
    "uniform int tonemap;\n"
    "varying vec2 film_uv;\n";

/* main(): one branch per curve, numbered as the Tonemap enum. */
static void fragment_main(char *text, size_t size)
{
    static const char *const curves[] = {
#define CURVE_ENUM_NAME(e, name) #e,
        TONEMAP_CURVES(CURVE_ENUM_NAME)
#undef CURVE_ENUM_NAME
    };
    size_t used = (size_t)snprintf(text, size,
                                   "void main() {\n"
                                   "    vec3 c = texture2D(film, film_uv).rgb * exposure_scale;\n"
                                   "    float r = c.r, g = c.g, b = c.b;\n"
                                   "    display_prepare(r, g, b);\n");
    for (int t = 0; t < TONEMAP_COUNT && used < size; t++)
        used += (size_t)snprintf(text + used, size - used,
                                 "    %sif (tonemap == %d) tonemap_%s(r, g, b);\n",
                                 t ? "else " : "", t, curves[t]);
    if (used < size)
        snprintf(text + used, size - used,
                 "    gl_FragColor = vec4(srgb_from_linear(r), srgb_from_linear(g), "
                 "srgb_from_linear(b), 1.0);\n}\n");
}

static GLuint compile_shader(GLenum type, GLsizei count, const char *const *sources, Error *err)
{
    GLuint shader = glCreateShader(type);
    glShaderSource(shader, count, (const GLchar **)sources, NULL);
    glCompileShader(shader);
    GLint ok = GL_FALSE;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[512] = "";
        glGetShaderInfoLog(shader, sizeof log, NULL, log);
        log[strcspn(log, "\n")] = '\0';
        error_set(err, ERR_SYSTEM, NULL, 0, "OpenGL %s: the display shader does not compile: %s",
                  (const char *)glGetString(GL_VERSION), log);
        glDeleteShader(shader);
        return 0;
    }
    return shader;
}

static bool link_program(ViewerDisplay *d, Error *err)
{
    char main_text[2048];
    fragment_main(main_text, sizeof main_text);
    const char *const fragment_parts[] = {fragment_head, DISPLAY_CURVE_GLSL_PARTS main_text};
    GLuint vertex = compile_shader(GL_VERTEX_SHADER, 1, &vertex_source, err);
    GLuint fragment = vertex ? compile_shader(GL_FRAGMENT_SHADER,
                                              sizeof fragment_parts / sizeof *fragment_parts,
                                              fragment_parts, err)
                             : 0;
    if (!fragment) {
        glDeleteShader(vertex);
        return false;
    }
    d->program = glCreateProgram();
    glAttachShader(d->program, vertex);
    glAttachShader(d->program, fragment);
    glLinkProgram(d->program);
    glDeleteShader(vertex);
    glDeleteShader(fragment);
    GLint ok = GL_FALSE;
    glGetProgramiv(d->program, GL_LINK_STATUS, &ok);
    if (!ok) {
        error_set(err, ERR_SYSTEM, NULL, 0, "OpenGL %s: the display shader does not link",
                  (const char *)glGetString(GL_VERSION));
        return false;
    }
    glUseProgram(d->program);
    glUniform1i(glGetUniformLocation(d->program, "film"), 0);
    d->exposure_scale_location = glGetUniformLocation(d->program, "exposure_scale");
    d->tonemap_location = glGetUniformLocation(d->program, "tonemap");
    return true;
}

bool viewer_display_create(ViewerDisplay *d, int width, int height, Error *err)
{
    memset(d, 0, sizeof *d);
    const char *version = (const char *)glGetString(GL_VERSION);
    int major = version ? atoi(version) : 0;
    if (major < 2) {
        error_set(err, ERR_SYSTEM, NULL, 0, "OpenGL %s is too old for 'pt view' (2.1 needed)",
                  version ? version : "(none)");
        return false;
    }
    if (!link_program(d, err))
        return false;
    glGenTextures(1, &d->texture);
    glBindTexture(GL_TEXTURE_2D, d->texture);
    /* The film is the framebuffer's size: one texel per pixel, no filtering. */
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glGenBuffers(1, &d->pixel_buffer);
    while (glGetError() != GL_NO_ERROR) {
    }
    viewer_display_resize(d, width, height);
    if (glGetError() != GL_NO_ERROR) {
        error_set(err, ERR_SYSTEM, NULL, 0, "OpenGL %s has no float textures (GL_RGB32F)", version);
        return false;
    }
    return true;
}

void viewer_display_resize(ViewerDisplay *d, int width, int height)
{
    d->width = width, d->height = height;
    glBindTexture(GL_TEXTURE_2D, d->texture);
    /* Float texels keep the linear radiance; the shader tone-maps. Black until the first upload. */
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB32F, width, height, 0, GL_RGB, GL_FLOAT, NULL);
}

float *viewer_display_upload_begin(ViewerDisplay *d)
{
    size_t bytes = (size_t)d->width * (size_t)d->height * 3 * sizeof(float);
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, d->pixel_buffer);
    /* A fresh store each frame: the driver may still read the previous one (orphaning). */
    glBufferData(GL_PIXEL_UNPACK_BUFFER, (GLsizeiptr)bytes, NULL, GL_STREAM_DRAW);
    float *pixels = glMapBuffer(GL_PIXEL_UNPACK_BUFFER, GL_WRITE_ONLY);
    if (!pixels)
        die("OpenGL: cannot map the %zu-byte pixel buffer", bytes);
    return pixels;
}

void viewer_display_upload_end(ViewerDisplay *d)
{
    glUnmapBuffer(GL_PIXEL_UNPACK_BUFFER);
    glBindTexture(GL_TEXTURE_2D, d->texture);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, d->width, d->height, GL_RGB, GL_FLOAT, NULL);
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
}

void viewer_display_draw(const ViewerDisplay *d, DisplaySettings display, int framebuffer_width,
                         int framebuffer_height)
{
    glViewport(0, 0, framebuffer_width, framebuffer_height);
    glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    glUseProgram(d->program);
    glUniform1f(d->exposure_scale_location, exp2f(display.exposure));
    glUniform1i(d->tonemap_location, (GLint)display.tonemap);
    glEnable(GL_TEXTURE_2D);
    glBindTexture(GL_TEXTURE_2D, d->texture);
    /* Film row 0 is the top of the image; texture row 0 is at t = 0, so t runs downward. */
    glBegin(GL_QUADS);
    glTexCoord2f(0.0f, 1.0f), glVertex2f(-1.0f, -1.0f);
    glTexCoord2f(1.0f, 1.0f), glVertex2f(1.0f, -1.0f);
    glTexCoord2f(1.0f, 0.0f), glVertex2f(1.0f, 1.0f);
    glTexCoord2f(0.0f, 0.0f), glVertex2f(-1.0f, 1.0f);
    glEnd();
}

bool viewer_display_save_screenshot(const char *path, int width, int height, Error *err)
{
    size_t row = (size_t)width * 3;
    unsigned char *pixels = malloc(row * (size_t)height), *flipped = malloc(row * (size_t)height);
    if (!pixels || !flipped)
        die("out of memory for a %dx%d screenshot", width, height);
    glReadBuffer(GL_BACK);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, pixels);
    /* GL rows go up from the bottom; PNG rows go down from the top. */
    for (int y = 0; y < height; y++)
        memcpy(flipped + (size_t)y * row, pixels + (size_t)(height - 1 - y) * row, row);
    bool ok = stbi_write_png(path, width, height, 3, flipped, (int)row) != 0;
    if (!ok)
        error_set(err, ERR_OUTPUT, path, 0, "%s: cannot write the screenshot", path);
    free(pixels);
    free(flipped);
    return ok;
}

void viewer_display_destroy(ViewerDisplay *d)
{
    if (d->pixel_buffer)
        glDeleteBuffers(1, &d->pixel_buffer);
    if (d->texture)
        glDeleteTextures(1, &d->texture);
    if (d->program)
        glDeleteProgram(d->program);
    memset(d, 0, sizeof *d);
}
