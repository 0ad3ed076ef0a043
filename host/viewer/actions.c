// SPDX-License-Identifier: MIT
/* viewer_actions.c: what the single-key actions of 'pt view' do: focus on the point under the
 * cursor, change the aperture, save the film, print the camera. */
#include "viewer/actions.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include "render/aov.h"
#include "render/bloom.h"
#include "scene/camera.h"
#include "io/image_io.h"
#include "viewer/camera_controls.h"

/* The cursor in film pixels (the window may be scaled on high-density screens). */
static void cursor_in_film(const Viewer *v, double *x, double *y)
{
    int window_width, window_height;
    glfwGetWindowSize(v->window, &window_width, &window_height);
    const SceneDesc *d = &v->session.scene.desc;
    *x = v->input.cursor_x * d->width / (window_width > 0 ? window_width : 1);
    *y = v->input.cursor_y * d->height / (window_height > 0 ? window_height : 1);
}

/* Ray distance to the first surface along dir from the eye, 0 on a miss: the depth AOV of a 1x1
 * film whose camera looks along dir through a tiny field of view. */
static float depth_along(Viewer *v, const float dir[3])
{
    Scene probe = v->session.scene; /* shallow: aov_render reads desc and the device buffers */
    CameraDesc *c = &probe.desc.camera;
    Camera basis = camera_from_desc(c, 1, 1);
    for (int i = 0; i < 3; i++)
        c->target[i] = c->eye[i] + dir[i], c->up[i] = basis.up.s[i];
    c->fov_y = 1e-3f, c->aperture = 0.0f, c->focus_distance = 0.0f;
    probe.desc.width = probe.desc.height = 1;
    float rgb[3];
    aov_render(&v->session.dev, &probe, &v->session.buffers, AOV_DEPTH, 1, 0, rgb);
    return rgb[0];
}

bool viewer_focus_under_cursor(Viewer *v)
{
    CameraDesc *c = &v->session.scene.desc.camera;
    double x, y;
    cursor_in_film(v, &x, &y);
    float dir[3];
    viewer_camera_pixel_direction(c, v->session.scene.desc.width, v->session.scene.desc.height, x,
                                  y, dir);
    float t = depth_along(v, dir);
    if (!(t > 0.0f)) {
        printf("focus: nothing under the cursor\n");
        return false;
    }
    c->focus_distance = viewer_camera_axis_distance(c, dir, t);
    printf("focus distance %.4g%s\n", c->focus_distance,
           c->aperture > 0.0f ? "" : " (aperture 0: press ] to open the lens)");
    return true;
}

void viewer_change_aperture(Viewer *v, int steps)
{
    CameraDesc *c = &v->session.scene.desc.camera;
    float smallest = 0.01f * v->scene_size;
    for (; steps > 0; steps--)
        c->aperture = c->aperture > 0.0f ? c->aperture * 1.5f : smallest;
    for (; steps < 0; steps++)
        c->aperture = c->aperture / 1.5f < smallest * 0.99f ? 0.0f : c->aperture / 1.5f;
    printf("aperture %.4g (focus distance %.4g)\n", c->aperture, c->focus_distance);
}

bool viewer_turn_environment(Viewer *v, int steps)
{
    SceneDesc *d = &v->session.scene.desc;
    if (v->session.buffers.params.env_width == 0) {
        printf("environment: the scene has no environment map to turn\n");
        return false;
    }
    double degrees = fmod((double)d->environment_rotation + 15.0 * steps, 360.0);
    if (degrees < 0.0)
        degrees += 360.0;
    d->environment_rotation = (float)degrees;
    /* What the kernels read (SceneParams.env_rotation, a fraction of a turn, as
     * environment_build stores it); the sampling tables do not depend on the rotation. */
    v->session.buffers.params.env_rotation = (float)(degrees / 360.0);
    v->session.scene.data.environment.rotation = v->session.buffers.params.env_rotation;
    printf("environment rotation %g degrees\n", degrees);
    viewer_print_event(&v->input, "environment rotation %g", degrees);
    return true;
}

bool viewer_is_exr_name(const char *path)
{
    size_t n = strlen(path);
    return n >= 4 && strcasecmp(path + n - 4, ".exr") == 0;
}

/* The film read back exactly as wavefront_render reads it for 'pt render'. */
static float *read_film(Viewer *v)
{
    const SceneDesc *d = &v->session.scene.desc;
    float *rgb = malloc((size_t)d->width * (size_t)d->height * 3 * sizeof *rgb);
    if (!rgb)
        die("out of memory for a %dx%d film", d->width, d->height);
    wavefront_read_film(v->wavefront, rgb);
    return rgb;
}

bool viewer_write_film_exr(Viewer *v, const char *path, Error *err)
{
    float *rgb = read_film(v);
    const SceneDesc *d = &v->session.scene.desc;
    bool ok = image_write_exr(path, rgb, d->width, d->height, err);
    free(rgb);
    return ok;
}

bool viewer_bloom(Viewer *v, float *rgb, Error *err)
{
    const SceneDesc *d = &v->session.scene.desc;
    return v->options->bloom_strength <= 0.0f ||
           bloom_apply(&v->session.dev, rgb, d->width, d->height, v->options->bloom_strength,
                       v->options->bloom_radius, err);
}

/* PNG + EXR of the film as out/<scene>-view-N, N the first free number. */
void viewer_save_film(Viewer *v)
{
    mkdir("out", 0777);
    char png[1100], exr[1100];
    struct stat st;
    for (int n = 1;; n++) {
        snprintf(png, sizeof png, "out/%s-view-%d.png", v->scene_name, n);
        snprintf(exr, sizeof exr, "out/%s-view-%d.exr", v->scene_name, n);
        if (stat(png, &st) != 0 && stat(exr, &st) != 0)
            break;
    }
    const SceneDesc *d = &v->session.scene.desc;
    float *rgb = read_film(v);
    Error err = {0};
    if (image_write_exr(exr, rgb, d->width, d->height, &err) && viewer_bloom(v, rgb, &err) &&
        image_write_png(png, rgb, d->width, d->height,
                        (DisplaySettings){.exposure = v->exposure, .tonemap = v->tonemap}, &err))
        printf("wrote %s\nwrote %s (%d spp, exposure %+.1f, %s)\n", exr, png,
               wavefront_spp_done(v->wavefront), v->exposure, tonemap_name(v->tonemap));
    else
        fprintf(stderr, "pt: %s\n", err.message); /* the window stays open */
    free(rgb);
}

void viewer_print_camera(const Viewer *v)
{
    char json[1024];
    viewer_camera_format(&v->session.scene.desc.camera, json, sizeof json);
    printf("%s\n", json);
}
