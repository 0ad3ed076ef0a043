/* SPDX-License-Identifier: MIT */
/* oidn_api.h: the part of Intel Open Image Denoise's C API (OIDN 2.x, include/OpenImageDenoise/oidn.h,
 * documented at openimagedenoise.github.io/documentation.html) that render/denoise.c uses. OIDN
 * ships no Debian package and pt links nothing of it: the library is opened at run time (dlopen)
 * and these are the types of the symbols looked up, with the enum values the ABI fixes. One table
 * (OIDN_FUNCTIONS) lists the functions, so the loader and its struct of pointers cannot disagree. */
#ifndef PT_OIDN_API_H
#define PT_OIDN_API_H

#include <stdbool.h>
#include <stddef.h>

typedef struct OIDNDeviceImpl *OIDNDevice;
typedef struct OIDNFilterImpl *OIDNFilter;
typedef struct OIDNBufferImpl *OIDNBuffer;

/* The values of oidn.h (OIDN 2.x ABI; the .so.2 soname keeps them). */
typedef enum {
    OIDN_DEVICE_TYPE_DEFAULT = 0,
    OIDN_DEVICE_TYPE_CPU = 1,
    OIDN_DEVICE_TYPE_SYCL = 2,
    OIDN_DEVICE_TYPE_CUDA = 3,
    OIDN_DEVICE_TYPE_HIP = 4,
    OIDN_DEVICE_TYPE_METAL = 5
} OIDNDeviceType;

typedef enum { OIDN_ERROR_NONE = 0 } OIDNError; /* 1..6: unknown .. cancelled; we print the message */

typedef enum { OIDN_FORMAT_FLOAT3 = 3 } OIDNFormat;

typedef enum { OIDN_QUALITY_DEFAULT = 0, OIDN_QUALITY_FAST = 4, OIDN_QUALITY_BALANCED = 5,
               OIDN_QUALITY_HIGH = 6 } OIDNQuality;

/* X(return type, name, (parameters)) */
#define OIDN_FUNCTIONS(X)                                                                          \
    X(OIDNDevice, oidnNewDevice, (OIDNDeviceType type))                                           \
    X(void, oidnCommitDevice, (OIDNDevice device))                                                 \
    X(void, oidnReleaseDevice, (OIDNDevice device))                                                \
    X(int, oidnGetDeviceInt, (OIDNDevice device, const char *name))                                \
    X(OIDNError, oidnGetDeviceError, (OIDNDevice device, const char **out_message))                \
    X(OIDNBuffer, oidnNewBuffer, (OIDNDevice device, size_t byte_size))                            \
    X(void, oidnWriteBuffer, (OIDNBuffer buffer, size_t byte_offset, size_t byte_size,             \
                              const void *src_host_ptr))                                           \
    X(void, oidnReadBuffer, (OIDNBuffer buffer, size_t byte_offset, size_t byte_size,              \
                             void *dst_host_ptr))                                                  \
    X(void, oidnReleaseBuffer, (OIDNBuffer buffer))                                                \
    X(OIDNFilter, oidnNewFilter, (OIDNDevice device, const char *type))                            \
    X(void, oidnSetFilterImage, (OIDNFilter filter, const char *name, OIDNBuffer buffer,           \
                                 OIDNFormat format, size_t width, size_t height,                   \
                                 size_t byte_offset, size_t pixel_byte_stride,                     \
                                 size_t row_byte_stride))                                          \
    X(void, oidnSetFilterBool, (OIDNFilter filter, const char *name, bool value))                  \
    X(void, oidnSetFilterInt, (OIDNFilter filter, const char *name, int value))                    \
    X(void, oidnCommitFilter, (OIDNFilter filter))                                                 \
    X(void, oidnExecuteFilter, (OIDNFilter filter))                                                \
    X(void, oidnReleaseFilter, (OIDNFilter filter))

#endif
