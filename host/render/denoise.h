/* SPDX-License-Identifier: MIT */
/* denoise.h: the image denoised by Intel Open Image Denoise (OIDN 2.x), loaded at run time
 * (render/oidn_api.h): pt builds and runs without it, and --denoise then says how to get it.
 * The library is looked for, in order: $PT_OIDN_LIBRARY (a path to libOpenImageDenoise.so.2);
 * <folder of pt>/../lib/ (a `make bundle` tree); <folder of pt>/../.oidn/lib/ (the source tree's,
 * filled by tools/install-oidn.sh); the system library path. */
#ifndef PT_DENOISE_H
#define PT_DENOISE_H

#include <stdbool.h>

#include "base/error.h"

/* --denoise-device: AUTO takes OIDN's CUDA device when pt renders on an NVIDIA GPU, its CPU
 * device otherwise. */
#define DENOISE_DEVICES(X) X(AUTO, "auto") X(CPU, "cpu") X(GPU, "gpu")
typedef enum {
#define DENOISE_DEVICE_ENUM(e, name) DENOISE_DEVICE_##e,
    DENOISE_DEVICES(DENOISE_DEVICE_ENUM)
#undef DENOISE_DEVICE_ENUM
    DENOISE_DEVICE_COUNT
} DenoiseDevice;

/* "cpu" -> DENOISE_DEVICE_CPU ...; false for an unknown name. */
bool denoise_device_from_name(const char *name, DenoiseDevice *out);
const char *denoise_device_name(DenoiseDevice device);

typedef struct Denoiser Denoiser;

/* Loads OIDN and opens the device asked for. A GPU that OIDN cannot open (no CUDA driver, an
 * unsupported card) falls back to the CPU device with a warning on stderr. NULL with err set
 * when the library is missing (the message says where pt looked and how to get it) or no device
 * opens. render_on_nvidia: pt's OpenCL device is an NVIDIA GPU. */
Denoiser *denoiser_open(DenoiseDevice want, bool render_on_nvidia, Error *err);
void denoiser_close(Denoiser *denoiser);

/* "2.5.1" and "CPU" / "CUDA": what the EXR header and the viewer's title name. */
const char *denoiser_version(const Denoiser *denoiser);
const char *denoiser_device(const Denoiser *denoiser);

/* Per pixel, 3 floats, row 0 at the top. albedo and normal are the guides (both or neither: NULL
 * denoises the colour alone); they are noisy (anti-aliased, depth-of-field and motion-blurred as
 * the image) and are prefiltered by OIDN's own filter first, as OIDN recommends for final frames
 * (its "cleanAux" high-quality mode). */
typedef struct {
    const float *color, *albedo, *normal;
    int width, height;
    bool interactive; /* OIDN's "balanced" quality (the viewer) instead of "high" */
} DenoiseInput;

/* Writes the denoised colour into out (may equal in->color); false with OIDN's message. */
bool denoiser_run(Denoiser *denoiser, const DenoiseInput *in, float *out, Error *err);

#endif
