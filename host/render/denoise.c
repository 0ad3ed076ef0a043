// SPDX-License-Identifier: MIT
/* denoise.c: OIDN opened with dlopen (render/oidn_api.h lists what is looked up), one device per
 * Denoiser, and the "RT" filter run on host copies of the images (oidnWriteBuffer/ReadBuffer: the
 * same code for the CPU and the CUDA device; the copies cost a few ms at 1080p). */
#include "render/denoise.h"

#include <dlfcn.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "render/oidn_api.h"

#define OIDN_SONAME "libOpenImageDenoise.so.2"

typedef struct {
#define OIDN_POINTER(ret, name, params) ret(*name) params;
    OIDN_FUNCTIONS(OIDN_POINTER)
#undef OIDN_POINTER
} OidnApi;

struct Denoiser {
    const OidnApi *api;
    OIDNDevice device;
    char version[32];
    const char *device_name;
};

bool denoise_device_from_name(const char *name, DenoiseDevice *out)
{
    static const char *const names[] = {
#define DENOISE_DEVICE_NAME(e, name) name,
        DENOISE_DEVICES(DENOISE_DEVICE_NAME)
#undef DENOISE_DEVICE_NAME
    };
    for (int d = 0; d < DENOISE_DEVICE_COUNT; d++)
        if (!strcmp(name, names[d])) {
            *out = (DenoiseDevice)d;
            return true;
        }
    return false;
}

const char *denoise_device_name(DenoiseDevice device)
{
    static const char *const names[] = {
#define DENOISE_DEVICE_NAME(e, name) name,
        DENOISE_DEVICES(DENOISE_DEVICE_NAME)
#undef DENOISE_DEVICE_NAME
    };
    return (unsigned)device < DENOISE_DEVICE_COUNT ? names[device] : "?";
}

/* The folder of the running executable ("" if /proc is not mounted). */
static void executable_folder(char *out, size_t size)
{
    char path[PATH_MAX];
    ssize_t n = readlink("/proc/self/exe", path, sizeof path - 1);
    out[0] = '\0';
    if (n <= 0)
        return;
    path[n] = '\0';
    char *slash = strrchr(path, '/');
    if (slash) {
        *slash = '\0';
        snprintf(out, size, "%s", path);
    }
}

/* Opens the first library of the search order (denoise.h); NULL with the places tried in err. */
static void *open_library(Error *err)
{
    const char *env = getenv("PT_OIDN_LIBRARY");
    char folder[PATH_MAX], candidates[3][PATH_MAX + 64];
    int count = 0;
    if (env && env[0]) {
        snprintf(candidates[count++], sizeof candidates[0], "%s", env);
    } else {
        executable_folder(folder, sizeof folder);
        if (folder[0]) {
            snprintf(candidates[count++], sizeof candidates[0], "%s/../lib/" OIDN_SONAME, folder);
            snprintf(candidates[count++], sizeof candidates[0], "%s/../.oidn/lib/" OIDN_SONAME,
                     folder);
        }
        snprintf(candidates[count++], sizeof candidates[0], OIDN_SONAME);
    }
    for (int c = 0; c < count; c++) {
        /* RTLD_LOCAL: OIDN's TBB and C++ runtime stay out of pt's symbol space. */
        void *library = dlopen(candidates[c], RTLD_NOW | RTLD_LOCAL);
        if (library)
            return library;
    }
    if (env && env[0])
        error_set(err, ERR_FILE_MISSING, env, 0,
                  "Intel Open Image Denoise could not be loaded from PT_OIDN_LIBRARY=%s (%s): "
                  "name a libOpenImageDenoise.so.2 there, or unset it and run "
                  "tools/install-oidn.sh (or make deps) in pt's source tree", env, dlerror());
    else
        error_set(err, ERR_FILE_MISSING, NULL, 0,
                  "Intel Open Image Denoise (" OIDN_SONAME ") is not installed: run "
                  "tools/install-oidn.sh (or make deps) in pt's source tree, or set "
                  "PT_OIDN_LIBRARY to a libOpenImageDenoise.so.2");
    return NULL;
}

/* The API of the process's one OIDN library, loaded on first use. It is never unloaded: OIDN's
 * TBB worker threads outlive a filter, and dlclose under them is undefined. */
static const OidnApi *oidn_api(Error *err)
{
    static OidnApi api;
    static bool loaded;
    if (loaded)
        return &api;
    void *library = open_library(err);
    if (!library)
        return NULL;
#define OIDN_LOOKUP(ret, name, params)                                                             \
    *(void **)&api.name = dlsym(library, #name);                                                   \
    if (!api.name) {                                                                               \
        error_set(err, ERR_FILE_READ, NULL, 0,                                                     \
                  "Intel Open Image Denoise: the library lacks %s (pt needs OIDN 2.x)", #name);    \
        return NULL;                                                                               \
    }
    OIDN_FUNCTIONS(OIDN_LOOKUP)
#undef OIDN_LOOKUP
    loaded = true;
    return &api;
}

/* OIDN's pending error, if any, into err; true when there was none. */
static bool oidn_ok(const Denoiser *d, const char *step, Error *err)
{
    const char *message = NULL;
    OIDNError code = d->api->oidnGetDeviceError(d->device, &message);
    if (code == OIDN_ERROR_NONE)
        return true;
    error_set(err, ERR_SYSTEM, NULL, 0, "Intel Open Image Denoise (%s device): %s: %s",
              d->device_name, step, message ? message : "unknown error");
    return false;
}

/* A committed device of the type, or NULL (err set) when OIDN cannot open one. */
static bool open_device(Denoiser *d, OIDNDeviceType type, Error *err)
{
    d->device_name = type == OIDN_DEVICE_TYPE_CUDA ? "CUDA" : "CPU";
    d->device = d->api->oidnNewDevice(type);
    if (!d->device) {
        error_set(err, ERR_SYSTEM, NULL, 0, "Intel Open Image Denoise has no %s device here",
                  d->device_name);
        return false;
    }
    d->api->oidnCommitDevice(d->device);
    if (!oidn_ok(d, "opening the device", err)) {
        d->api->oidnReleaseDevice(d->device);
        d->device = NULL;
        return false;
    }
    int version = d->api->oidnGetDeviceInt(d->device, "version"); /* 20501 = 2.5.1 */
    snprintf(d->version, sizeof d->version, "%d.%d.%d", version / 10000, version / 100 % 100,
             version % 100);
    return true;
}

Denoiser *denoiser_open(DenoiseDevice want, bool render_on_nvidia, Error *err)
{
    const OidnApi *api = oidn_api(err);
    if (!api)
        return NULL;
    Denoiser *d = calloc(1, sizeof *d);
    if (!d) {
        error_set(err, ERR_OUT_OF_MEMORY, NULL, 0, "out of memory for the denoiser");
        return NULL;
    }
    d->api = api;
    bool gpu = want == DENOISE_DEVICE_GPU || (want == DENOISE_DEVICE_AUTO && render_on_nvidia);
    if (gpu) {
        Error gpu_err = {0};
        if (open_device(d, OIDN_DEVICE_TYPE_CUDA, &gpu_err))
            return d;
        fprintf(stderr, "pt: warning: %s: denoising on the CPU\n", gpu_err.message);
    }
    if (open_device(d, OIDN_DEVICE_TYPE_CPU, err))
        return d;
    free(d);
    return NULL;
}

void denoiser_close(Denoiser *denoiser)
{
    if (!denoiser)
        return;
    denoiser->api->oidnReleaseDevice(denoiser->device);
    free(denoiser);
}

const char *denoiser_version(const Denoiser *denoiser) { return denoiser->version; }
const char *denoiser_device(const Denoiser *denoiser) { return denoiser->device_name; }

/* One "RT" filter over the images bound (each a FLOAT3 buffer of the frame), run once. */
typedef struct {
    const char *name;
    OIDNBuffer buffer;
} FilterImage;

static bool run_filter(Denoiser *d, const FilterImage *images, int count, const DenoiseInput *in,
                       bool colour, bool clean_aux, const char *what, Error *err)
{
    const OidnApi *api = d->api;
    OIDNFilter filter = api->oidnNewFilter(d->device, "RT");
    if (!filter) {
        if (oidn_ok(d, what, err)) /* no message from OIDN: say what failed */
            error_set(err, ERR_SYSTEM, NULL, 0, "Intel Open Image Denoise: %s: no \"RT\" filter",
                      what);
        return false;
    }
    for (int i = 0; i < count; i++)
        api->oidnSetFilterImage(filter, images[i].name, images[i].buffer, OIDN_FORMAT_FLOAT3,
                                (size_t)in->width, (size_t)in->height, 0, 0, 0);
    if (colour) { /* a guide's own filter takes neither: its input is [0, 1] or a direction */
        api->oidnSetFilterBool(filter, "hdr", true);
        api->oidnSetFilterBool(filter, "cleanAux", clean_aux);
    }
    api->oidnSetFilterInt(filter, "quality",
                          in->interactive ? OIDN_QUALITY_BALANCED : OIDN_QUALITY_HIGH);
    api->oidnCommitFilter(filter);
    api->oidnExecuteFilter(filter);
    bool ok = oidn_ok(d, what, err);
    api->oidnReleaseFilter(filter);
    return ok;
}

bool denoiser_run(Denoiser *d, const DenoiseInput *in, float *out, Error *err)
{
    const OidnApi *api = d->api;
    size_t bytes = (size_t)in->width * (size_t)in->height * 3 * sizeof(float);
    bool guided = in->albedo && in->normal;
    OIDNBuffer color = api->oidnNewBuffer(d->device, bytes);
    OIDNBuffer albedo = guided ? api->oidnNewBuffer(d->device, bytes) : NULL;
    OIDNBuffer normal = guided ? api->oidnNewBuffer(d->device, bytes) : NULL;
    bool ok = oidn_ok(d, "allocating the images", err);
    if (ok) {
        api->oidnWriteBuffer(color, 0, bytes, in->color);
        if (guided) {
            api->oidnWriteBuffer(albedo, 0, bytes, in->albedo);
            api->oidnWriteBuffer(normal, 0, bytes, in->normal);
            /* The guides are prefiltered in place (OIDN's documented high-quality recipe): the
             * colour filter then trusts them as noise-free (cleanAux) and keeps their detail. */
            FilterImage albedo_pass[] = {{"albedo", albedo}, {"output", albedo}};
            FilterImage normal_pass[] = {{"normal", normal}, {"output", normal}};
            ok = run_filter(d, albedo_pass, 2, in, false, false, "prefiltering the albedo",
                            err) &&
                 run_filter(d, normal_pass, 2, in, false, false, "prefiltering the normal", err);
        }
        FilterImage beauty[] = {{"color", color}, {"output", color}, {"albedo", albedo},
                                {"normal", normal}};
        ok = ok && run_filter(d, beauty, guided ? 4 : 2, in, true, guided, "denoising", err);
        if (ok)
            api->oidnReadBuffer(color, 0, bytes, out);
        ok = ok && oidn_ok(d, "reading the result", err);
    }
    OIDNBuffer made[] = {color, albedo, normal};
    for (int b = 0; b < 3; b++)
        if (made[b])
            api->oidnReleaseBuffer(made[b]);
    return ok;
}
