// SPDX-License-Identifier: MIT
/* Device layer: the program builds on PoCL, shared structs have the same size on both sides, bad
 * device specs and oversized allocations are reported, a broken kernel shows its build log. */
#include <criterion/criterion.h>
#include <string.h>

#include "device.h"
#include "shared_types.h"
#include "support.h"

Test(device, shared_struct_sizes_match_host)
{
    Device *dev = test_device();
    Error err = {0};
    cl_mem out = device_buffer(dev, "sizes", CL_MEM_WRITE_ONLY, SIZEOF_COUNT * sizeof(cl_uint), NULL, &err);
    cl_kernel kernel = device_kernel(dev, "report_sizes");
    KERNEL_ARG(kernel, 0, out);
    device_run(dev, kernel, 1, 1, NULL);
    cl_uint sizes[SIZEOF_COUNT];
    device_read(dev, out, 0, sizeof sizes, sizes);
    cr_expect_eq(sizes[SIZEOF_TRIANGLE], sizeof(Triangle));
    cr_expect_eq(sizes[SIZEOF_BVH_NODE], sizeof(BvhNode));
    cr_expect_eq(sizes[SIZEOF_BVH_TRIANGLE], sizeof(BvhTriangle));
    cr_expect_eq(sizes[SIZEOF_MATERIAL], sizeof(Material));
    cr_expect_eq(sizes[SIZEOF_TEXTURE_INFO], sizeof(TextureInfo));
    cr_expect_eq(sizes[SIZEOF_CAMERA], sizeof(Camera));
    cr_expect_eq(sizes[SIZEOF_RENDER_PARAMS], sizeof(RenderParams));
    cr_expect_eq(sizes[SIZEOF_LIGHT_ENTRY], sizeof(LightEntry));
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
    cr_expect_not(device_build(&dev, "kernel void broken(global int *x) { x[0] = undefined_name; }",
                               "broken.cl", &err));
    cr_expect_eq(err.code, ERR_KERNEL_BUILD);
    device_close(&dev);
}
