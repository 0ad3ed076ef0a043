// SPDX-License-Identifier: MIT
/* program_background.c: a part of a device's program built on a thread of its own while the
 * render goes on (device_build_in_background, device.h): its start, its registry (joined at exit),
 * and its taking in by the render's thread. */
#include "device/device_internal.h"

#include "base/clock.h"

#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>

struct BackgroundBuild {
    pthread_t thread;
    Device *dev;
    int part;
    atomic_bool done;
    bool ok, compiled;
    cl_program program;
    double seconds;
    Error err;
};

static void *build_in_background(void *arg)
{
    BackgroundBuild *b = arg;
    double start = seconds_now();
    b->ok = program_build_part_program(b->dev, b->part, false, &b->program, &b->compiled, &b->err);
    b->seconds = seconds_now() - start;
    atomic_store(&b->done, true);
    return NULL;
}

/* The builds under way, joined at exit: a die() on the render's thread must not run the exit
 * handlers (the driver's among them) while a compile is inside the driver. */
#define MAX_BACKGROUND_BUILDS 64
static pthread_mutex_t background_lock = PTHREAD_MUTEX_INITIALIZER;
static BackgroundBuild *background_builds[MAX_BACKGROUND_BUILDS];

static void join_background_builds_at_exit(void)
{
    pthread_mutex_lock(&background_lock);
    for (int i = 0; i < MAX_BACKGROUND_BUILDS; i++)
        if (background_builds[i])
            pthread_join(background_builds[i]->thread, NULL), background_builds[i] = NULL;
    pthread_mutex_unlock(&background_lock);
}

/* Starts b's thread (with room on its stack for a compiler) and registers it; false when no
 * thread can be had. */
static bool start_background_build(BackgroundBuild *b)
{
    static atomic_bool registered;
    if (!atomic_exchange(&registered, true))
        atexit(join_background_builds_at_exit);
    pthread_mutex_lock(&background_lock);
    int slot = -1;
    for (int i = 0; i < MAX_BACKGROUND_BUILDS && slot < 0; i++)
        if (!background_builds[i])
            slot = i;
    bool started = false;
    pthread_attr_t attr;
    if (slot >= 0 && pthread_attr_init(&attr) == 0) {
        pthread_attr_setstacksize(&attr, 64u << 20);
        started = pthread_create(&b->thread, &attr, build_in_background, b) == 0;
        pthread_attr_destroy(&attr);
    }
    if (started)
        background_builds[slot] = b;
    pthread_mutex_unlock(&background_lock);
    return started;
}

/* Takes in the background build's part once it is done (at once when `wait`): then
 * dev->programs[part] is set; a failed build is a warning (the render goes on without the part,
 * which device_kernel_ready no longer offers; device_kernel builds it again, and fails there). */
static void take_background_build(Device *dev, bool wait)
{
    BackgroundBuild *b = dev->background;
    if (!b || (!wait && !atomic_load(&b->done)))
        return;
    pthread_mutex_lock(&background_lock);
    for (int i = 0; i < MAX_BACKGROUND_BUILDS; i++)
        if (background_builds[i] == b)
            background_builds[i] = NULL;
    pthread_mutex_unlock(&background_lock);
    pthread_join(b->thread, NULL); /* outside the lock: another device's build may go on */
    dev->background = NULL;
    if (b->ok) {
        dev->programs[b->part] = b->program;
        dev->build_seconds += b->seconds;
        if (b->compiled)
            dev->cache_hit = false;
    } else {
        dev->parts_failed |= 1u << b->part;
        warn("%s (the %s part, built beside the render: going on without it)", b->err.message,
             program_parts[b->part].name);
    }
    free(b);
}

void device_build_in_background(Device *dev, const char *name)
{
    int part = dev->whole_program ? 0 : program_part_of_kernel(name);
    if (dev->programs[part] || dev->background || (dev->parts_failed & 1u << part))
        return;
    /* A part the kernel cache has loads in milliseconds: then now, so that the render has it from
     * its first window. */
    bool cached = program_part_cached(dev, part);
    BackgroundBuild *b = cached ? NULL : calloc(1, sizeof *b);
    if (b) {
        b->dev = dev, b->part = part;
        atomic_init(&b->done, false);
        if (start_background_build(b)) {
            dev->background = b;
            return;
        }
        free(b);
    }
    Error err = {0};
    if (!program_build_part(dev, part, &err)) /* cached, or no thread could be had */
        die("%s", err.message);
}

cl_kernel device_kernel_ready(Device *dev, const char *name)
{
    take_background_build(dev, false);
    int part = dev->whole_program ? 0 : program_part_of_kernel(name);
    if (!dev->programs[part] || (dev->parts_failed & 1u << part))
        return NULL;
    return device_kernel(dev, name);
}

void device_finish_background_build(Device *dev)
{
    BackgroundBuild *b = dev->background;
    /* A first render shorter than the build waits for it here, once: say why. */
    if (b && program_build_notice() && !atomic_load(&b->done)) {
        char part[PROGRAM_PART_WORD_SIZE];
        program_part_word(b->part, part);
        fprintf(stderr, "pt: finishing the kernels of the %s part for the next renders (first time "
                "only) ...\n", part);
        fflush(stderr);
    }
    take_background_build(dev, true);
}

void program_wait_for_background_part(Device *dev, int part)
{
    if (dev->background && dev->background->part == part)
        take_background_build(dev, true);
}
