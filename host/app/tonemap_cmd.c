// SPDX-License-Identifier: MIT
/* tonemap_cmd.c: pt tonemap (tonemap_cmd.h). The PNG equals the one `pt render -o X.png` writes
 * with the same options from the same film: the EXR holds the film's mean as 32-bit floats, and
 * bloom (render/bloom.h, on a device: --device as for pt render) and the display curve
 * (io/image_io.h image_write_png) are the same calls. */
#include "app/tonemap_cmd.h"

#include <stdio.h>
#include <stdlib.h>

#include "base/error.h"
#include "base/fs.h"
#include "device/device.h"
#include "io/image_io.h"
#include "render/bloom.h"

/* Bloom runs on a device, as pt render's does: the program is built for no scene features (the
 * bloom kernels are in every program; the kernel cache keeps it). */
static bool apply_bloom(const Options *o, float *rgb, int width, int height, Error *err)
{
    Device dev;
    if (!device_open(&dev, o->device, err))
        return false;
    if (o->no_cache)
        dev.use_cache = false;
    bool ok = device_build(&dev, 0u, NULL, NULL, err) &&
              bloom_apply(&dev, rgb, width, height, o->bloom_strength, o->bloom_radius, err);
    device_close(&dev);
    return ok;
}

int command_tonemap(const Options *o)
{
    Error err = {0};
    if (!fs_has_suffix(o->output, ".png"))
        die("-o %s: pt tonemap writes a PNG (name it OUT.png)", o->output);
    if (!fs_has_suffix(o->scene, ".exr"))
        die("%s: pt tonemap reads an EXR (a render's, or any RGB EXR)", o->scene);
    if (!fs_check_writable(o->output, &err))
        die("%s", err.message);
    float *rgb;
    int width, height;
    if (!image_read_exr(o->scene, &rgb, &width, &height, &err))
        die("%s", err.message);
    if (o->bloom_strength > 0.0f && !apply_bloom(o, rgb, width, height, &err)) {
        free(rgb);
        die("%s", err.message);
    }
    DisplaySettings display = {.exposure = o->exposure, .tonemap = o->tonemap};
    bool ok = image_write_png(o->output, rgb, width, height, display, &err);
    free(rgb);
    if (!ok)
        die("%s", err.message);
    if (!o->quiet)
        printf("wrote %s\n", o->output);
    return 0;
}
