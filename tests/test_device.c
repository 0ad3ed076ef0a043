// SPDX-License-Identifier: MIT
/* Device layer: the program builds on PoCL, shared structs have the same layout on both sides, bad
 * device specs and oversized allocations are reported, a broken kernel shows its build log. */
#include <criterion/criterion.h>
#include <stdlib.h>
#include <string.h>

#include "device/device.h"
#include "device/device_internal.h"
#include "base/shared_types.h"
#include "support.h"

/* The host's side of report_layout (tests/cl/sizes.cl), word for word, with names for messages. */
typedef struct {
    cl_uint words[SHARED_LAYOUT_WORDS];
    const char *names[SHARED_LAYOUT_WORDS];
} Layout;

static void host_layout(Layout *l)
{
    size_t i = 0;
#define HOST_STRUCT(type, size) l->names[i] = "sizeof(" #type ")", l->words[i++] = sizeof(type);
#define HOST_FIELD(type, field)                                                                    \
    l->names[i] = "offsetof(" #type ", " #field ")", l->words[i++] = offsetof(type, field);        \
    l->names[i] = "sizeof(" #type "." #field ")", l->words[i++] = sizeof(((type *)0)->field);
    SHARED_STRUCTS(HOST_STRUCT, HOST_FIELD)
#undef HOST_STRUCT
#undef HOST_FIELD
}

/* Every field starts where the one before it ends and the last ends at sizeof: no field of a
 * shared struct is left out of SHARED_STRUCTS, and no compiler inserts padding. Returns the number
 * of gaps. */
static int layout_gaps(const Layout *l)
{
    int gaps = 0;
    size_t i = 0, end = 0, struct_size = 0;
    const char *struct_name = NULL;
#define CHECK_END()                                                                                \
    if (struct_name && end != struct_size) {                                                       \
        cr_log_error("%s: fields end at %zu", struct_name, end);                                   \
        gaps++;                                                                                    \
    }
#define GAP_STRUCT(type, size)                                                                     \
    CHECK_END();                                                                                   \
    struct_name = l->names[i], struct_size = l->words[i++], end = 0;
#define GAP_FIELD(type, field)                                                                     \
    if (l->words[i] != end) {                                                                      \
        cr_log_error("%s = %u, the field before ends at %zu", l->names[i], l->words[i], end);      \
        gaps++;                                                                                    \
    }                                                                                              \
    end = (size_t)l->words[i] + l->words[i + 1], i += 2;
    SHARED_STRUCTS(GAP_STRUCT, GAP_FIELD)
    CHECK_END();
#undef GAP_STRUCT
#undef GAP_FIELD
#undef CHECK_END
    return gaps;
}

Test(device, shared_struct_layout_matches_host)
{
    Device *dev = test_device();
    Error err = {0};
    cl_mem out = device_buffer(dev, "layout", CL_MEM_WRITE_ONLY, SHARED_LAYOUT_WORDS * sizeof(cl_uint),
                               NULL, &err);
    cl_kernel kernel = device_kernel(dev, "report_layout");
    KERNEL_ARGS(kernel, 0, KARG(out));
    device_run(dev, kernel, 1, 1, NULL);
    static Layout host;
    host_layout(&host);
    cl_uint device[SHARED_LAYOUT_WORDS];
    device_read(dev, out, 0, sizeof device, device);
    for (size_t i = 0; i < SHARED_LAYOUT_WORDS; i++)
        cr_expect_eq(device[i], host.words[i], "%s: device %u, host %u", host.names[i], device[i],
                     host.words[i]);
    cr_expect_eq(layout_gaps(&host), 0, "the host's shared structs have gaps or unlisted fields");
    clReleaseKernel(kernel);
    clReleaseMemObject(out);
    test_device_release(dev);
}

Test(device, unknown_device_is_an_error)
{
    const char *specs[] = {"tpu", "9:0", "0:99", "x:y", "0:"};
    for (size_t i = 0; i < sizeof specs / sizeof specs[0]; i++) {
        Device dev;
        Error err = {0};
        cr_expect_not(device_open(&dev, specs[i], &err), "spec %s", specs[i]);
        cr_expect_eq(err.code, ERR_DEVICE_UNKNOWN, "spec %s", specs[i]);
        cr_expect(strstr(err.message, specs[i]) != NULL, "message names the spec: %s", err.message);
    }
}

Test(device, bvh_width_comes_from_the_device_type_or_pt_bvh_width)
{
    Device dev;
    Error err = {0};
    unsetenv("PT_BVH_WIDTH");
    cr_assert(device_open(&dev, "cpu", &err), "%s", err.message);
    cr_expect_eq(dev.bvh_width, 8, "a CPU walks the 8-wide BVH");
    cr_expect(strstr(device_build_options(&dev), "-DBVH_WIDTH=8") != NULL, "%s", device_build_options(&dev));
    device_close(&dev);
    setenv("PT_BVH_WIDTH", "4", 1);
    cr_assert(device_open(&dev, "cpu", &err), "%s", err.message);
    cr_expect_eq(dev.bvh_width, 4);
    device_close(&dev);
    setenv("PT_BVH_WIDTH", "3", 1);
    cr_expect_not(device_open(&dev, "cpu", &err));
    cr_expect_eq(err.code, ERR_SETTINGS);
    cr_expect(strstr(err.message, "PT_BVH_WIDTH=3") != NULL, "%s", err.message);
    setenv("PT_BVH_WIDTH", "2", 1);
    setenv("PT_BVH_QUANTIZED", "1", 1);
    err = (Error){0};
    cr_assert(device_open(&dev, "cpu", &err), "%s", err.message);
    cr_expect(dev.bvh_quantized);
    cr_expect(strstr(device_build_options(&dev), "-DBVH_QUANTIZED=1") != NULL, "%s", device_build_options(&dev));
    device_close(&dev);
    setenv("PT_BVH_WIDTH", "8", 1);
    err = (Error){0};
    cr_expect_not(device_open(&dev, "cpu", &err), "quantised nodes are 2-wide only");
    cr_expect(strstr(err.message, "PT_BVH_QUANTIZED=1") != NULL, "%s", err.message);
    setenv("PT_BVH_QUANTIZED", "yes", 1);
    unsetenv("PT_BVH_WIDTH");
    err = (Error){0};
    cr_expect_not(device_open(&dev, "cpu", &err));
    cr_expect(strstr(err.message, "PT_BVH_QUANTIZED=yes") != NULL, "%s", err.message);
    unsetenv("PT_BVH_QUANTIZED");
}

/* The maths options for every kind of device: NVIDIA drops correctly rounded division and square
 * root unless exact maths is asked for, every other device that offers them keeps them, and none
 * asks for them where they are not offered (PoCL, the CI's device, sees only the second case). */
Test(device, maths_options_drop_exact_division_on_nvidia_only)
{
    const char *flag = "-cl-fp32-correctly-rounded-divide-sqrt";
    cr_expect(strstr(device_maths_options(true, true, false), flag) == NULL, "NVIDIA, default");
    cr_expect(strstr(device_maths_options(true, true, true), flag) != NULL, "NVIDIA, exact");
    cr_expect(strstr(device_maths_options(true, false, false), flag) != NULL, "others, default");
    cr_expect(strstr(device_maths_options(true, false, true), flag) != NULL, "others, exact");
    for (int nvidia = 0; nvidia < 2; nvidia++)
        for (int exact = 0; exact < 2; exact++)
            cr_expect(strstr(device_maths_options(false, nvidia, exact), flag) == NULL,
                      "not offered (nvidia %d, exact %d)", nvidia, exact);
}

/* PT_EXACT_MATHS: PoCL keeps correctly rounded division and square root either way (only NVIDIA
 * drops them by default), and the box test widens its margin wherever the build lacks them; a bad
 * value is refused with the variable named. */
Test(device, exact_maths_and_the_box_margin_follow_the_build_options)
{
    Device dev;
    Error err = {0};
    const char *exact = "-cl-fp32-correctly-rounded-divide-sqrt";
    for (int on = 0; on < 2; on++) {
        setenv("PT_EXACT_MATHS", on ? "1" : "0", 1);
        err = (Error){0};
        cr_assert(device_open(&dev, "cpu", &err), "%s", err.message);
        const char *options = device_build_options(&dev);
        cr_expect(strstr(options, exact) != NULL, "PT_EXACT_MATHS=%d on PoCL: %s", on, options);
        cr_expect(strstr(options, "PT_INEXACT_DIVIDE") == NULL, "%s", options);
        device_close(&dev);
    }
    setenv("PT_CL_OPTIONS", "-cl-mad-enable", 1);
    err = (Error){0};
    cr_assert(device_open(&dev, "cpu", &err), "%s", err.message);
    cr_expect(strstr(device_build_options(&dev), "-DPT_INEXACT_DIVIDE=1") != NULL, "%s",
              device_build_options(&dev));
    device_close(&dev);
    unsetenv("PT_CL_OPTIONS");
    setenv("PT_EXACT_MATHS", "2", 1);
    err = (Error){0};
    cr_expect_not(device_open(&dev, "cpu", &err));
    cr_expect_eq(err.code, ERR_SETTINGS);
    cr_expect(strstr(err.message, "PT_EXACT_MATHS=2") != NULL, "%s", err.message);
    setenv("PT_EXACT_MATHS", "1", 1);
}

Test(device, allocation_above_the_limit_names_the_buffer)
{
    Device dev;
    Error err = {0};
    cr_assert(device_open(&dev, "cpu", &err), "%s", err.message);
    size_t too_big = (size_t)dev.max_alloc + 1;
    cl_mem buf = device_buffer(&dev, "giant_buffer", CL_MEM_READ_WRITE, too_big, NULL, &err);
    cr_expect_null(buf);
    cr_expect_eq(err.code, ERR_ALLOC_TOO_LARGE);
    cr_expect(strstr(err.message, "giant_buffer") != NULL, "%s", err.message);
    device_close(&dev);
}

Test(device, broken_kernel_reports_a_build_failure)
{
    Device dev;
    Error err = {0};
    cr_assert(device_open(&dev, "cpu", &err), "%s", err.message);
    cr_expect_not(device_build(&dev, PROGRAM_FEATURES_ALL,
                               "kernel void broken(global int *x) { x[0] = undefined_name; }",
                               "broken.cl", &err));
    cr_expect_eq(err.code, ERR_KERNEL_BUILD);
    device_close(&dev);
}

/* The kernel cache: a second build loads the stored binary; a corrupt entry is rebuilt silently and
 * replaced; a changed source gets its own entry. */
Test(device, kernel_cache_hit_and_corrupt_entry_rebuild, .timeout = 120)
{
    const char *dir = test_temp_dir();
    setenv("XDG_CACHE_HOME", dir, 1);
    unsetenv("PT_NO_CACHE");
    const char *extra = "kernel void cache_probe(global int *x) { x[0] = 42; }";
    Error err = {0};
    Device a, b, c, d;
    cr_assert(device_open(&a, "cpu", &err), "%s", err.message);
    cr_assert(device_build(&a, PROGRAM_FEATURES_ALL, extra, "probe.cl", &err), "%s", err.message);
    cr_expect_not(a.cache_hit, "first build cannot come from an empty cache");
    cr_assert(device_open(&b, "cpu", &err) && device_build(&b, PROGRAM_FEATURES_ALL, extra, "probe.cl",
                                                             &err));
    cr_expect(b.cache_hit, "second build should load the cached binary");

    /* The cached program works. */
    cl_mem out = device_buffer(&b, "out", CL_MEM_WRITE_ONLY, sizeof(cl_int), NULL, &err);
    cl_kernel kernel = device_kernel(&b, "cache_probe");
    KERNEL_ARGS(kernel, 0, KARG(out));
    device_run(&b, kernel, 1, 1, NULL);
    cl_int value = 0;
    device_read(&b, out, 0, sizeof value, &value);
    cr_expect_eq(value, 42);
    clReleaseKernel(kernel);
    clReleaseMemObject(out);

    /* Corrupt every entry: the next build compiles and succeeds. */
    char command[600];
    snprintf(command, sizeof command, "for f in %s/pt/*.bin; do echo garbage > $f; done", dir);
    cr_assert_eq(system(command), 0);
    cr_assert(device_open(&c, "cpu", &err) && device_build(&c, PROGRAM_FEATURES_ALL, extra, "probe.cl",
                                                             &err),
              "%s", err.message);
    cr_expect_not(c.cache_hit, "a corrupt entry must not be used");
    cr_assert(device_open(&d, "cpu", &err) && device_build(&d, PROGRAM_FEATURES_ALL, extra, "probe.cl",
                                                             &err));
    cr_expect(d.cache_hit, "the rebuilt binary replaced the corrupt entry");
    device_close(&a), device_close(&b), device_close(&c), device_close(&d);
}
