// SPDX-License-Identifier: MIT
#include "base/error.h"

#include <stdarg.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static atomic_int g_warning_count; /* warn() may run on a part's build thread too */
static SettingNamer g_setting_namer;
static bool g_warnings_quiet;

/* A name longer than NAME_SHOWN_MAX bytes (a 100 KB file name, say) is shown as its first and last
 * NAME_KEEP bytes around an ellipsis: enough to recognise it, short enough for one line. */
#define NAME_KEEP 60
#define NAME_SHOWN_MAX (2 * NAME_KEEP + 8)
static const char ellipsis[] = "\xe2\x80\xa6"; /* U+2026, UTF-8 */

static bool is_utf8_continuation(char c) { return ((unsigned char)c & 0xC0) == 0x80; }

/* Replaces text[start, start + length) by its shortened form; returns the new length of the span.
 * Cuts on UTF-8 character boundaries. */
static size_t shorten_span(char *text, size_t start, size_t length)
{
    size_t head = NAME_KEEP, tail = length - NAME_KEEP;
    while (head > 0 && is_utf8_continuation(text[start + head]))
        head--;
    while (tail < length && is_utf8_continuation(text[start + tail]))
        tail++;
    size_t shown = head + strlen(ellipsis) + (length - tail);
    memcpy(text + start + head, ellipsis, strlen(ellipsis));
    memmove(text + start + head + strlen(ellipsis), text + start + tail,
            strlen(text + start + tail) + 1);
    return shown;
}

/* Shortens, in place, every occurrence of `name` (which may hold blanks) and then every other run
 * of non-blank bytes longer than NAME_SHOWN_MAX. The text only gets shorter. */
static void shorten_long_names(char *text, const char *name)
{
    size_t name_length = name ? strlen(name) : 0;
    if (name_length > NAME_SHOWN_MAX) {
        for (char *at = strstr(text, name); at; at = strstr(at, name))
            at += shorten_span(text, (size_t)(at - text), name_length);
    }
    size_t i = 0;
    while (text[i]) {
        size_t run = strcspn(text + i, " \t\n");
        if (run > NAME_SHOWN_MAX)
            run = shorten_span(text, i, run);
        i += run;
        i += strspn(text + i, " \t\n");
    }
}

/* fmt with its arguments, long names shortened; malloc'ed (NULL when out of memory). */
static char *format_message(const char *name, const char *fmt, va_list ap)
{
    va_list copy;
    va_copy(copy, ap);
    int length = vsnprintf(NULL, 0, fmt, copy);
    va_end(copy);
    char *text = length >= 0 ? malloc((size_t)length + 1) : NULL;
    if (!text)
        return NULL;
    vsnprintf(text, (size_t)length + 1, fmt, ap);
    shorten_long_names(text, name);
    return text;
}

void error_set(Error *err, ErrorCode code, const char *file, int line, const char *fmt, ...)
{
    if (!err || err->code != ERR_NONE)
        return;
    err->code = code;
    err->line = line;
    snprintf(err->file, sizeof err->file, "%s", file ? file : "");
    va_list ap;
    va_start(ap, fmt);
    char *text = format_message(file, fmt, ap);
    va_end(ap);
    snprintf(err->message, sizeof err->message, "%s", text ? text : fmt);
    free(text);
}

void error_set_setting_namer(SettingNamer namer) { g_setting_namer = namer; }

void error_set_setting(Error *err, const char *setting, const char *fmt, ...)
{
    if (!err || err->code != ERR_NONE)
        return;
    const char *shown = g_setting_namer ? g_setting_namer(setting) : NULL;
    va_list ap;
    va_start(ap, fmt);
    char *text = format_message(NULL, fmt, ap);
    va_end(ap);
    error_set(err, ERR_SETTINGS, NULL, 0, "%s %s", shown ? shown : setting, text ? text : fmt);
    free(text);
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
    char *text = format_message(NULL, fmt, ap);
    va_end(ap);
    fprintf(stderr, "pt: warning: %s\n", text ? text : fmt);
    free(text);
}

int warning_count(void) { return g_warning_count; }
void warnings_set_quiet(bool quiet) { g_warnings_quiet = quiet; }

void die(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    char *text = format_message(NULL, fmt, ap);
    va_end(ap);
    fprintf(stderr, "pt: %s\n", text ? text : fmt);
    free(text);
    exit(1);
}
