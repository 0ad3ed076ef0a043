// SPDX-License-Identifier: MIT
/* The kernel cache and the program's parts (issue 39): the cache key follows every build option;
 * two processes building one entry at once both succeed and leave one whole entry; the cache stays
 * under its size bound by dropping the least recently used entries; the program is built in parts,
 * the device's own part first and the others when a kernel of theirs is first asked for. */
#include <criterion/criterion.h>
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/time.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "device/device.h"
#include "device/kernel_cache.h"
#include "support.h"

static const char *fresh_cache(void)
{
    const char *dir = test_temp_dir();
    setenv("XDG_CACHE_HOME", dir, 1);
    unsetenv("PT_NO_CACHE");
    unsetenv("PT_CL_OPTIONS");
    unsetenv("PT_KERNEL_CACHE_MB");
    unsetenv("PT_PROGRAM_PARTS");
    unsetenv("PT_CACHE_BINARIES");
    return dir;
}

/* Files named kernels-*.bin in the cache folder. */
static int count_entries(void)
{
    DIR *d = opendir(kernel_cache_dir());
    int n = 0;
    for (struct dirent *e; d && (e = readdir(d));)
        n += strncmp(e->d_name, "kernels-", 8) == 0 && strstr(e->d_name, ".bin") &&
             !strstr(e->d_name, ".tmp");
    if (d)
        closedir(d);
    return n;
}

static bool build_probe(Device *dev, const char *extra, Error *err)
{
    return device_open(dev, "cpu", err) &&
           device_build(dev, PROGRAM_FEATURES_ALL, extra, "probe.cl", err);
}

/* A build option the user changes (PT_CL_OPTIONS) or a changed source is another entry, never the
 * old binary. */
Test(kernel_cache, key_follows_options_and_source, .timeout = 600)
{
    fresh_cache();
    const char *extra = "kernel void cache_key_probe(global int *x) { x[0] = 1; }";
    Error err = {0};
    Device a, b, c, d;
    cr_assert(build_probe(&a, extra, &err), "%s", err.message);
    cr_expect_not(a.cache_hit);
    setenv("PT_CL_OPTIONS", "-cl-mad-enable", 1);
    cr_assert(build_probe(&b, extra, &err), "%s", err.message);
    cr_expect_not(b.cache_hit, "other build options must not load the first binary");
    unsetenv("PT_CL_OPTIONS");
    cr_assert(build_probe(&c, "kernel void cache_key_probe(global int *x) { x[0] = 2; }", &err),
              "%s", err.message);
    cr_expect_not(c.cache_hit, "another source must not load the first binary");
    cr_assert(build_probe(&d, extra, &err), "%s", err.message);
    cr_expect(d.cache_hit, "the first program again comes from the cache");
    cr_expect_eq(count_entries(), 3);
    device_close(&a), device_close(&b), device_close(&c), device_close(&d);
}

/* Two processes that build the same program into an empty cache at the same moment (they wait on
 * one pipe, then build) both succeed, and leave one whole entry that a third build loads. */
Test(kernel_cache, two_processes_build_one_entry, .timeout = 900)
{
    fresh_cache();
    const char *extra = "kernel void cache_race_probe(global int *x) { x[0] = 3; }";
    int go[2];
    cr_assert_eq(pipe(go), 0);
    pid_t children[2];
    for (int i = 0; i < 2; i++) {
        children[i] = fork();
        cr_assert(children[i] >= 0);
        if (children[i] == 0) {
            close(go[1]);
            char byte;
            if (read(go[0], &byte, 1) != 1)
                _exit(3);
            Device dev;
            Error err = {0};
            bool ok = build_probe(&dev, extra, &err);
            if (!ok)
                fprintf(stderr, "child %d: %s\n", i, err.message);
            _exit(ok ? 0 : 1);
        }
    }
    close(go[0]);
    cr_assert_eq(write(go[1], "gg", 2), 2); /* both start now */
    close(go[1]);
    for (int i = 0; i < 2; i++) {
        int status = 0;
        cr_assert_eq(waitpid(children[i], &status, 0), children[i]);
        cr_expect(WIFEXITED(status) && WEXITSTATUS(status) == 0, "child %d failed (status %d)", i,
                  status);
    }
    cr_expect_eq(count_entries(), 1, "one entry, no temporary files left");
    Device third;
    Error err = {0};
    cr_assert(build_probe(&third, extra, &err), "%s", err.message);
    cr_expect(third.cache_hit, "the entry the two wrote is whole");
    device_close(&third);
}

static void store_entry(uint64_t key, size_t size, time_t used)
{
    unsigned char *data = calloc(size, 1);
    cr_assert(data);
    data[0] = (unsigned char)key;
    kernel_cache_store(key, data, size);
    free(data);
    char path[1200];
    snprintf(path, sizeof path, "%s/kernels-%016llx-v2.bin", kernel_cache_dir(),
             (unsigned long long)key);
    struct timeval times[2] = {{.tv_sec = used}, {.tv_sec = used}};
    cr_assert_eq(utimes(path, times), 0, "%s", path);
}

static bool entry_exists(uint64_t key)
{
    char path[1200];
    snprintf(path, sizeof path, "%s/kernels-%016llx-v2.bin", kernel_cache_dir(),
             (unsigned long long)key);
    struct stat st;
    return stat(path, &st) == 0;
}

/* Over PT_KERNEL_CACHE_MB the least recently used entries go, and a load counts as a use. */
Test(kernel_cache, size_bound_drops_least_recently_used)
{
    fresh_cache();
    setenv("PT_KERNEL_CACHE_MB", "1", 1);
    const size_t size = 300 << 10; /* four of these are over 1 MiB, three are not */
    store_entry(1, size, 1000);
    store_entry(2, size, 2000);
    store_entry(3, size, 3000);
    cr_expect(entry_exists(1) && entry_exists(2) && entry_exists(3), "under the bound: all kept");
    unsigned char *data;
    size_t got;
    cr_assert(kernel_cache_load(1, &data, &got)); /* entry 1 is used now: the newest */
    cr_expect_eq(got, size);
    free(data);
    store_entry(4, size, time(NULL));
    /* 1.2 MiB > 1 MiB: drop the oldest until at most 768 KiB remain, i.e. two entries. */
    cr_expect_not(entry_exists(2), "the least recently used entry is dropped");
    cr_expect_not(entry_exists(3), "then the next");
    cr_expect(entry_exists(1), "an entry just loaded stays");
    cr_expect(entry_exists(4), "the entry just stored stays");
    unsetenv("PT_KERNEL_CACHE_MB");
}

/* Without kernels of its own the program is built in parts: on a CPU the megakernel's first, the
 * wavefront's when one of its kernels is asked for; each part lacks the other's big kernels; the
 * second part's build time adds to the total. PT_PROGRAM_PARTS=0 builds it whole. */
Test(kernel_cache, program_parts_built_when_needed, .timeout = 900)
{
    fresh_cache();
    Device dev;
    Error err = {0};
    cr_assert(device_open(&dev, "cpu", &err), "%s", err.message);
    dev.use_cache = false;
    cr_assert(device_build(&dev, 0, NULL, NULL, &err), "%s", err.message);
    cr_expect_not_null(dev.programs[PROGRAM_PART_MEGAKERNEL], "the CPU's own part first");
    cr_expect_null(dev.programs[PROGRAM_PART_CORE], "the wavefront's part is not built yet");
    cr_expect_null(dev.programs[PROGRAM_PART_AOV]);
    double first = dev.build_seconds;
    cl_int status;
    cl_kernel missing = clCreateKernel(dev.programs[PROGRAM_PART_MEGAKERNEL], "shade_surface", &status);
    cr_expect_eq(status, CL_INVALID_KERNEL_NAME, "the megakernel's part has no shade_surface");
    if (missing)
        clReleaseKernel(missing);
    cl_kernel closest = device_kernel(&dev, "intersect_closest");
    cr_expect_not_null(dev.programs[PROGRAM_PART_CORE], "asking for intersect_closest built its part");
    cr_expect_gt(dev.build_seconds, first);
    cl_kernel trace = device_kernel(&dev, "trace_paths");
    cr_expect_not_null(trace);
    cr_expect_null(dev.programs[PROGRAM_PART_AOV], "no render_aov was asked for");
    clReleaseKernel(closest);
    clReleaseKernel(trace);
    device_close(&dev);

    setenv("PT_PROGRAM_PARTS", "0", 1);
    Device whole;
    cr_assert(device_open(&whole, "cpu", &err), "%s", err.message);
    whole.use_cache = false;
    cr_assert(device_build(&whole, 0, NULL, NULL, &err), "%s", err.message);
    cl_kernel aov = device_kernel(&whole, "render_aov");
    cr_expect_not_null(aov);
    cr_expect_null(whole.programs[PROGRAM_PART_AOV], "a whole program is programs[0] alone");
    clReleaseKernel(aov);
    device_close(&whole);
    unsetenv("PT_PROGRAM_PARTS");
}

/* A part a render can do without (the wavefront's tail) builds on a thread of its own when the
 * kernel cache does not have it, and at once when it does; device_kernel and device_close wait for
 * a build under way rather than start another or leave it running. */
Test(kernel_cache, part_built_in_background, .timeout = 900)
{
    fresh_cache();
    Error err = {0};
    Device dev;
    cr_assert(device_open(&dev, "cpu", &err), "%s", err.message);
    cr_assert(device_build(&dev, 0, NULL, NULL, &err), "%s", err.message);
    device_build_in_background(&dev, "finish_paths");
    cr_expect_not_null(dev.background, "an empty cache: the part builds on a thread");
    cr_expect_null(dev.programs[PROGRAM_PART_TAIL], "taken in only by the render's thread");
    device_finish_background_build(&dev);
    cr_expect_null(dev.background);
    cr_expect_not_null(dev.programs[PROGRAM_PART_TAIL], "the finished build was taken in");
    cl_kernel ready = device_kernel_ready(&dev, "finish_paths");
    cr_expect_not_null(ready);
    device_build_in_background(&dev, "finish_paths");
    cr_expect_null(dev.background, "a part already built is not built again");
    clReleaseKernel(ready);
    device_close(&dev);

    Device again; /* the entry the thread stored: at once */
    cr_assert(device_open(&again, "cpu", &err), "%s", err.message);
    cr_assert(device_build(&again, 0, NULL, NULL, &err), "%s", err.message);
    device_build_in_background(&again, "finish_paths");
    cr_expect_null(again.background, "a cached part is built at once");
    cr_expect_not_null(again.programs[PROGRAM_PART_TAIL]);
    device_close(&again);

    Device waits; /* device_kernel waits for the thread's build */
    cr_assert(device_open(&waits, "cpu", &err), "%s", err.message);
    waits.use_cache = false;
    cr_assert(device_build(&waits, 0, NULL, NULL, &err), "%s", err.message);
    device_build_in_background(&waits, "finish_paths");
    cr_expect_not_null(waits.background);
    cl_kernel k = device_kernel(&waits, "finish_paths");
    cr_expect_not_null(k);
    cr_expect_null(waits.background, "device_kernel took the thread's build in");
    clReleaseKernel(k);
    device_close(&waits);

    /* Closed while the thread builds: device_close waits for it, which then stored its part (a
     * close that left it running would find the entry missing: the compile takes a second). */
    fresh_cache();
    Device closed;
    cr_assert(device_open(&closed, "cpu", &err), "%s", err.message);
    cr_assert(device_build(&closed, 0, NULL, NULL, &err), "%s", err.message);
    int before = count_entries();
    device_build_in_background(&closed, "finish_paths");
    cr_expect_not_null(closed.background);
    device_close(&closed);
    cr_expect_eq(count_entries(), before + 1, "the part's entry is stored when device_close returns");
}

/* The one entry's key and size (the cache holds exactly one). */
static uint64_t only_entry(long *size)
{
    DIR *d = opendir(kernel_cache_dir());
    cr_assert(d);
    unsigned long long key = 0;
    int found = 0;
    for (struct dirent *e; (e = readdir(d));)
        if (sscanf(e->d_name, "kernels-%16llx-v2.bin", &key) == 1 && !strstr(e->d_name, ".tmp")) {
            char path[1200];
            snprintf(path, sizeof path, "%s/%s", kernel_cache_dir(), e->d_name);
            struct stat st;
            cr_assert_eq(stat(path, &st), 0);
            *size = (long)st.st_size;
            found++;
        }
    closedir(d);
    cr_assert_eq(found, 1, "one entry");
    return key;
}

static bool build_cornell_part(Device *dev, Error *err)
{
    return device_open(dev, "cpu", err) && device_build(dev, 0, NULL, NULL, err);
}

/* PoCL keeps its programs itself: pt's entry is a small marker, not a binary (asking PoCL for one
 * compiles every kernel); the marker makes the next build a cache hit, and an entry that is not a
 * marker is rebuilt over. */
Test(kernel_cache, pocl_entry_is_a_marker, .timeout = 900)
{
    fresh_cache();
    Device a, b, c, d;
    Error err = {0};
    cr_assert(build_cornell_part(&a, &err), "%s", err.message);
    cr_assert(strstr(a.platform_name, "Portable Computing Language"), "the test device is PoCL");
    cr_expect_not(a.cache_hit);
    long size = 0;
    uint64_t key = only_entry(&size);
    cr_expect_lt(size, 1024, "a marker, not a program binary (%ld bytes)", size);
    cr_assert(build_cornell_part(&b, &err), "%s", err.message);
    cr_expect(b.cache_hit, "the marker is a hit");
    cl_kernel trace = device_kernel(&b, "trace_paths");
    cr_expect_not_null(trace);
    clReleaseKernel(trace);
    /* A whole entry (its checksum right) that is not a marker: rebuilt, and the marker is back. */
    kernel_cache_store(key, (const unsigned char *)"not a marker", 12);
    cr_assert(build_cornell_part(&c, &err), "%s", err.message);
    cr_expect_not(c.cache_hit, "a foreign entry is no hit");
    cr_assert(build_cornell_part(&d, &err), "%s", err.message);
    cr_expect(d.cache_hit, "the rebuild stored the marker again");
    device_close(&a), device_close(&b), device_close(&c), device_close(&d);
}

/* PT_CACHE_BINARIES=1 stores the program binary on PoCL too, and the next build loads it. */
Test(kernel_cache, binaries_when_asked, .timeout = 900)
{
    fresh_cache();
    setenv("PT_CACHE_BINARIES", "1", 1);
    Device a, b;
    Error err = {0};
    cr_assert(build_cornell_part(&a, &err), "%s", err.message);
    cr_expect_not(a.cache_hit);
    long size = 0;
    only_entry(&size);
    cr_expect_gt(size, 64 << 10, "a program binary (%ld bytes)", size);
    cr_assert(build_cornell_part(&b, &err), "%s", err.message);
    cr_expect(b.cache_hit, "the binary is loaded");
    cl_kernel trace = device_kernel(&b, "trace_paths");
    cr_expect_not_null(trace);
    clReleaseKernel(trace);
    device_close(&a), device_close(&b);
    unsetenv("PT_CACHE_BINARIES");
}
