/* SPDX-License-Identifier: MIT */
/* ply_header.c: the PLY header, line by line: "ply", format, element, property (scalar or list),
 * comment / obj_info (ignored), end_header, and lines of other writers' own (counted, ignored); then the element counts are checked against the size
 * of the body before the reader allocates anything by them. */
#include "io/ply_header.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

const PlyScalarType PLY_TYPES[16] = {
    {"char", 1, PLY_INT},    {"int8", 1, PLY_INT},     {"uchar", 1, PLY_UINT},
    {"uint8", 1, PLY_UINT},  {"short", 2, PLY_INT},    {"int16", 2, PLY_INT},
    {"ushort", 2, PLY_UINT}, {"uint16", 2, PLY_UINT},  {"int", 4, PLY_INT},
    {"int32", 4, PLY_INT},   {"uint", 4, PLY_UINT},    {"uint32", 4, PLY_UINT},
    {"float", 4, PLY_FLOAT}, {"float32", 4, PLY_FLOAT}, {"double", 8, PLY_FLOAT},
    {"float64", 8, PLY_FLOAT},
};

typedef struct {
    const char *path;
    Error *err;
    const char *data;
    size_t size, pos; /* pos: the start of the next header line */
    PlyHeader *h;
    const char *line_text; /* the current line, whole (for an unknown line's warning) */
} HeaderParser;

bool ply_failv(const char *path, Error *err, ErrorCode code, int line, const char *fmt,
               va_list args)
{
    char message[768];
    vsnprintf(message, sizeof message, fmt, args);
    if (line > 0)
        error_set(err, code, path, line, "%s: line %d: %s", path, line, message);
    else
        error_set(err, code, path, 0, "%s: %s", path, message);
    return false;
}

static bool fail(HeaderParser *p, ErrorCode code, int line, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
static bool fail(HeaderParser *p, ErrorCode code, int line, const char *fmt, ...)
{
    va_list args;
    va_start(args, fmt);
    ply_failv(p->path, p->err, code, line, fmt, args);
    va_end(args);
    return false;
}

static int find_type(const char *name)
{
    for (size_t i = 0; i < sizeof PLY_TYPES / sizeof PLY_TYPES[0]; i++)
        if (strcmp(PLY_TYPES[i].name, name) == 0)
            return (int)i;
    return -1;
}

/* Splits a header line in place on blanks; returns the number of words (max + 1: too many). */
static int split_words(char *line, char **words, int max)
{
    int n = 0;
    for (char *c = line; *c;) {
        while (*c == ' ' || *c == '\t')
            *c++ = '\0';
        if (!*c)
            break;
        if (n == max)
            return max + 1;
        words[n++] = c;
        while (*c && *c != ' ' && *c != '\t')
            c++;
    }
    return n;
}

static bool parse_count(const char *text, uint64_t *out)
{
    if (!*text || strlen(text) > 19)
        return false;
    uint64_t value = 0;
    for (const char *c = text; *c; c++) {
        if (*c < '0' || *c > '9')
            return false;
        value = value * 10 + (uint64_t)(*c - '0');
    }
    *out = value;
    return true;
}

static bool parse_property(HeaderParser *p, int line, char **words, int n)
{
    if (p->h->num_elements == 0)
        return fail(p, ERR_OBJ_PARSE, line, "property before any element");
    PlyElement *e = &p->h->elements[p->h->num_elements - 1];
    if (e->num_properties == PLY_MAX_PROPERTIES)
        return fail(p, ERR_TOO_LARGE, line, "element '%s' has more than %d properties", e->name,
                    PLY_MAX_PROPERTIES);
    PlyProperty *prop = &e->properties[e->num_properties];
    const char *type = words[1], *name = words[2];
    prop->count_type = -1;
    if (n == 5 && strcmp(words[1], "list") == 0) {
        prop->count_type = find_type(words[2]);
        if (prop->count_type < 0)
            return fail(p, ERR_OBJ_PARSE, line, "unknown property type '%s'", words[2]);
        if (PLY_TYPES[prop->count_type].kind == PLY_FLOAT)
            return fail(p, ERR_OBJ_PARSE, line, "list count type '%s' is not an integer type",
                        words[2]);
        type = words[3];
        name = words[4];
    } else if (n != 3) {
        return fail(p, ERR_OBJ_PARSE, line,
                    "malformed property (expected 'property <type> <name>' or 'property list "
                    "<count type> <item type> <name>')");
    }
    prop->type = find_type(type);
    if (prop->type < 0)
        return fail(p, ERR_OBJ_PARSE, line, "unknown property type '%s'", type);
    snprintf(prop->name, sizeof prop->name, "%s", name);
    e->num_properties++;
    return true;
}

/* A line of no PLY keyword: other writers put their own lines in the header (Blender 2.47's
 * "Created by ..."); what pt needs is in the keywords, so such a line is counted, not refused. */
static bool note_unknown(HeaderParser *p, int line, const char *text)
{
    if (p->h->unknown_lines++ == 0) {
        p->h->first_unknown_line = line;
        snprintf(p->h->first_unknown, sizeof p->h->first_unknown, "%.40s", text);
    }
    return true;
}

static bool is_keyword(const char *word, size_t len)
{
    static const char *const keywords[] = {"ply", "format", "element", "property", "end_header"};
    for (size_t i = 0; i < sizeof keywords / sizeof keywords[0]; i++)
        if (strlen(keywords[i]) == len && memcmp(word, keywords[i], len) == 0)
            return true;
    return false;
}

/* One header line (words split); sets *done at end_header. */
static bool parse_header_line(HeaderParser *p, int line, char **words, int n, bool *have_format)
{
    if (strcmp(words[0], "format") == 0) {
        static const char *const formats[] = {"ascii", "binary_little_endian", "binary_big_endian"};
        for (int f = 0; n == 3 && f < 3; f++)
            if (strcmp(words[1], formats[f]) == 0) {
                if (strcmp(words[2], "1.0") != 0)
                    return fail(p, ERR_OBJ_PARSE, line, "unsupported format version '%s'",
                                words[2]);
                p->h->format = (PlyFormat)f;
                *have_format = true;
                return true;
            }
        return fail(p, ERR_OBJ_PARSE, line, "unknown format '%s'", n > 1 ? words[1] : "");
    }
    if (strcmp(words[0], "element") == 0) {
        if (n != 3)
            return fail(p, ERR_OBJ_PARSE, line,
                        "malformed element (expected 'element <name> <count>')");
        if (p->h->num_elements == PLY_MAX_ELEMENTS)
            return fail(p, ERR_TOO_LARGE, line, "more than %d elements", PLY_MAX_ELEMENTS);
        PlyElement *e = &p->h->elements[p->h->num_elements];
        if (!parse_count(words[2], &e->count))
            return fail(p, ERR_OBJ_PARSE, line, "element count '%s' is not a count", words[2]);
        snprintf(e->name, sizeof e->name, "%s", words[1]);
        p->h->num_elements++;
        return true;
    }
    if (strcmp(words[0], "property") == 0)
        return parse_property(p, line, words, n);
    return note_unknown(p, line, p->line_text);
}

static bool parse_header(HeaderParser *p)
{
    bool have_format = false;
    for (int line = 1;; line++) {
        if (p->pos >= p->size)
            return fail(p, ERR_OBJ_PARSE, 0, "missing end_header");
        const char *start = p->data + p->pos;
        const char *newline = memchr(start, '\n', p->size - p->pos);
        size_t len = newline ? (size_t)(newline - start) : p->size - p->pos;
        p->pos += len + (newline != NULL);
        if (len > 0 && start[len - 1] == '\r')
            len--;
        if (line == 1) {
            if (len != 3 || memcmp(start, "ply", 3) != 0)
                return fail(p, ERR_OBJ_PARSE, 1, "not a PLY file (the first line is not 'ply')");
            continue;
        }
        size_t skip = strspn(start, " \t");
        if (skip < len && (strncmp(start + skip, "comment", 7) == 0 ||
                           strncmp(start + skip, "obj_info", 8) == 0))
            continue;
        char text[256], *words[6];
        if (len >= sizeof text) {
            size_t word = strcspn(start + skip, " \t\r\n");
            if (!is_keyword(start + skip, word)) {
                snprintf(text, 41, "%s", start + skip);
                text[strcspn(text, "\r\n")] = '\0';
                note_unknown(p, line, text);
                continue;
            }
            return fail(p, ERR_OBJ_PARSE, line, "header line longer than %zu bytes",
                        sizeof text - 1);
        }
        memcpy(text, start, len);
        text[len] = '\0';
        if (memchr(text, '\0', len))
            return fail(p, ERR_OBJ_PARSE, line, "NUL byte in the header");
        char whole[sizeof text];
        memcpy(whole, text, len + 1);
        p->line_text = whole;
        int n = split_words(text, words, 5);
        if (n == 0)
            continue;
        if (strcmp(words[0], "end_header") == 0) {
            if (!have_format)
                return fail(p, ERR_OBJ_PARSE, line, "end_header before any format line");
            p->h->body_line = line + 1;
            p->h->body = p->pos;
            return true;
        }
        if (n > 5 && !is_keyword(words[0], strlen(words[0]))) {
            note_unknown(p, line, whole);
            continue;
        }
        if (n > 5)
            return fail(p, ERR_OBJ_PARSE, line, "too many words in '%s' line", words[0]);
        if (!parse_header_line(p, line, words, n, &have_format))
            return false;
    }
}

/* Refuses element counts the rest of the file cannot hold, before anything is allocated: an item
 * takes at least one byte per property in ascii, its scalars and list counts in binary. */
static bool check_counts(HeaderParser *p)
{
    uint64_t left = p->size - p->pos;
    for (int i = 0; i < p->h->num_elements; i++) {
        const PlyElement *e = &p->h->elements[i];
        uint64_t item = 0;
        for (int k = 0; k < e->num_properties; k++) {
            const PlyProperty *prop = &e->properties[k];
            item += p->h->format == PLY_ASCII ? 1u
                    : PLY_TYPES[prop->count_type >= 0 ? prop->count_type : prop->type].size;
        }
        if (item == 0)
            continue; /* nothing to read, nothing to allocate */
        if (e->count > left / item)
            return fail(p, ERR_OBJ_PARSE, 0,
                        "the header claims %llu '%s' elements, more than the %llu bytes of data "
                        "can hold", (unsigned long long)e->count, e->name,
                        (unsigned long long)(p->size - p->pos));
        left -= e->count * item;
    }
    return true;
}

bool ply_header_parse(const char *path, const char *data, size_t size, PlyHeader *out, Error *err)
{
    memset(out, 0, sizeof *out);
    HeaderParser p = {.path = path, .err = err, .data = data, .size = size, .h = out};
    return parse_header(&p) && check_counts(&p);
}
