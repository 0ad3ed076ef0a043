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

bool exr_ok(exr_result_t result, const char *step, const char *path, ErrorCode code, Error *err)
{
    if (result == EXR_ERR_SUCCESS)
        return true;
    const char *detail =
        exr_last_message[0] ? exr_last_message : exr_get_default_error_message(result);
    error_set(err, code, path, 0, "%s: %s failed: %s (%s)", path, step,
              exr_get_error_code_as_string(result), detail);
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
