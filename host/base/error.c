// SPDX-License-Identifier: MIT
#include "base/error.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int g_warning_count;
static bool g_warnings_quiet;

void error_set(Error *err, ErrorCode code, const char *file, int line, const char *fmt, ...)
{
    if (!err || err->code != ERR_NONE)
        return;
    err->code = code;
    err->line = line;
    snprintf(err->file, sizeof err->file, "%s", file ? file : "");
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err->message, sizeof err->message, fmt, ap);
    va_end(ap);
}

const char *error_code_name(ErrorCode code)
{
    switch (code) {
#define X(c, text) \
    case c:        \
        return #c;
        ERROR_CODES(X)
#undef X
    }
    return "ERR_?";
}

bool error_is_set(const Error *err) { return err && err->code != ERR_NONE; }

void warn(const char *fmt, ...)
{
    g_warning_count++;
    if (g_warnings_quiet)
        return;
    va_list ap;
    va_start(ap, fmt);
    fputs("pt: warning: ", stderr);
    vfprintf(stderr, fmt, ap);
    fputc('\n', stderr);
    va_end(ap);
}

int warning_count(void) { return g_warning_count; }
void warnings_set_quiet(bool quiet) { g_warnings_quiet = quiet; }

void die(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fputs("pt: ", stderr);
    vfprintf(stderr, fmt, ap);
    fputc('\n', stderr);
    va_end(ap);
    exit(1);
}
