// SPDX-License-Identifier: MIT
#include "io/exr_common.h"

#include <stdio.h>
#include <string.h>

/* OpenEXR reports the detail of a failure (e.g. the strerror of a failed open) through a callback
 * and would print it to stderr by default; keep the latest one so the Error can carry it. */
static _Thread_local char exr_last_message[256];

static void exr_capture_message(exr_const_context_t ctxt, exr_result_t code, const char *message)
{
    (void)ctxt;
    (void)code;
    snprintf(exr_last_message, sizeof exr_last_message, "%s", message ? message : "");
}

exr_context_initializer_t exr_quiet_initializer(void)
{
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = exr_capture_message;
    exr_last_message[0] = '\0';
    return init;
}

/* What OpenEXR's code means for the user's file, as a sentence; NULL: no plain meaning (the
 * library's step and code are quoted then: a bug report needs them). */
static const char *exr_sentence(exr_result_t result)
{
    switch (result) {
    case EXR_ERR_OUT_OF_MEMORY: return "out of memory for this image";
    case EXR_ERR_FILE_ACCESS: return "cannot be opened";
    case EXR_ERR_FILE_BAD_HEADER: return "is not an OpenEXR image, or its header is damaged";
    case EXR_ERR_READ_IO: return "cannot be read (truncated or unreadable)";
    case EXR_ERR_WRITE_IO: return "cannot be written";
    case EXR_ERR_MISSING_REQ_ATTR:
    case EXR_ERR_INVALID_ATTR:
    case EXR_ERR_ATTR_TYPE_MISMATCH:
    case EXR_ERR_ATTR_SIZE_MISMATCH: return "its header is damaged (an attribute is missing or invalid)";
    case EXR_ERR_BAD_CHUNK_LEADER:
    case EXR_ERR_CORRUPT_CHUNK:
    case EXR_ERR_INCORRECT_PART:
    case EXR_ERR_INCORRECT_CHUNK:
    case EXR_ERR_INVALID_SAMPLE_DATA: return "its pixel data is damaged or truncated";
    case EXR_ERR_FEATURE_NOT_IMPLEMENTED: return "uses an OpenEXR feature this build cannot read";
    default: return NULL;
    }
}

bool exr_ok(exr_result_t result, const char *step, const char *path, ErrorCode code, Error *err)
{
    if (result == EXR_ERR_SUCCESS)
        return true;
    const char *sentence = exr_sentence(result);
    bool system = result == EXR_ERR_FILE_ACCESS || result == EXR_ERR_READ_IO ||
                  result == EXR_ERR_WRITE_IO; /* the detail is the system's reason */
    if (sentence && system && exr_last_message[0])
        error_set(err, code, path, 0, "%s: %s (%s)", path, sentence, exr_last_message);
    else if (sentence)
        error_set(err, code, path, 0, "%s: %s", path, sentence);
    else
        error_set(err, code, path, 0, "%s: %s failed: %s (%s)", path, step,
                  exr_get_error_code_as_string(result),
                  exr_last_message[0] ? exr_last_message : exr_get_default_error_message(result));
    return false;
}

int exr_rgb_index(const char *name)
{
    if (strcmp(name, "R") == 0)
        return 0;
    if (strcmp(name, "G") == 0)
        return 1;
    if (strcmp(name, "B") == 0)
        return 2;
    return -1;
}
