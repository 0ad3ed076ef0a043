// SPDX-License-Identifier: MIT
/* One pass over the OBJ text before tinyobjloader sees it: the only place that still knows line
 * numbers and the exact tokens, so every bad record is reported where it is. */
#include "io/obj_lines.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"

typedef enum {
    RECORD_OTHER,
    RECORD_POSITION,
    RECORD_TEXCOORD,
    RECORD_NORMAL,
    RECORD_FACE
} RecordKind;

typedef struct {
    const char *next, *end; /* rest of the file */
    const char *line, *line_end;
    int number; /* 1-based number of `line` */
} LineCursor;

/* A face index with a positive value is resolved against the whole file, so it can only be checked
 * at the end: remember the largest one of each kind and where it was. */
typedef struct {
    long long value;
    int line;
    const char *corner; /* the corner's text in the file */
    int corner_length;
} LargestIndex;

static const char *const kind_names[] = {"", "position", "texcoord", "normal"};

static bool is_blank(char c) { return c == ' ' || c == '\t'; }

/* Advances to the next line; \n, \r\n and \r all end a line (tinyobjloader's safeGetline). */
static bool next_line(LineCursor *cursor)
{
    if (cursor->next >= cursor->end)
        return false;
    const char *p = memchr(cursor->next, '\n', (size_t)(cursor->end - cursor->next));
    if (!p)
        p = cursor->end;
    const char *carriage_return = memchr(cursor->next, '\r', (size_t)(p - cursor->next));
    if (carriage_return)
        p = carriage_return;
    cursor->line = cursor->next;
    cursor->line_end = p;
    if (p < cursor->end && *p == '\r' && p + 1 < cursor->end && p[1] == '\n')
        p++;
    cursor->next = p < cursor->end ? p + 1 : p;
    cursor->number++;
    return true;
}

/* Classifies a line and moves *p past its keyword. */
static RecordKind record_kind(const char **p, const char *end)
{
    const char *s = *p;
    while (s < end && is_blank(*s))
        s++;
    if (end - s < 2 || (s[0] != 'v' && s[0] != 'f'))
        return RECORD_OTHER; /* the common case, decided on one byte */
    RecordKind kind = RECORD_OTHER;
    if (is_blank(s[1]))
        kind = s[0] == 'v' ? RECORD_POSITION : RECORD_FACE;
    else if (end - s >= 3 && s[0] == 'v' && is_blank(s[2]))
        kind = s[1] == 't' ? RECORD_TEXCOORD : s[1] == 'n' ? RECORD_NORMAL : RECORD_OTHER;
    if (kind != RECORD_OTHER)
        *p = s + (kind == RECORD_TEXCOORD || kind == RECORD_NORMAL ? 2 : 1);
    return kind;
}

/* Next blank-separated token of [*p, end); false at the end of the line. */
static bool next_token(const char **p, const char *end, const char **token, const char **token_end)
{
    const char *s = *p;
    while (s < end && is_blank(*s))
        s++;
    if (s == end)
        return false;
    *token = s;
    while (s < end && !is_blank(*s))
        s++;
    *token_end = s;
    *p = s;
    return true;
}

static void copy_token(char *out, size_t size, const char *token, const char *token_end)
{
    size_t n = (size_t)(token_end - token);
    snprintf(out, size, "%.*s", (int)(n < size ? n : size - 1), token);
}

static size_t count_tokens(const char *p, const char *end)
{
    size_t count = 0;
    const char *token, *token_end;
    while (next_token(&p, end, &token, &token_end))
        count++;
    return count;
}

/* ERR_NONE when the token is a decimal number tinyobjloader reads exactly ([sign] digits [. digits]
 * [e [sign] digits]) that fits a float; the text is converted only when it could overflow. */
static ErrorCode check_number(const char *token, const char *token_end)
{
    const char *s = token;
    if (s < token_end && (*s == '+' || *s == '-'))
        s++;
    size_t integer_digits = 0, digits = 0;
    for (; s < token_end && *s >= '0' && *s <= '9'; s++)
        integer_digits++;
    digits = integer_digits;
    if (s < token_end && *s == '.')
        for (s++; s < token_end && *s >= '0' && *s <= '9'; s++)
            digits++;
    bool exponent = false, grammar_ok = digits > 0;
    if (grammar_ok && s < token_end && (*s == 'e' || *s == 'E')) {
        exponent = true;
        s++;
        if (s < token_end && (*s == '+' || *s == '-'))
            s++;
        const char *exponent_digits = s;
        while (s < token_end && *s >= '0' && *s <= '9')
            s++;
        grammar_ok = s > exponent_digits;
    }
    grammar_ok = grammar_ok && s == token_end;
    if (grammar_ok && !exponent && integer_digits < 39) /* below 1e38 < FLT_MAX */
        return ERR_NONE;
    char text[128];
    copy_token(text, sizeof text, token, token_end);
    char *parsed_end = NULL;
    float value = strtof(text, &parsed_end);
    if (*parsed_end == '\0' && !isfinite(value))
        return ERR_OBJ_NONFINITE; /* nan, inf, or too large for a float */
    return grammar_ok ? ERR_NONE : ERR_OBJ_PARSE;
}

static bool check_coordinates(const char *p, const char *end, RecordKind kind, const char *path,
                              int line, Error *err)
{
    static const char *const record_names[] = {"", "vertex", "texture coordinate", "normal"};
    size_t needed = kind == RECORD_TEXCOORD ? 1 : 3;
    size_t count = 0;
    const char *token, *token_end;
    while (count < 3 && next_token(&p, end, &token, &token_end) && *token != '#') {
        ErrorCode code = check_number(token, token_end);
        if (code != ERR_NONE) {
            char text[64];
            copy_token(text, sizeof text, token, token_end);
            error_set(err, code, path, line, "%s:%d: %s coordinate '%s' is %s", path, line,
                      record_names[kind], text,
                      code == ERR_OBJ_NONFINITE ? "not finite as a float" : "not a number");
            return false;
        }
        count++;
    }
    if (count < needed) {
        error_set(err, ERR_OBJ_PARSE, path, line, "%s:%d: %s needs %zu coordinates, has %zu", path,
                  line, record_names[kind], needed, count);
        return false;
    }
    return true;
}

/* Reads a signed integer, clamped far beyond any valid index so that it cannot overflow. */
static bool parse_index(const char **p, const char *end, long long *value)
{
    const char *s = *p;
    bool negative = s < end && *s == '-';
    if (s < end && (*s == '-' || *s == '+'))
        s++;
    const char *digits = s;
    long long magnitude = 0;
    for (; s < end && *s >= '0' && *s <= '9'; s++)
        if (magnitude < (1LL << 40))
            magnitude = magnitude * 10 + (*s - '0');
    if (s == digits)
        return false;
    *value = negative ? -magnitude : magnitude;
    *p = s;
    return true;
}

/* Splits a corner token (i, i/j, i//k or i/j/k) into its position, texcoord and normal index
 * values; present[] says which were given. */
static bool parse_corner(const char *token, const char *token_end, long long values[3],
                         bool present[3])
{
    const char *s = token;
    present[0] = present[1] = present[2] = false;
    for (int field = 0; field < 3; field++) {
        if (field > 0) {
            if (s == token_end)
                break;
            if (*s != '/')
                return false;
            s++;
        }
        if (field == 1 && s < token_end && *s == '/')
            continue; /* i//k: no texcoord */
        if (!parse_index(&s, token_end, &values[field]))
            return false;
        present[field] = true;
    }
    return s == token_end;
}

static void index_error(Error *err, const char *path, int line, int kind, long long value,
                        const char *corner, int corner_length, size_t defined)
{
    error_set(err, ERR_OBJ_INDEX, path, line,
              "%s:%d: face %s index %lld out of range (corner '%.*s', %zu %ss defined)", path, line,
              kind_names[kind], value, corner_length, corner, defined, kind_names[kind]);
}

/* Checks one face; negative indices against the records so far, positive ones remembered. */
static bool check_face(const char *p, const char *end, const size_t defined[4],
                       LargestIndex largest[4], const char *path, int line, size_t *corners,
                       Error *err)
{
    const char *token, *token_end;
    *corners = 0;
    while (next_token(&p, end, &token, &token_end)) {
        long long values[3];
        bool present[3];
        int length = (int)(token_end - token < 64 ? token_end - token : 64);
        if (!parse_corner(token, token_end, values, present)) {
            error_set(err, ERR_OBJ_PARSE, path, line,
                      "%s:%d: face corner '%.*s' is not i, i/j, i//k or i/j/k", path, line, length,
                      token);
            return false;
        }
        for (int kind = RECORD_POSITION; kind <= RECORD_NORMAL; kind++) {
            if (!present[kind - RECORD_POSITION])
                continue;
            long long value = values[kind - RECORD_POSITION];
            if (value == 0 || (value < 0 && (unsigned long long)-value > defined[kind])) {
                index_error(err, path, line, kind, value, token, length, defined[kind]);
                return false;
            }
            if (value > largest[kind].value) {
                largest[kind].value = value;
                largest[kind].line = line;
                largest[kind].corner = token;
                largest[kind].corner_length = length;
            }
        }
        (*corners)++;
    }
    if (*corners > OBJ_MAX_FACE_CORNERS) {
        error_set(err, ERR_TOO_LARGE, path, line,
                  "%s:%d: face with %zu corners: at most %d are supported", path, line, *corners,
                  OBJ_MAX_FACE_CORNERS);
        return false;
    }
    if (*corners < 3)
        warn("%s:%d: face with %zu corners skipped", path, line, *corners);
    return true;
}

/* Control bytes other than blanks and line ends never occur in OBJ text: they mean the file is
 * something else (an image, an archive) and every "record" in it would be noise. */
static const char *find_binary_byte(const char *p, const char *end)
{
    for (; p < end; p++) {
        unsigned char c = (unsigned char)*p;
        bool text_control = c == '\t' || c == '\v' || c == '\f' || c == '\r' || c == '\n';
        if ((c < 0x20 && !text_control) || c == 0x7f)
            return p;
    }
    return NULL;
}

/* Lines that are not text, or absurdly long ones (tinyobjloader copies each line into a string). */
static bool check_line_text(const LineCursor *cursor, const char *path, Error *err)
{
    size_t length = (size_t)(cursor->line_end - cursor->line);
    if (length > OBJ_MAX_LINE_LENGTH) {
        error_set(err, ERR_TOO_LARGE, path, cursor->number,
                  "%s:%d: line of %zu bytes, over the limit of %d", path, cursor->number, length,
                  OBJ_MAX_LINE_LENGTH);
        return false;
    }
    const char *binary = find_binary_byte(cursor->line, cursor->line_end);
    if (binary) {
        error_set(err, ERR_OBJ_PARSE, path, cursor->number,
                  "%s:%d: not an OBJ text file (binary data at line %d: byte 0x%02x)", path,
                  cursor->number, cursor->number, (unsigned char)*binary);
        return false;
    }
    return true;
}

bool obj_lines_check(const char *text, size_t size, const char *path, ObjRecordCounts *counts,
                     Error *err)
{
    size_t defined[4] = {0, 0, 0, 0}; /* by RecordKind */
    LargestIndex largest[4];
    memset(largest, 0, sizeof largest);
    size_t faces = 0;
    LineCursor cursor = {.next = text, .end = text + size};
    while (next_line(&cursor)) {
        if (!check_line_text(&cursor, path, err))
            return false;
        const char *p = cursor.line;
        RecordKind kind = record_kind(&p, cursor.line_end);
        if (kind == RECORD_FACE) {
            size_t corners;
            if (!check_face(p, cursor.line_end, defined, largest, path, cursor.number, &corners,
                            err))
                return false;
            faces += corners >= 3;
        } else if (kind != RECORD_OTHER) {
            if (!check_coordinates(p, cursor.line_end, kind, path, cursor.number, err))
                return false;
            defined[kind]++;
        }
    }
    for (int kind = RECORD_POSITION; kind <= RECORD_NORMAL; kind++)
        if ((unsigned long long)largest[kind].value > defined[kind]) {
            index_error(err, path, largest[kind].line, kind, largest[kind].value,
                        largest[kind].corner, largest[kind].corner_length, defined[kind]);
            return false;
        }
    *counts = (ObjRecordCounts){.positions = defined[RECORD_POSITION],
                                .texcoords = defined[RECORD_TEXCOORD],
                                .normals = defined[RECORD_NORMAL],
                                .faces = faces};
    return true;
}

int obj_lines_find_record(const char *text, size_t size, const char *keyword, size_t ordinal)
{
    RecordKind wanted = strcmp(keyword, "v") == 0    ? RECORD_POSITION
                        : strcmp(keyword, "vt") == 0 ? RECORD_TEXCOORD
                        : strcmp(keyword, "vn") == 0 ? RECORD_NORMAL
                        : strcmp(keyword, "f") == 0  ? RECORD_FACE
                                                     : RECORD_OTHER;
    if (wanted == RECORD_OTHER)
        return 0;
    size_t seen = 0;
    LineCursor cursor = {.next = text, .end = text + size};
    while (next_line(&cursor)) {
        const char *p = cursor.line;
        if (record_kind(&p, cursor.line_end) != wanted)
            continue;
        if (wanted == RECORD_FACE && count_tokens(p, cursor.line_end) < 3)
            continue;
        if (seen++ == ordinal)
            return cursor.number;
    }
    return 0;
}
