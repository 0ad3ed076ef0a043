// SPDX-License-Identifier: MIT
/* render_cmd.c: `pt render`: open the session, plan the outputs (never overwriting without -o),
 * path-trace the beauty, run the AOV pass when asked (--aov), write the EXR (beauty, layers and
 * metadata, app/render_output.h) and/or the PNG (the beauty alone), and report; SIGINT, SIGTERM
 * and SIGHUP stop the render and keep the image, marked partial. */
#include "app/render_cmd.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "dist/mpi_link.h"
#include "app/render_cmd_units.h"
#include "app/render_denoise.h"
#include "app/render_loop.h"
#include "app/render_output.h"
#include "app/stop_signals.h"
#include "base/clock.h"
#include "base/fs.h"
#include "io/image_io.h"
#include "render/aov.h"
#include "render/aov_layers.h"
#include "render/bloom.h"
#include "render/session.h"
#include "render/wavefront.h"

typedef struct {
    char exr[1100];
    char png[1100];
} OutputPaths;

/* Without -o: out/<name>.exr, then <name>-2 ... <name>-MAX_NUMBERED_OUTPUTS; past that, an error
 * (never an overwrite). */
#define MAX_NUMBERED_OUTPUTS 9999

/* Numbered outputs this run claimed: created empty with O_EXCL before the render, so that two pt
 * started together cannot both pick out/<name>.exr (the image replaces the empty file by an atomic
 * rename). A claim not written by the end (an error, a stop before the first samples) is removed
 * at exit. */
static struct {
    char path[2][1100];
    bool written[2];
} g_claims;

static void remove_unwritten_claims(void)
{
    for (int i = 0; i < 2; i++)
        if (g_claims.path[i][0] && !g_claims.written[i])
            unlink(g_claims.path[i]);
}

static void claim_written(const char *path)
{
    for (int i = 0; i < 2; i++)
        g_claims.written[i] = g_claims.written[i] || !strcmp(g_claims.path[i], path);
}

/* Creates path if nothing is there (0), 1 when something is, -1 (err set) when it cannot. */
static int claim(const char *path, int slot, Error *err)
{
    int fd = open(path, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0 && errno == EEXIST)
        return 1;
    if (fd < 0) {
        error_set(err, ERR_OUTPUT, path, 0, "cannot create %s: %s", path, strerror(errno));
        return -1;
    }
    close(fd);
    snprintf(g_claims.path[slot], sizeof g_claims.path[slot], "%s", path);
    return 0;
}

/* Claims the EXR and the PNG of one numbered name: 0 both, 1 one exists (none kept), -1 error. */
static int claim_pair(const OutputPaths *paths, Error *err)
{
    int exr = claim(paths->exr, 0, err);
    if (exr != 0)
        return exr;
    int png = claim(paths->png, 1, err);
    if (png != 0) {
        unlink(paths->exr);
        g_claims.path[0][0] = '\0';
    }
    return png;
}

/* -o names the output (and may overwrite it: the user asked). Without -o, out/<name>.exr + .png,
 * numbered (<name>-2, -3, ...) so that nothing already there is overwritten. */
static bool plan_outputs(const Options *o, const char *suffix, OutputPaths *paths, Error *err)
{
    memset(paths, 0, sizeof *paths);
    if (o->output) {
        if (strlen(o->output) + 4 >= sizeof paths->exr) {
            error_set(err, ERR_OUTPUT, o->output, 0, "-o %s: the output path is too long (%zu bytes)",
                      o->output, strlen(o->output));
            return false;
        }
        if (fs_has_suffix(o->output, ".exr")) {
            snprintf(paths->exr, sizeof paths->exr, "%s", o->output);
            if (o->preview)
                snprintf(paths->png, sizeof paths->png, "%.*s.png", (int)strlen(o->output) - 4,
                         o->output);
        } else if (fs_has_suffix(o->output, ".png")) {
            snprintf(paths->png, sizeof paths->png, "%s", o->output);
        } else {
            error_set(err, ERR_USAGE, NULL, 0, "-o %s: the output must end in .exr or .png", o->output);
            return false;
        }
    } else {
        char name[512];
        fs_stem(o->scene, name, sizeof name);
        if (!fs_exists("out") && mkdir("out", 0777) != 0) {
            error_set(err, ERR_OUTPUT, "out", 0, "cannot create the output folder 'out'");
            return false;
        }
        bool found = false;
        atexit(remove_unwritten_claims);
        for (int n = 1; n <= MAX_NUMBERED_OUTPUTS && !found; n++) {
            char stem[600];
            if (n == 1)
                snprintf(stem, sizeof stem, "out/%s%s", name, suffix);
            else
                snprintf(stem, sizeof stem, "out/%s%s-%d", name, suffix, n);
            snprintf(paths->exr, sizeof paths->exr, "%s.exr", stem);
            snprintf(paths->png, sizeof paths->png, "%s.png", stem);
            int taken = claim_pair(paths, err);
            if (taken < 0)
                return false;
            found = taken == 0;
        }
        if (!found) {
            error_set(err, ERR_OUTPUT, "out", 0,
                      "out/%s%s.exr to out/%s%s-%d.exr (or .png) all exist: move some away or name "
                      "the output with -o", name, suffix, name, suffix, MAX_NUMBERED_OUTPUTS);
            return false;
        }
    }
    if (paths->exr[0] && !fs_check_writable(paths->exr, err))
        return false;
    if (paths->png[0] && !fs_check_writable(paths->png, err))
        return false;
    fs_remove_stale_temps(paths->exr); /* a write SIGKILLed earlier ("" names none) */
    fs_remove_stale_temps(paths->png);
    return true;
}

/* A PNG holds no layers, and writing an EXR the user did not name would surprise: -o X.png with
 * --aov is refused before anything is loaded. */
static bool check_aov_output(const Options *o, Error *err)
{
    if (o->aov_mask && o->output && fs_has_suffix(o->output, ".png")) {
        error_set(err, ERR_USAGE, NULL, 0,
                  "--aov: AOV layers go into the EXR, and -o %s writes only a PNG: name an .exr "
                  "(with --preview for the PNG too)", o->output);
        return false;
    }
    return true;
}

/* PT_TEST_RAISE=SIGNAL@write raises its signal between a temporary file and its rename. */
static void raise_at_write_point(void) { stop_signals_test_point("write"); }

static ProgressStyle progress_style(const Options *o)
{
    return render_loop_progress_style(o->quiet, o->progress, isatty(STDERR_FILENO));
}

static void report_render(const Options *o, const RenderStats *stats)
{
    if (stats->nonfinite)
        fprintf(stderr, "pt: warning: %u samples were NaN or Inf and were counted as black\n",
                stats->nonfinite);
    if (!o->quiet)
        fprintf(stderr,
                "pt: %d spp in %.2f s: %.2f Mpaths/s, %.2f Mrays/s (%.2f extension + %.2f shadow); "
                "pool %u paths, %u windows of %u samples\n",
                stats->spp_done, stats->seconds, stats->paths / stats->seconds * 1e-6,
                (stats->extension_rays + stats->shadow_rays) / stats->seconds * 1e-6,
                stats->extension_rays / stats->seconds * 1e-6,
                stats->shadow_rays / stats->seconds * 1e-6, stats->config.pool_size, stats->windows,
                stats->config.window_size);
    if (o->profile)
        render_stats_print_profile(stderr, stats, "stage");
}

/* MPI: without --device, the ranks of a node take the devices of `--device all` in turn (one
 * GPU each on a node of several; PoCL's one CPU device is shared), by their local rank. */
static void choose_rank_device(const Options *o, RenderDesc *render, DeviceSpecList *devices)
{
    Error err = {0};
    if (mpi_link_size() == 1 || o->device || !device_spec_list("all", devices, &err))
        return; /* none found: the default device says why */
    render->device = devices->spec[mpi_link_local_rank() % devices->count];
}

/* The checkpoint of a unit render sits beside -o's file, or at out/<scene>.ptckpt (not numbered,
 * so that --resume finds it): base is that output's path. */
static void checkpoint_base(const Options *o, char *base, size_t size)
{
    if (o->output) {
        snprintf(base, size, "%s", o->output);
        return;
    }
    char stem[512];
    fs_stem(o->scene, stem, sizeof stem);
    snprintf(base, size, "out/%s", stem);
}

/* The albedo, normal and depth layers asked for (and the denoiser's guides): after the beauty, in
 * a pass of their own, so that the beauty's bits cannot depend on them; then --denoise. */
static void aov_pass(const Options *o, RenderImages *images, Session *session,
                     const RenderSettings *settings, int spp_done, bool denoise)
{
    int aov_spp = denoise ? denoise_guide_spp(spp_done) : aov_pass_spp(spp_done);
    Error err = {0};
    double start = seconds_now();
    if (!render_images_aov_pass(images, session, settings, aov_spp, &err))
        die("%s", err.message);
    if (!o->quiet && (images->layer[AOV_LAYER_ALBEDO] || images->layer[AOV_LAYER_NORMAL] ||
                       images->layer[AOV_LAYER_DEPTH]))
        fprintf(stderr, "pt: AOV pass: %d spp in %.2f s\n", aov_spp, seconds_now() - start);
    if (denoise)
        render_images_denoise(images, session, (DenoiseDevice)o->denoise_device, o->quiet);
}

/* The camera sees no geometry at all (a file's camera looking away, a model far off): said before
 * the render, from one camera ray per pixel (the AOV pass's first sample: W x H rays, nothing
 * beside a render). A scene of sky alone (no objects) sees none on purpose. */
static void warn_when_nothing_in_view(Session *session, const RenderSettings *settings)
{
    const SceneDesc *desc = &session->scene.desc;
    size_t n = (size_t)desc->width * (size_t)desc->height;
    float *coverage = desc->num_objects > 0 ? malloc(n * sizeof *coverage) : NULL;
    if (!coverage)
        return;
    AovSettings probe = {.spp = 1, .max_depth = 1, .seed = settings->seed,
                         .first_sample = settings->first_sample};
    AovImages images = {.coverage = coverage};
    Error err = {0};
    double hits = 0.0;
    bool probed = aov_render_layers(&session->dev, &session->scene, &session->buffers, &probe, &images, &err);
    for (size_t p = 0; probed && p < n; p++)
        hits += coverage[p];
    free(coverage);
    if (probed && hits == 0.0)
        warn("%s: the camera sees no geometry (every camera ray missed it): %s", desc->path,
             desc->camera_given ? "the scene's camera looks away from the model; --frame frames it "
                                  "in a 3/4 view"
                                : "--camera places the camera");
}

/* The camera sees geometry that no light reaches (the file's lights hidden from it: a closed room
 * seen from outside): said after the render, from the image and its coverage. */
static void warn_when_black(const RenderImages *images, const Session *session)
{
    const SceneDesc *desc = &session->scene.desc;
    size_t n = (size_t)desc->width * (size_t)desc->height;
    double coverage = 0.0, light = 0.0;
    for (size_t p = 0; p < n; p++) {
        coverage += images->alpha[p];
        light += images->rgb[3 * p] + images->rgb[3 * p + 1] + images->rgb[3 * p + 2];
    }
    /* A scene with no light at all is black on purpose (--no-default-light). */
    const SceneData *d = &session->scene.data;
    bool lit = d->num_emissive > 0 || d->num_analytic > 0 || d->environment.width > 0 ||
               desc->background[0] > 0.0f || desc->background[1] > 0.0f || desc->background[2] > 0.0f;
    if (lit && coverage > 0.0 && light == 0.0)
        warn("%s: the image is black: no light reaches the camera (%u emissive triangles, %u lights, "
             "%s; they light nothing the camera sees, e.g. a closed room seen from outside): "
             "--camera to look from elsewhere", desc->path, session->scene.data.num_emissive,
             session->scene.data.num_analytic,
             session->scene.data.environment.width > 0 ? "an environment" : "no environment");
}

/* The EXR (linear, every layer, the record in its header), then the PNG (bloom and the display
 * curve applied to the beauty after the EXR was written). */
static void write_outputs(const Options *o, const OutputPaths *out, RenderImages *images,
                          Session *session, const RenderStats *stats, int spp, RenderStop stop)
{
    const SceneDesc *desc = &session->scene.desc;
    Error err = {0};
    if (out->exr[0]) {
        RenderRecord record = {.spp_done = stats->spp_done,
                               .spp_requested = spp,
                               .seed = o->seed, /* 0 unless --seed */
                               .render_seconds = stats->seconds,
                               .scene = o->scene,
                               .partial = stop != RENDER_COMPLETE};
        if (!render_write_exr(out->exr, images, session, &record, &err))
            die("%s", err.message);
        claim_written(out->exr);
        printf("wrote %s\n", out->exr);
    }
    if (out->png[0]) {
        if (o->bloom_strength > 0.0f &&
            !bloom_apply(&session->dev, images->rgb, desc->width, desc->height, o->bloom_strength,
                         o->bloom_radius, &err))
            die("%s", err.message);
        DisplaySettings display = {.exposure = o->exposure, .tonemap = o->tonemap};
        if (!image_write_png(out->png, images->rgb, desc->width, desc->height, display, &err))
            die("%s", err.message);
        claim_written(out->png);
        printf("wrote %s\n", out->png);
    }
}

/* Why the image holds fewer spp than asked, when it does. */
static void report_stop(RenderStop stop, int spp_done, int spp, bool has_exr)
{
    const char *partial = has_exr ? " (its EXR header says partial = 1)" : "";
    if (stop_signal_received())
        fprintf(stderr, "pt: stopped by %s: the image holds %d of %d spp%s\n",
                stop_signal_name(stop_signal_received()), spp_done, spp,
                spp_done < spp ? partial : "");
    else if (stop == RENDER_STOPPED_BY_TIME_LIMIT)
        fprintf(stderr, "pt: stopped by the time limit: the image holds %d of %d spp%s\n", spp_done,
                spp, partial);
}

int command_render(const Options *o)
{
    Error err = {0};
    Session session;
    RenderDesc render = cli_render_desc(o);
    bool units = render_cmd_wants_units(o);
    DeviceSpecList devices = {0};
    if (!check_aov_output(o, &err) || !stop_signals_configure(&err) ||
        (units && !render_cmd_units_devices(o, &devices, &err)))
        die("%s", err.message);
    if (devices.count > 0)
        render.device = devices.spec[0]; /* the session's own; render_units opens the rest */
    DeviceSpecList rank_devices; /* MPI: holds the spec chosen for this rank */
    choose_rank_device(o, &render, &rank_devices);
    if (mpi_link_rank() > 0)
        warnings_set_quiet(true); /* the scene's warnings: rank 0 gives them once */
    if (!session_open(&session, &render, &err))
        die("%s", err.message);
    bool root = mpi_link_rank() == 0; /* MPI: rank 0 alone writes and reports */
    OutputPaths out;
    memset(&out, 0, sizeof out);
    if (root && !plan_outputs(o, "", &out, &err))
        die("%s", err.message);
    if (!o->quiet && root)
        session_print_summary(&session);

    const SceneDesc *desc = &session.scene.desc;
    size_t num_pixels = (size_t)desc->width * (size_t)desc->height;
    RenderImages images;
    bool denoise = o->denoise || desc->denoise;
    if (!render_images_alloc(&images, o->aov_mask, num_pixels) ||
        (denoise && !render_images_add_guides(&images, num_pixels)))
        die("out of memory for a %dx%d film", desc->width, desc->height);
    int spp = desc->spp, spp_done = spp;
    RenderStop stop = RENDER_COMPLETE; /* anything else: the image is partial */
    /* From here on, SIGINT, SIGTERM and SIGHUP stop the render and keep the image. */
    stop_signals_install();
    fs_set_before_rename_hook(raise_at_write_point);
    RenderSettings settings = cli_render_settings(o);
    session_settle_settings(&session, &settings, o->sort_materials);
    if (root)
        warn_when_nothing_in_view(&session, &settings);
    RenderStats stats;
    RenderLoopDesc loop = {.progress = progress_style(o), .time_limit = o->time_limit};
    bool rendered;
    char base[1100] = ""; /* the output a checkpoint sits beside */
    if (units) {
        checkpoint_base(o, base, sizeof base);
        rendered = render_cmd_units_run(o, &session, &devices, &settings, base, &images, &stats,
                                        &stop, &err);
    } else {
        rendered = render_loop_run(&session, &settings, &loop, &images, &stats, &stop, &err);
    }
    if (!rendered && root)
        die("%s", err.message);
    if (!rendered)
        die("rank %d: %s", mpi_link_rank(), err.message);
    if (!root) { /* MPI: this rank's film is rank 0's now */
        render_images_free(&images);
        session_close(&session);
        return stop_exit_status();
    }
    report_render(o, &stats);
    spp_done = stats.spp_done;
    if (stats.paths == 0 && stats.spp_done == 0) { /* a resumed film may be whole already */
        fprintf(stderr, "pt: stopped by %s before the first samples: nothing written\n",
                stop_signal_name(stop_signal_received()));
        render_images_free(&images);
        session_close(&session);
        return stop_exit_status();
    }
    aov_pass(o, &images, &session, &settings, spp_done, denoise);
    warn_when_black(&images, &session);
    write_outputs(o, &out, &images, &session, &stats, spp, stop);
    if (units && stop == RENDER_COMPLETE)
        render_cmd_units_remove_checkpoint(o, base);
    render_images_free(&images);
    session_close(&session);
    report_stop(stop, spp_done, spp, out.exr[0] != 0);
    return stop_exit_status(); /* 0 after a time limit: the render the user asked for */
}
