// SPDX-License-Identifier: MIT
/* Checkpoint and resume end to end (pt as a child process, PoCL): a render killed with SIGKILL at
 * a pseudo-random moment and resumed gives the pixels of a render never interrupted, bit for bit,
 * on one device or two (POCL_DEVICES="pthread pthread" --device all); checkpoints of another scene
 * or other settings, damaged, truncated or of another version are refused with one line; --resume
 * with nothing, and a checkpoint left without --resume, too; a finished render removes its
 * checkpoint.
 *
 * No test depends on timing. pt kills itself (PT_TEST_RAISE=SIGKILL@unit:N: the N-th run of units
 * finished) so that the moment is chosen, not slept for; a first stage stops by SIGTERM after one
 * run, which always writes a checkpoint (the driver saves a stopped render), so a checkpoint
 * exists whenever the kill comes. The periodic checkpoints (--checkpoint 0.001) come when time
 * says, so what the killed run left on disk varies: any of those states must resume to the same
 * bits. The film is 6 tiles of 8 rows (--unit-rows 8); a run never spans tiles, so after the first
 * stage (one run per device, at most 2 tiles) at least 4 runs remain and a kill at run 1 to 3
 * always comes before the end. Pixels are compared, not files (the EXR header holds the time). */
#include <criterion/criterion.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "cli_run.h"
#include "io/image_io.h"
#include "dist/checkpoint.h"
#include "support.h"

#define SCENE "render scenes/cornell-box"
#define FILM "--width 64 --height 48 --spp 8 --max-depth 4 --unit-rows 8 --quiet"
#define TWO_DEVICES "POCL_DEVICES='pthread pthread'"

typedef struct {
    char dir[128];
    char exr[256];   /* DIR/out.exr */
    char ckpt[300];  /* DIR/out.exr.ptckpt */
    char ref[256];   /* DIR/ref.exr: the render never interrupted */
} Paths;

static void paths_init(Paths *p)
{
    snprintf(p->dir, sizeof p->dir, "%s", test_temp_dir());
    snprintf(p->exr, sizeof p->exr, "%s/out.exr", p->dir);
    snprintf(p->ckpt, sizeof p->ckpt, "%s.ptckpt", p->exr);
    snprintf(p->ref, sizeof p->ref, "%s/ref.exr", p->dir);
}

static Run pt(const char *env, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static Run pt(const char *env, const char *fmt, ...)
{
    char args[2048];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(args, sizeof args, fmt, ap);
    va_end(ap);
    return run_pt_env(NULL, env, args);
}

static bool killed(Run r) { return r.exit_code == -1 || r.exit_code == 128 + 9; }

static void render_reference(const Paths *p)
{
    Run r = pt(NULL, SCENE " " FILM " -o %s", p->ref);
    cr_assert_eq(r.exit_code, 0, "the reference render: %s", r.err);
}

/* Every float of the two EXRs' rgb alike, bit for bit. */
static void expect_same_pixels(const char *a, const char *b, const char *what)
{
    float *pa = NULL, *pb = NULL;
    int wa, ha, wb, hb;
    Error err = {0};
    cr_assert(image_read_exr(a, &pa, &wa, &ha, &err), "%s", err.message);
    cr_assert(image_read_exr(b, &pb, &wb, &hb, &err), "%s", err.message);
    cr_assert(wa == wb && ha == hb);
    size_t n = (size_t)wa * ha * 3, differ = 0, first = 0;
    for (size_t i = 0; i < n; i++)
        if (memcmp(&pa[i], &pb[i], sizeof(float)) != 0 && !differ++)
            first = i;
    cr_expect_eq(differ, 0, "%s: %zu of %zu values differ (first: value %zu, %.9g vs %.9g)", what,
                 differ, n, first, differ ? pa[first] : 0.0, differ ? pb[first] : 0.0);
    free(pa), free(pb);
}

/* Stage 1: stopped (SIGTERM) after the first run: a checkpoint is saved. */
static void stop_after_one_run(const Paths *p, const char *env, const char *devices)
{
    char e[256];
    snprintf(e, sizeof e, "%s PT_TEST_RAISE=SIGTERM@unit:1", env);
    Run r = pt(e, SCENE " " FILM " %s --checkpoint 0.001 -o %s", devices, p->exr);
    cr_assert_eq(r.exit_code, 143, "the first stage: exit %d: %s", r.exit_code, r.err);
    cr_assert_eq(access(p->ckpt, F_OK), 0, "no checkpoint after a stopped render: %s", r.err);
}

/* Stage 3: resumed to the end; the checkpoint goes, the pixels are the reference's. */
static void resume_to_the_end(const Paths *p, const char *env, const char *devices,
                              const char *what)
{
    Run r = pt(env, SCENE " " FILM " %s --resume -o %s", devices, p->exr);
    cr_assert_eq(r.exit_code, 0, "%s: the resumed render: exit %d: %s", what, r.exit_code, r.err);
    cr_expect_neq(access(p->ckpt, F_OK), 0, "%s: the checkpoint is left after a complete render",
                  what);
    expect_same_pixels(p->ref, p->exr, what);
}

/* The pseudo-random kill points: seeded from PT_TEST_SEED, else the clock; printed, so that a
 * failure can be replayed. */
static unsigned kill_seed(void)
{
    const char *given = getenv("PT_TEST_SEED");
    unsigned seed = given ? (unsigned)strtoul(given, NULL, 10) : (unsigned)time(NULL);
    fprintf(stderr, "test_checkpoint: kill points from PT_TEST_SEED=%u\n", seed);
    return seed;
}

static void kill_and_resume(const char *env, const char *killed_devices,
                            const char *resumed_devices, int rounds)
{
    Paths p;
    paths_init(&p);
    render_reference(&p);
    unsigned seed = kill_seed();
    for (int round = 0; round < rounds; round++) {
        unsigned n = 1 + (seed = seed * 1103515245u + 12345u) / 65536u % 3u;
        char what[128], e[256];
        snprintf(what, sizeof what, "round %d: SIGKILL at run %u", round, n);
        fprintf(stderr, "test_checkpoint: %s (%s)\n", what, killed_devices);
        stop_after_one_run(&p, env, killed_devices);
        snprintf(e, sizeof e, "%s PT_TEST_RAISE=SIGKILL@unit:%u", env, n);
        Run r = pt(e, SCENE " " FILM " %s --checkpoint 0.001 --resume -o %s", killed_devices,
                   p.exr);
        cr_assert(killed(r), "%s: not killed: exit %d: %s", what, r.exit_code, r.err);
        cr_assert_eq(access(p.ckpt, F_OK), 0, "%s: the checkpoint is gone", what);
        resume_to_the_end(&p, env, resumed_devices, what);
    }
}

Test(checkpoint, sigkill_at_a_random_run_then_resume_is_bit_identical, .timeout = 600)
{
    kill_and_resume("", "", "", 3);
}

/* Killed while both devices render, resumed on one. */
Test(checkpoint, sigkill_with_two_devices_resumed_on_one_is_bit_identical, .timeout = 600)
{
    kill_and_resume(TWO_DEVICES, "--device all", "", 2);
}

/* A kill right after a periodic checkpoint, or during the write of a file (the checkpoint's
 * temporary copy or the image's, complete but not renamed): whichever comes first, what is on
 * disk resumes to the same bits. */
Test(checkpoint, sigkill_at_a_checkpoint_or_a_write_then_resume_is_bit_identical, .timeout = 600)
{
    Paths p;
    paths_init(&p);
    render_reference(&p);
    const char *points[] = {"checkpoint:1", "checkpoint:2", "write:1"};
    for (size_t i = 0; i < sizeof points / sizeof points[0]; i++) {
        stop_after_one_run(&p, "", "");
        char e[128];
        snprintf(e, sizeof e, "PT_TEST_RAISE=SIGKILL@%s", points[i]);
        Run r = pt(e, SCENE " " FILM " --checkpoint 0.001 --resume -o %s", p.exr);
        fprintf(stderr, "test_checkpoint: %s: %s\n", e, killed(r) ? "killed" : "not reached");
        if (!killed(r)) { /* no periodic checkpoint came before the end: a whole render */
            cr_assert_eq(r.exit_code, 0, "%s: exit %d: %s", e, r.exit_code, r.err);
            cr_expect_neq(access(p.ckpt, F_OK), 0, "%s: the checkpoint is left", e);
            expect_same_pixels(p.ref, p.exr, e);
            continue;
        }
        resume_to_the_end(&p, "", "", e);
    }
}

/* Killed while the image of a complete resumed render is written (no periodic checkpoints: the
 * first file written is the image): the checkpoint must still be there for the next --resume. */
Test(checkpoint, sigkill_while_the_image_is_written_keeps_the_checkpoint, .timeout = 600)
{
    Paths p;
    paths_init(&p);
    render_reference(&p);
    stop_after_one_run(&p, "", "");
    Run r = pt("PT_TEST_RAISE=SIGKILL@write:1", SCENE " " FILM " --resume -o %s", p.exr);
    cr_assert(killed(r), "not killed: exit %d: %s", r.exit_code, r.err);
    cr_assert_eq(access(p.ckpt, F_OK), 0, "the checkpoint went before the image was written");
    resume_to_the_end(&p, "", "", "killed during the image's write");
}

/* A checkpoint holding every unit (a crash after the last periodic checkpoint, before the image):
 * --resume renders nothing and writes the image of its film. Made here with zero sums (a black
 * image) for FILM's render of SCENE. */
Test(checkpoint, a_complete_checkpoint_resumes_to_its_image, .timeout = 600)
{
    Paths p;
    paths_init(&p);
    Scene scene;
    Error err = {0};
    warnings_set_quiet(true);
    cr_assert(scene_load("scenes/cornell-box", &scene, &err), "%s", err.message);
    scene.desc.width = 64, scene.desc.height = 48;
    RenderSettings settings = {.spp = 8, .max_depth = 4};
    UnitGrid grid;
    cr_assert(unit_grid_init(&grid, 64, 48, 8, 0, 8, &err), "%s", err.message);
    RenderIdentity id = render_identity(&scene, &settings, &grid);
    scene_free(&scene);
    UnitFilm film;
    cr_assert(unit_film_init(&film, &grid, &err));
    for (uint32_t u = 0; u < grid.count; u++)
        unit_bitmap_set(film.done, u);
    film.units_done = grid.count;
    cr_assert(checkpoint_write(p.ckpt, id, &film, &err), "%s", err.message);
    unit_film_free(&film);
    Run r = pt(NULL, SCENE " " FILM " --resume -o %s", p.exr);
    cr_assert_eq(r.exit_code, 0, "exit %d: %s", r.exit_code, r.err);
    cr_expect_neq(access(p.ckpt, F_OK), 0, "the checkpoint is left after a complete render");
    float *rgb = NULL;
    int w, h;
    cr_assert(image_read_exr(p.exr, &rgb, &w, &h, &err), "%s", err.message);
    for (int i = 0; i < w * h * 3; i++)
        cr_expect_eq(rgb[i], 0.0f, "value %d: %g, not the checkpoint's black", i, rgb[i]);
    free(rgb);
}

Test(checkpoint, another_scene_or_other_settings_are_refused, .timeout = 600)
{
    Paths p;
    paths_init(&p);
    stop_after_one_run(&p, "", "");
    Run r = pt(NULL, SCENE "/mirror.json " FILM " --resume -o %s", p.exr);
    expect_clean_error(r, "another scene", p.ckpt, "made for another scene");
    r = pt(NULL, SCENE " " FILM " --spp 16 --resume -o %s", p.exr);
    expect_clean_error(r, "other spp", p.ckpt, "spp 8 in it, 16 here");
    r = pt(NULL, SCENE " " FILM " --unit-spp 2 --resume -o %s", p.exr);
    expect_clean_error(r, "other units", p.ckpt, "unit size differs");
    r = pt(NULL, SCENE " " FILM " --seed 5 --resume -o %s", p.exr);
    expect_clean_error(r, "other seed", p.ckpt, "seed 0 in it, 5 here");
    /* Refused, the checkpoint stays for the right command. */
    r = pt(NULL, SCENE " " FILM " --resume -o %s", p.exr);
    cr_expect_eq(r.exit_code, 0, "the right command after the refusals: %s", r.err);
}

static void write_bytes(const char *path, const void *data, size_t size)
{
    FILE *file = fopen(path, "wb");
    cr_assert(file);
    cr_assert_eq(fwrite(data, 1, size, file), size);
    fclose(file);
}

Test(checkpoint, truncated_damaged_or_other_version_are_refused, .timeout = 600)
{
    Paths p;
    paths_init(&p);
    stop_after_one_run(&p, "", "");
    size_t size;
    uint8_t *good = (uint8_t *)test_read_file(p.ckpt, &size), *bad = malloc(size);
    cr_assert(good && bad && size > 200);

    write_bytes(p.ckpt, good, size / 2);
    expect_clean_error(pt(NULL, SCENE " " FILM " --resume -o %s", p.exr), "truncated", p.ckpt,
                       "truncated checkpoint");
    memcpy(bad, good, size);
    bad[8] = 2; /* the format version */
    write_bytes(p.ckpt, bad, size);
    expect_clean_error(pt(NULL, SCENE " " FILM " --resume -o %s", p.exr), "version", p.ckpt,
                       "checkpoint format version 2");
    memcpy(bad, good, size);
    bad[size / 2] ^= 0x10; /* a film word */
    write_bytes(p.ckpt, bad, size);
    expect_clean_error(pt(NULL, SCENE " " FILM " --resume -o %s", p.exr), "damaged", p.ckpt,
                       "checksum mismatch");
    memcpy(bad, good, size);
    memcpy(bad, "GIF89a\0\0", 8);
    write_bytes(p.ckpt, bad, size);
    expect_clean_error(pt(NULL, SCENE " " FILM " --resume -o %s", p.exr), "magic", p.ckpt,
                       "not a pt checkpoint");
    write_bytes(p.ckpt, good, 0);
    expect_clean_error(pt(NULL, SCENE " " FILM " --resume -o %s", p.exr), "empty", p.ckpt,
                       "not a pt checkpoint");
    free(good), free(bad);
}

Test(checkpoint, resume_with_nothing_to_resume_is_refused, .timeout = 600)
{
    Paths p;
    paths_init(&p);
    Run r = pt(NULL, SCENE " " FILM " --resume -o %s", p.exr);
    expect_clean_error(r, "--resume without a checkpoint", p.ckpt, "start without --resume");
    cr_expect_neq(access(p.exr, F_OK), 0, "an image was written");
}

/* A checkpoint is never overwritten unless --resume continues it. */
Test(checkpoint, a_checkpoint_left_without_resume_is_refused, .timeout = 600)
{
    Paths p;
    paths_init(&p);
    stop_after_one_run(&p, "", "");
    size_t before_size, after_size;
    char *before = test_read_file(p.ckpt, &before_size);
    Run r = pt(NULL, SCENE " " FILM " --checkpoint 10 -o %s", p.exr);
    expect_clean_error(r, "a checkpoint without --resume", p.ckpt, "continue it with --resume");
    char *after = test_read_file(p.ckpt, &after_size);
    cr_expect(before && after && before_size == after_size && !memcmp(before, after, before_size),
              "the checkpoint changed");
    free(before), free(after);
}

/* The kill points' syntax (app/stop_signals.h): a count from 1, a known point; else one line. */
Test(checkpoint, malformed_kill_points_are_one_clear_line, .timeout = 600)
{
    const char *bad[] = {"SIGKILL@unit:0", "SIGKILL@unit:", "SIGKILL@unit:x", "SIGKILL@unit:-1",
                         "SIGKILL@unit:5x", "KILL@units", "SIGKILL@", "SIGSTOP@unit"};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        char env[64];
        snprintf(env, sizeof env, "PT_TEST_RAISE=%s", bad[i]);
        expect_clean_error(pt(env, SCENE " " FILM " -o /dev/null.exr"), bad[i], bad[i],
                           "expected SIGNAL@POINT or SIGNAL@POINT:COUNT");
    }
}
