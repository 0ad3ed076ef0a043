/* SPDX-License-Identifier: MIT */
/* error.h: bad input returns an Error (code + the input's file and line) so callers print one line
 * and tests assert which error happened; bugs and OpenCL failures abort (see cl_check.h). */
#ifndef PT_ERROR_H
#define PT_ERROR_H

#include <stdbool.h>

#define ERROR_CODES(X)                                                                             \
    X(ERR_NONE, "no error")                                                                        \
    X(ERR_USAGE, "bad command line")                                                               \
    X(ERR_FILE_MISSING, "file not found")                                                          \
    X(ERR_FILE_READ, "file unreadable")                                                            \
    X(ERR_JSON_SYNTAX, "malformed JSON")                                                           \
    X(ERR_JSON_UNKNOWN_KEY, "unknown key")                                                         \
    X(ERR_JSON_TYPE, "wrong type")                                                                 \
    X(ERR_JSON_VALUE, "value out of range")                                                        \
    X(ERR_OBJ_PARSE, "malformed OBJ")                                                              \
    X(ERR_OBJ_INDEX, "face index out of range")                                                    \
    X(ERR_OBJ_NONFINITE, "non-finite vertex")                                                      \
    X(ERR_NO_TRIANGLES, "scene has no triangles")                                                  \
    X(ERR_TEXTURE, "texture unreadable or corrupt")                                                \
    X(ERR_DEVICE_UNKNOWN, "unknown OpenCL device")                                                 \
    X(ERR_NO_PLATFORM, "no OpenCL platform")                                                       \
    X(ERR_ALLOC_TOO_LARGE, "allocation larger than the device allows")                             \
    X(ERR_KERNEL_BUILD, "kernel build failed")                                                     \
    X(ERR_OUTPUT, "output not writable")                                                           \
    X(ERR_TOO_LARGE, "input too large")                                                            \
    X(ERR_SETTINGS, "invalid setting")                                                             \
    X(ERR_OUT_OF_MEMORY, "out of memory")                                                          \
    X(ERR_SYSTEM, "operating system failure")                                                      \
    X(ERR_MPI, "MPI job failure")                                                                  \
    X(ERR_PATH_ESCAPES, "path leaves the file's folder")

typedef enum {
#define X(code, text) code,
    ERROR_CODES(X)
#undef X
} ErrorCode;

typedef struct {
    ErrorCode code;
    int line;           /* line in `file`, 0 when not applicable */
    char file[512];     /* the input file the error is about, "" when none */
    char message[1024]; /* one line, already naming file/line/key/value */
} Error;

/* Records an error; message is printf-formatted. Keeps the first error if one is already set. */
void error_set(Error *err, ErrorCode code, const char *file, int line, const char *fmt, ...)
    __attribute__((format(printf, 5, 6)));
/* An ERR_SETTINGS error about a render setting, worded by the layer that checks it (render/,
 * dist/) with the setting's own name (RenderSettings' field: "min_spp"): the message is that name,
 * a blank and fmt. The command layer, which knows the flag that set it, registers a namer that
 * gives the name users typed ("--min-spp"); NULL from the namer, or no namer, keeps the setting's. */
typedef const char *(*SettingNamer)(const char *setting);
void error_set_setting_namer(SettingNamer namer);
void error_set_setting(Error *err, const char *setting, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
const char *error_code_name(ErrorCode code);
bool error_is_set(const Error *err);

/* Warnings about incomplete input (missing MTL, missing texture): printed to stderr and counted,
 * so tests can assert that one was given. */
void warn(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
int warning_count(void);
void warnings_set_quiet(bool quiet);

/* Prints "pt: <message>" and exits 1. */
_Noreturn void die(const char *fmt, ...) __attribute__((format(printf, 1, 2)));

#endif
