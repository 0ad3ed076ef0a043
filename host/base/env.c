// SPDX-License-Identifier: MIT
#include "base/env.h"

#include <ctype.h>
#include <errno.h>
#include <stdlib.h>
#include <string.h>

/* The variable's value, or NULL when unset or empty (both mean "use the default"). */
static const char *env_value(const char *name)
{
    const char *value = getenv(name);
    return value && *value ? value : NULL;
}

bool env_int(const char *name, long min, long max, long fallback, long *out, Error *err)
{
    const char *value = env_value(name);
    if (!value) {
        *out = fallback;
        return true;
    }
    char *end;
    errno = 0;
    long v = strtol(value, &end, 10);
    if (errno || end == value || *end || v < min || v > max) {
        error_set(err, ERR_SETTINGS, NULL, 0,
                  "environment variable %s=%s: expected an integer from %ld to %ld", name, value,
                  min, max);
        return false;
    }
    *out = v;
    return true;
}

bool env_flag(const char *name, bool fallback, bool *out, Error *err)
{
    const char *value = env_value(name);
    if (!value) {
        *out = fallback;
        return true;
    }
    if (strcmp(value, "0") && strcmp(value, "1")) {
        error_set(err, ERR_SETTINGS, NULL, 0, "environment variable %s=%s: expected 0 or 1", name,
                  value);
        return false;
    }
    *out = value[0] == '1';
    return true;
}

bool env_text(const char *name, size_t max_length, const char *fallback, const char **out,
              Error *err)
{
    const char *value = getenv(name);
    if (!value) {
        *out = fallback;
        return true;
    }
    size_t length = strlen(value);
    for (size_t i = 0; i < length; i++) {
        if (!isprint((unsigned char)value[i])) {
            error_set(err, ERR_SETTINGS, NULL, 0,
                      "environment variable %s: character %zu (code %d) is not printable", name,
                      i + 1, (unsigned char)value[i]);
            return false;
        }
    }
    if (length >= max_length) {
        error_set(err, ERR_SETTINGS, NULL, 0,
                  "environment variable %s is %zu characters long, at most %zu allowed", name,
                  length, max_length - 1);
        return false;
    }
    *out = value;
    return true;
}
