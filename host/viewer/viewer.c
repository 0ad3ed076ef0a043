// SPDX-License-Identifier: MIT
/* viewer.c: 'pt view'. Each frame: read the input, apply it to the camera (a change empties the
 * film), trace what is left of FRAME_BUDGET_S after showing the film, in paths at the measured
 * rate, then stream the film to the screen. Windows (the wavefront's indivisible steps) are sized
 * from the same measurement so that one is never long enough to make the window unresponsive, on
 * a GPU or on PoCL. */
#include "viewer/viewer.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/clock.h"
#include "base/fs.h"
#include "render/session.h"
#include "scene/camera.h"
#include "viewer/actions.h"
#include "viewer/camera_controls.h"
#include "viewer/display.h"
#include "viewer/input.h"
#include "viewer/pacing.h"
#include "viewer/stats.h"
#include "render/wavefront.h"

#define TITLE_INTERVAL_S 0.25
#define UNLIMITED_SPP (1 << 30)
/* Below this many slots, launch overheads dominate on PoCL: 1024-slot pools traced about a third
 * fewer paths per second than 4096-slot ones in our runs at 512x512. */
#define SMALLEST_EFFICIENT_POOL (1u << 14)


static char glfw_error_text[512] = "unknown error";
static void on_glfw_error(int code, const char *description)
{
    (void)code;
    snprintf(glfw_error_text, sizeof glfw_error_text, "%s", description);
}

/* ---- The film: a Wavefront sized to the framebuffer ---------------------------------------- */

/* A film whose steps are windows of window_size samples, traced by a pool of the usual fraction
 * of a window (slots are refilled from the window as paths end), or the whole window if small. */
static void create_film(Viewer *v, uint32_t window_size)
{
    Error err = {0};
    if (v->wavefront)
        wavefront_destroy(v->wavefront);
    v->settings.window_size = window_size;
    uint32_t pool = window_size / WINDOW_PER_POOL;
    if (pool < SMALLEST_EFFICIENT_POOL)
        pool = window_size < SMALLEST_EFFICIENT_POOL ? window_size : SMALLEST_EFFICIENT_POOL;
    v->settings.pool_size = pool;
    v->wavefront = wavefront_create(&v->session.dev, &v->session.scene, &v->session.buffers,
                                    &v->settings, &err);
    if (!v->wavefront)
        die("%s", err.message);
    v->film_changed = true;
    v->film_generation++;
}

/* A new window when the measured rate calls for one at least 4x larger or smaller (the first
 * frames, or a device much faster than guessed); the film restarts, which costs little then. */
static void adapt_window(Viewer *v)
{
    if (v->recent_seconds < 0.1) /* too young a measurement */
        return;
    uint32_t current = wavefront_stats(v->wavefront)->config.window_size;
    uint32_t wanted = viewer_window_for_rate(v->paths_per_second);
    uint64_t film = (uint64_t)v->session.scene.desc.width * (uint64_t)v->session.scene.desc.height;
    bool capped = current >= film * (uint64_t)v->target_spp; /* the whole render fits already */
    if ((wanted >= 4ull * current && !capped) || current >= 4ull * wanted)
        create_film(v, wanted);
}

static void apply_camera(Viewer *v)
{
    const SceneDesc *d = &v->session.scene.desc;
    Camera camera = camera_from_desc(&d->camera, d->width, d->height);
    wavefront_set_camera(v->wavefront, &camera);
    v->film_changed = true;
    v->film_generation++;
    v->paused = false; /* a new view is always wanted rendered */
}

/* The film follows the framebuffer (zero while minimised: keep the old one). */
static void resize_film(Viewer *v)
{
    int width, height;
    glfwGetFramebufferSize(v->window, &width, &height);
    SceneDesc *d = &v->session.scene.desc;
    if (width <= 0 || height <= 0 || (width == d->width && height == d->height))
        return;
    d->width = width, d->height = height;
    create_film(v, wavefront_stats(v->wavefront)->config.window_size);
    viewer_display_resize(&v->display, width, height);
}

/* ---- One frame ------------------------------------------------------------------------------ */

/* Applies what the user did since the last frame; seconds: time since then (for flying). */
static void apply_input(Viewer *v, double seconds)
{
    ViewerInput *in = &v->input;
    CameraDesc *c = &v->session.scene.desc.camera;
    int film_height = v->session.scene.desc.height, window_width, window_height;
    glfwGetWindowSize(v->window, &window_width, &window_height);
    float to_film = (float)film_height / (float)(window_height > 0 ? window_height : 1);
    bool moved = false;
    if (in->resized) {
        resize_film(v);
        const SceneDesc *d = &v->session.scene.desc;
        viewer_print_event(in, "film %dx%d", d->width, d->height);
    }
    if (in->orbit_dx != 0.0 || in->orbit_dy != 0.0) /* grab the scene: it turns with the cursor */
        viewer_camera_orbit(c, -0.005f * (float)in->orbit_dx, -0.005f * (float)in->orbit_dy), moved = true;
    if (in->pan_dx != 0.0 || in->pan_dy != 0.0)
        viewer_camera_pan(c, to_film * (float)in->pan_dx, to_film * (float)in->pan_dy, film_height), moved = true;
    if (in->dolly_steps != 0.0)
        viewer_camera_dolly(c, (float)in->dolly_steps), moved = true;
    float move[3];
    bool fast;
    if (viewer_input_fly(in, move, &fast)) {
        double step = fmin(seconds, 0.1) * 0.3 * v->scene_size * (fast ? 4.0 : 1.0);
        viewer_camera_fly(c, move, (float)step), moved = true;
    }
    if (in->aperture_steps)
        viewer_change_aperture(v, in->aperture_steps), moved = true;
    if ((in->actions & VIEWER_FOCUS) && viewer_focus_under_cursor(v))
        moved = true;
    if (moved)
        apply_camera(v);
    /* A new rotation is a new scene for the film: the wavefront takes it at creation. */
    if (in->environment_steps && viewer_turn_environment(v, in->environment_steps)) {
        create_film(v, wavefront_stats(v->wavefront)->config.window_size);
        v->paused = false;
    }
    if (in->exposure_steps) {
        v->exposure += 0.5f * (float)in->exposure_steps;
        printf("exposure %+.1f EV\n", v->exposure);
    }
    if (in->actions & VIEWER_NEXT_TONEMAP) {
        v->tonemap = (Tonemap)((v->tonemap + 1) % TONEMAP_COUNT);
        printf("tone map %s\n", tonemap_name(v->tonemap));
    }
    if (in->actions & VIEWER_PAUSE) {
        v->paused = !v->paused;
        printf("%s at %d spp\n", v->paused ? "paused" : "resumed", wavefront_spp_done(v->wavefront));
    }
    if (in->actions & VIEWER_RESET)
        wavefront_reset(v->wavefront), v->film_changed = true, v->film_generation++;
    if (in->actions & VIEWER_DENOISE)
        viewer_toggle_denoise(v);
    if (in->actions & VIEWER_SAVE)
        viewer_save_film(v);
    if (in->actions & VIEWER_PRINT_CAMERA)
        viewer_print_camera(v);
    if (in->actions & VIEWER_HELP)
        viewer_input_print_help(stdout);
    fflush(stdout);
    viewer_input_clear(in);
}

static bool converged(const Viewer *v) { return wavefront_spp_done(v->wavefront) >= v->target_spp; }

/* What is left of FRAME_BUDGET_S once the film is shown, in paths at the measured rate (one window
 * before any measurement). Showing the film has a cost of its own (about 13 ms at 512x512 on
 * llvmpipe), which is why it counts; sampling keeps at least a quarter of the frame. */
static void render_step(Viewer *v)
{
    v->last_sampling_seconds = 0.0;
    if (v->paused || converged(v))
        return;
    double budget = fmax(FRAME_BUDGET_S - v->display_seconds, 0.25 * FRAME_BUDGET_S);
    uint64_t wanted = (uint64_t)(v->paths_per_second * budget);
    /* Slow start: a young measurement can be far off (the first window may be quick), so ask for
     * at most twice what the last frame did. */
    if (wanted > 2 * v->last_paths)
        wanted = 2 * v->last_paths;
    double start = seconds_now();
    uint64_t done = wavefront_advance(v->wavefront, wanted ? wanted : 1, v->target_spp);
    double seconds = seconds_now() - start;
    /* Paths over time, both decaying: a steadier rate than averaging per-frame rates, in which
     * a short frame (a pass ending) weighs as much as a long one. */
    v->recent_paths = 0.7 * v->recent_paths + (double)done;
    v->recent_seconds = 0.7 * v->recent_seconds + seconds;
    if (v->recent_seconds > 1e-4)
        v->paths_per_second = v->recent_paths / v->recent_seconds;
    viewer_stats_add_sampling(&v->stats, done, seconds);
    v->title_paths += done;
    v->last_paths = done;
    v->last_sampling_seconds = seconds;
    v->film_changed = true;
    adapt_window(v);
    if (converged(v)) /* once per film: render_step traces nothing more until it changes */
        viewer_print_event(&v->input, "converged %d spp", wavefront_spp_done(v->wavefront));
}

/* The film into the display's texture; with --bloom, bloomed on a copy first (the mapped pixel
 * buffer is write-only). */
static void upload_film(Viewer *v)
{
    if (v->options->bloom_strength <= 0.0f) {
        wavefront_read_film(v->wavefront, viewer_display_upload_begin(&v->display));
        viewer_display_upload_end(&v->display);
        return;
    }
    const SceneDesc *d = &v->session.scene.desc;
    size_t bytes = (size_t)d->width * (size_t)d->height * 3 * sizeof(float);
    float *rgb = malloc(bytes);
    if (!rgb)
        die("out of memory for a %dx%d film", d->width, d->height);
    wavefront_read_film(v->wavefront, rgb);
    Error err = {0};
    if (!viewer_bloom(v, rgb, &err))
        die("%s", err.message);
    memcpy(viewer_display_upload_begin(&v->display), rgb, bytes);
    viewer_display_upload_end(&v->display);
    free(rgb);
}

static void show_film(Viewer *v)
{
    if (v->film_changed && !viewer_showing_denoised(v)) {
        upload_film(v);
        v->film_changed = false;
    }
    DisplaySettings display = {.exposure = v->exposure, .tonemap = v->tonemap};
    viewer_display_draw(&v->display, display, v->session.scene.desc.width,
                        v->session.scene.desc.height);
}

static void update_title(Viewer *v, double now, double frame_ms)
{
    v->title_frame_ms = v->title_frame_ms > 0.0 ? 0.8 * v->title_frame_ms + 0.2 * frame_ms : frame_ms;
    if (now - v->title_time < TITLE_INTERVAL_S)
        return;
    char title[1400];
    char denoised[48] = "";
    if (viewer_showing_denoised(v))
        snprintf(denoised, sizeof denoised, " | denoised (%d spp)", v->shown_spp);
    else if (v->denoise_on)
        snprintf(denoised, sizeof denoised, " | denoising");
    if (strcmp(denoised, v->title_denoised)) { /* --events: scripts wait for the state */
        viewer_print_event(&v->input, "title%s", denoised[0] ? denoised + 2 : " noisy");
        snprintf(v->title_denoised, sizeof v->title_denoised, "%s", denoised);
    }
    snprintf(title, sizeof title, "pt view %s | %d spp%s%s | %.2f Msamples/s | %s | %.0f ms",
             v->scene_name, wavefront_spp_done(v->wavefront),
             v->paused ? " (paused)" : converged(v) ? " (done)" : "", denoised,
             (double)v->title_paths / (now - v->title_time) * 1e-6, v->session.dev.name,
             v->title_frame_ms);
    glfwSetWindowTitle(v->window, title);
    v->title_time = now, v->title_paths = 0;
}

/* The frame loop: input, samples, display, until Esc, the window closes, or --frames. */
static void run_frames(Viewer *v)
{
    double last = seconds_now();
    while (!glfwWindowShouldClose(v->window)) {
        bool idle = (v->paused || converged(v)) && !v->options->frames;
        if (idle)
            glfwWaitEventsTimeout(TITLE_INTERVAL_S); /* nothing to trace: sleep until input */
        else
            glfwPollEvents();
        double start = seconds_now();
        apply_input(v, start - last);
        render_step(v);
        viewer_update_denoised(v, v->paused || converged(v));
        show_film(v);
        glfwSwapBuffers(v->window);
        double now = seconds_now(), frame_ms = 1e3 * (now - start);
        last = start;
        viewer_stats_add_frame(&v->stats, frame_ms);
        double display = now - start - v->last_sampling_seconds;
        v->display_seconds = v->stats.frames > 1 ? 0.9 * v->display_seconds + 0.1 * display : display;
        update_title(v, now, frame_ms);
        /* --frames N --screenshot: past N frames, on until every pixel has a whole sample, so
         * the picture saved has no band still black (a frame's budget may cover part of the film). */
        bool whole = !v->options->screenshot || wavefront_spp_done(v->wavefront) >= 1;
        if (v->options->frames && v->stats.frames >= v->options->frames && whole)
            break;
    }
}

/* ---- Setup ---------------------------------------------------------------------------------- */

static void open_window(Viewer *v)
{
    SceneDesc *d = &v->session.scene.desc;
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 2);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 1);
    v->window = glfwCreateWindow(d->width, d->height, "pt view", NULL, NULL);
    if (!v->window)
        die("cannot open a %dx%d OpenGL 2.1 window (%s); use 'pt render' to render to a file",
            d->width, d->height, glfw_error_text);
    glfwMakeContextCurrent(v->window);
    glfwSwapInterval(0); /* the frame budget paces the loop; vsync would add up to a refresh */
    glfwGetFramebufferSize(v->window, &d->width, &d->height); /* the film is the framebuffer */
    Error err = {0};
    if (!viewer_display_create(&v->display, d->width, d->height, &err))
        die("%s", err.message);
    viewer_input_attach(v->window, &v->input, v->options->print_events);
}

int command_view(const ViewerDesc *o)
{
    static Viewer viewer; /* large; and the GLFW callbacks hold a pointer into it */
    Viewer *v = &viewer;
    memset(v, 0, sizeof *v);
    v->options = o;
    v->exposure = o->exposure;
    v->tonemap = o->tonemap;
    glfwSetErrorCallback(on_glfw_error);
    if (!glfwInit())
        die("cannot open a window: no display (%s); use 'pt render' to render to a file",
            glfw_error_text);
    Error err = {0};
    if (!session_open(&v->session, &o->render, &err))
        die("%s", err.message);
    /* --camera (o->render.camera_json) is already the scene's camera: session_open applied it. */
    SceneDesc *d = &v->session.scene.desc;
    fs_stem(o->render.scene, v->scene_name, sizeof v->scene_name);
    const float *lo = v->session.scene.data.bounds_min, *hi = v->session.scene.data.bounds_max;
    v->scene_size = sqrtf((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                          (hi[2] - lo[2]) * (hi[2] - lo[2]));
    if (!(v->scene_size > 0.0f))
        v->scene_size = 1.0f;
    v->target_spp = o->render.spp ? o->render.spp : UNLIMITED_SPP;
    v->settings = o->settings;
    v->settings.spp = v->target_spp;
    session_settle_settings(&v->session, &v->settings, o->sort_materials);
    if (!o->quiet) {
        session_print_summary(&v->session);
        fprintf(stderr, "pt: view: press H in the window for the keys\n");
    }
    open_window(v);
    /* A first guess at the window, refined from the first frames' rate. */
    create_film(v, (v->session.dev.type & CL_DEVICE_TYPE_GPU) ? 1u << 20 : 1u << 14);
    viewer_print_event(&v->input, "ready %dx%d", d->width, d->height);
    if (o->denoise)
        viewer_toggle_denoise(v);
    v->title_time = seconds_now();
    run_frames(v);

    bool saved = true;
    if (o->screenshot && viewer_is_exr_name(o->screenshot)) {
        saved = viewer_write_film_exr(v, o->screenshot, &err);
        if (saved && !o->quiet)
            printf("wrote %s (%d spp)\n", o->screenshot, wavefront_spp_done(v->wavefront));
    } else if (o->screenshot) {
        show_film(v); /* the last frame again, into the back buffer that is read */
        saved = viewer_display_save_screenshot(o->screenshot, d->width, d->height, &err);
        if (saved && !o->quiet)
            printf("wrote %s\n", o->screenshot);
    }
    if (!o->quiet)
        viewer_stats_print(&v->stats, wavefront_spp_done(v->wavefront), v->session.dev.name, stderr);
    viewer_stats_destroy(&v->stats);
    denoise_view_stop(&v->denoise);
    wavefront_destroy(v->wavefront);
    viewer_display_destroy(&v->display);
    glfwDestroyWindow(v->window);
    glfwTerminate();
    session_close(&v->session);
    if (!saved)
        die("%s", err.message);
    return 0;
}
