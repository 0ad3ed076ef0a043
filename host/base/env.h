/* SPDX-License-Identifier: MIT */
/* env.h: the PT_* environment variables, read and checked in one way. An unset or empty variable
 * takes its default; anything else must be valid, or the read fails with ERR_SETTINGS and one line
 * naming the variable, its value and what is allowed (the user set it on purpose: a typo must not
 * silently fall back to the default). */
#ifndef PT_ENV_H
#define PT_ENV_H

#include <stdbool.h>
#include <stddef.h>

#include "base/error.h"

/* A decimal integer in [min, max]. */
bool env_int(const char *name, long min, long max, long fallback, long *out, Error *err);
/* 0 or 1. */
bool env_flag(const char *name, bool fallback, bool *out, Error *err);
/* Free text (compiler options) of printable characters, shorter than max_length; *out points into
 * the environment, or is fallback. */
bool env_text(const char *name, size_t max_length, const char *fallback, const char **out,
              Error *err);

#endif
