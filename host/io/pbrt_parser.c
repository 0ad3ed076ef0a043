// SPDX-License-Identifier: MIT
/* pbrt_parser.c: the tokenizer of pbrt-v4 files, the Include/Import file stack and typed parameter
 * lists (io/pbrt_parser.h). */
#include "io/pbrt_parser.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/fs.h"
#include "io/input_file.h"

#define PBRT_FILE_LIMIT ((size_t)1 << 30)
#define PBRT_INCLUDE_DEPTH 32 /* also ends include cycles */
#define PBRT_PARAM_VALUES_LIMIT (1 << 28)

typedef struct {
    char path[1024];
    char *text;
    size_t pos;
    int line;
} PbrtFile;

struct PbrtReader {
    PbrtFile files[PBRT_INCLUDE_DEPTH];
    int depth;       /* files open; files[depth - 1] is read */
    char *token;     /* the current WORD / STRING text */
    size_t token_cap;
    PbrtToken peeked;
    bool has_peeked;
};

static const char *const type_spellings[] = {
#define PBRT_PARAM_SPELLING(name, spelling, per, alt) spelling,
    PBRT_PARAM_TYPES(PBRT_PARAM_SPELLING)
#undef PBRT_PARAM_SPELLING
};
static const char *const type_alternatives[] = {
#define PBRT_PARAM_ALT(name, spelling, per, alt) alt,
    PBRT_PARAM_TYPES(PBRT_PARAM_ALT)
#undef PBRT_PARAM_ALT
};

const char *pbrt_param_type_name(PbrtParamType type) { return type_spellings[type]; }

static bool push_file(PbrtReader *r, const char *path, Error *err)
{
    if (r->depth == PBRT_INCLUDE_DEPTH) {
        PbrtFile *f = &r->files[r->depth - 1];
        error_set(err, ERR_FILE_READ, f->path, f->line, "%s:%d: Include: more than %d files deep "
                  "(an include cycle?)", f->path, f->line, PBRT_INCLUDE_DEPTH);
        return false;
    }
    PbrtFile *f = &r->files[r->depth];
    size_t size;
    if (!input_file_read(path, "a pbrt file", PBRT_FILE_LIMIT, &f->text, &size, err))
        return false;
    if (strlen(f->text) != size) {
        free(f->text);
        error_set(err, ERR_FILE_READ, path, 0, "%s: NUL byte in the pbrt file", path);
        return false;
    }
    snprintf(f->path, sizeof f->path, "%s", path);
    f->pos = 0;
    f->line = 1;
    r->depth++;
    return true;
}

PbrtReader *pbrt_reader_open(const char *path, Error *err)
{
    PbrtReader *r = calloc(1, sizeof *r);
    if (!r) {
        error_set(err, ERR_OUT_OF_MEMORY, path, 0, "%s: out of memory", path);
        return NULL;
    }
    if (!push_file(r, path, err)) {
        free(r);
        return NULL;
    }
    return r;
}

void pbrt_reader_close(PbrtReader *r)
{
    if (!r)
        return;
    for (int i = 0; i < r->depth; i++)
        free(r->files[i].text);
    free(r->token);
    free(r);
}

const char *pbrt_reader_path(const PbrtReader *r) { return r->files[0].path; }

static bool token_append(PbrtReader *r, size_t *len, char c)
{
    if (*len + 2 > r->token_cap) {
        size_t cap = r->token_cap ? 2 * r->token_cap : 256;
        char *grown = realloc(r->token, cap);
        if (!grown)
            return false;
        r->token = grown;
        r->token_cap = cap;
    }
    r->token[(*len)++] = c;
    r->token[*len] = '\0';
    return true;
}

static bool lex_fail(PbrtFile *f, Error *err, const char *what)
{
    error_set(err, ERR_FILE_READ, f->path, f->line, "%s:%d: %s", f->path, f->line, what);
    return false;
}

/* A quoted string, f->pos just after the opening quote. pbrt's escapes: \n \t \b \f \r \\ \" \'. */
static bool lex_string(PbrtReader *r, PbrtFile *f, Error *err)
{
    size_t len = 0;
    if (!token_append(r, &len, 'x'))
        return lex_fail(f, err, "out of memory");
    len = 0;
    r->token[0] = '\0';
    for (;;) {
        char c = f->text[f->pos++];
        if (c == '\0' || c == '\n')
            return lex_fail(f, err, "unterminated string");
        if (c == '"')
            return true;
        if (c == '\\') {
            char e = f->text[f->pos++];
            static const char from[] = "ntbfr\\\"'", to[] = "\n\t\b\f\r\\\"'";
            const char *hit = e ? strchr(from, e) : NULL;
            if (!hit)
                return lex_fail(f, err, "unknown escape in a string");
            c = to[hit - from];
        }
        if (!token_append(r, &len, c))
            return lex_fail(f, err, "out of memory");
    }
}

/* One token of the current file; END at its end (the caller pops it). */
static bool lex(PbrtReader *r, PbrtToken *t, Error *err)
{
    PbrtFile *f = &r->files[r->depth - 1];
    const char *s = f->text;
    for (;;) {
        while (s[f->pos] == ' ' || s[f->pos] == '\t' || s[f->pos] == '\r' || s[f->pos] == '\n')
            f->line += s[f->pos++] == '\n';
        if (s[f->pos] != '#')
            break;
        while (s[f->pos] && s[f->pos] != '\n')
            f->pos++;
    }
    *t = (PbrtToken){.file = f->path, .line = f->line};
    char c = s[f->pos];
    if (c == '\0') {
        t->kind = PBRT_TOKEN_END;
        return true;
    }
    if (c == '[' || c == ']') {
        f->pos++;
        t->kind = c == '[' ? PBRT_TOKEN_OPEN : PBRT_TOKEN_CLOSE;
        return true;
    }
    if (c == '"') {
        f->pos++;
        t->kind = PBRT_TOKEN_STRING;
        bool ok = lex_string(r, f, err);
        t->text = r->token;
        return ok;
    }
    if (isdigit((unsigned char)c) || c == '-' || c == '+' || c == '.') {
        char *end;
        errno = 0;
        t->number = strtod(s + f->pos, &end);
        if (end == s + f->pos || !isfinite(t->number) ||
            (*end && !isspace((unsigned char)*end) && *end != ']' && *end != '[' && *end != '"' && *end != '#'))
            return lex_fail(f, err, "malformed number");
        f->pos = (size_t)(end - s);
        t->kind = PBRT_TOKEN_NUMBER;
        return true;
    }
    if (!isalpha((unsigned char)c))
        return lex_fail(f, err, "unexpected character");
    size_t len = 0;
    while (isalnum((unsigned char)s[f->pos]) || s[f->pos] == '_')
        if (!token_append(r, &len, s[f->pos++]))
            return lex_fail(f, err, "out of memory");
    t->kind = PBRT_TOKEN_WORD;
    t->text = r->token;
    return true;
}

/* Include "file" / Import "file": the named file is read next, resolved against the main file's
 * folder as pbrt-v4 resolves every relative name (its search directory). */
static bool include(PbrtReader *r, const char *directive, Error *err)
{
    PbrtToken name;
    PbrtFile *f = &r->files[r->depth - 1];
    int line = f->line;
    if (!lex(r, &name, err))
        return false;
    if (name.kind != PBRT_TOKEN_STRING) {
        error_set(err, ERR_FILE_READ, f->path, line, "%s:%d: %s: expected a quoted file name",
                  f->path, line, directive);
        return false;
    }
    char resolved[1024];
    Error escaped = {0};
    if (!fs_resolve_inside(r->files[0].path, name.text, directive, resolved, sizeof resolved, &escaped)) {
        error_set(err, escaped.code, f->path, line, "%s:%d: %.900s", f->path, line, escaped.message);
        return false;
    }
    return push_file(r, resolved, err);
}

static bool next_token(PbrtReader *r, PbrtToken *t, Error *err)
{
    for (;;) {
        if (!lex(r, t, err))
            return false;
        if (t->kind == PBRT_TOKEN_END && r->depth > 1) {
            free(r->files[--r->depth].text);
            continue;
        }
        if (t->kind == PBRT_TOKEN_WORD && (strcmp(t->text, "Include") == 0 || strcmp(t->text, "Import") == 0)) {
            char directive[8];
            snprintf(directive, sizeof directive, "%s", t->text);
            if (!include(r, directive, err))
                return false;
            continue;
        }
        return true;
    }
}

bool pbrt_next(PbrtReader *r, PbrtToken *t, Error *err)
{
    if (r->has_peeked) {
        *t = r->peeked;
        r->has_peeked = false;
        return true;
    }
    return next_token(r, t, err);
}

bool pbrt_peek(PbrtReader *r, PbrtToken *t, Error *err)
{
    if (!r->has_peeked) {
        if (!next_token(r, &r->peeked, err))
            return false;
        r->has_peeked = true;
    }
    *t = r->peeked;
    return true;
}

/* ---- Parameter lists ------------------------------------------------------------------------ */

void pbrt_params_free(PbrtParams *p)
{
    for (int i = 0; i < p->count; i++) {
        free(p->items[i].numbers);
        for (int k = 0; p->items[i].strings && k < p->items[i].count; k++)
            free(p->items[i].strings[k]);
        free(p->items[i].strings);
    }
    free(p->items);
    memset(p, 0, sizeof *p);
}

PbrtParam *pbrt_param(PbrtParams *p, const char *name)
{
    for (int i = 0; i < p->count; i++)
        if (strcmp(p->items[i].name, name) == 0) {
            p->items[i].used = true;
            return &p->items[i];
        }
    return NULL;
}

static bool param_fail(const PbrtToken *t, Error *err, const char *directive, const char *param,
                       const char *what)
{
    error_set(err, ERR_FILE_READ, t->file, t->line, "%s:%d: %s: \"%s\": %s", t->file, t->line,
              directive, param, what);
    return false;
}

/* "type name": the declaration's two words. */
static bool parse_declaration(const PbrtToken *t, PbrtParam *p, Error *err, const char *directive)
{
    char type[32], name[64], extra;
    if (sscanf(t->text, " %31s %63s %c", type, name, &extra) != 2)
        return param_fail(t, err, directive, t->text, "expected \"type name\" (e.g. \"float fov\")");
    for (int i = 0; i < PBRT_PARAM_TYPE_COUNT; i++)
        if (strcmp(type, type_spellings[i]) == 0 ||
            (type_alternatives[i] && strcmp(type, type_alternatives[i]) == 0)) {
            p->type = (PbrtParamType)i;
            snprintf(p->name, sizeof p->name, "%s", name);
            return true;
        }
    return param_fail(t, err, directive, t->text, "unknown parameter type");
}

/* One value of p from token v (a number, a string or a bare true/false). */
static bool add_value(PbrtParam *p, const PbrtToken *v, Error *err, const char *directive)
{
    bool is_string_type = p->type == PBRT_STRING || p->type == PBRT_TEXTURE ||
                          (p->type == PBRT_SPECTRUM && v->kind == PBRT_TOKEN_STRING);
    if (p->count >= PBRT_PARAM_VALUES_LIMIT)
        return param_fail(v, err, directive, p->name, "too many values");
    if (is_string_type) {
        if (v->kind != PBRT_TOKEN_STRING || p->numbers)
            return param_fail(v, err, directive, p->name, "expected a quoted string");
        char **grown = realloc(p->strings, (size_t)(p->count + 1) * sizeof *grown);
        size_t len = strlen(v->text) + 1;
        char *copy = grown ? malloc(len) : NULL;
        if (grown)
            p->strings = grown;
        if (!copy)
            return param_fail(v, err, directive, p->name, "out of memory");
        memcpy(copy, v->text, len);
        p->strings[p->count++] = copy;
        return true;
    }
    double x;
    if (p->type == PBRT_BOOL) {
        if ((v->kind != PBRT_TOKEN_STRING && v->kind != PBRT_TOKEN_WORD) ||
            (strcmp(v->text, "true") != 0 && strcmp(v->text, "false") != 0))
            return param_fail(v, err, directive, p->name, "expected true or false");
        x = strcmp(v->text, "true") == 0;
    } else if (v->kind == PBRT_TOKEN_NUMBER) {
        x = v->number;
        if (p->type == PBRT_INTEGER && (x != floor(x) || fabs(x) > 2147483647.0))
            return param_fail(v, err, directive, p->name, "expected an integer");
    } else {
        return param_fail(v, err, directive, p->name, "expected a number");
    }
    if ((p->count & (p->count - 1)) == 0) { /* grow at powers of two */
        double *grown = realloc(p->numbers, (size_t)(p->count ? 2 * p->count : 1) * sizeof *grown);
        if (!grown)
            return param_fail(v, err, directive, p->name, "out of memory");
        p->numbers = grown;
    }
    p->numbers[p->count++] = x;
    return true;
}

static bool read_values(PbrtReader *r, PbrtParam *p, Error *err, const char *directive)
{
    PbrtToken v;
    if (!pbrt_next(r, &v, err))
        return false;
    if (v.kind != PBRT_TOKEN_OPEN)
        return add_value(p, &v, err, directive);
    for (;;) {
        if (!pbrt_next(r, &v, err))
            return false;
        if (v.kind == PBRT_TOKEN_CLOSE)
            return true;
        if (v.kind == PBRT_TOKEN_END)
            return param_fail(&v, err, directive, p->name, "unterminated [");
        if (!add_value(p, &v, err, directive))
            return false;
    }
}

/* The element count per value is checked here, so readers index without checks. */
static bool check_shape(const PbrtToken *t, const PbrtParam *p, Error *err, const char *directive)
{
    static const int per[] = {
#define PBRT_PARAM_PER(name, spelling, n, alt) n,
        PBRT_PARAM_TYPES(PBRT_PARAM_PER)
#undef PBRT_PARAM_PER
    };
    if (p->count == 0)
        return param_fail(t, err, directive, p->name, "no values");
    if (per[p->type] > 1 && p->count % per[p->type] != 0) {
        char what[96];
        snprintf(what, sizeof what, "%d values is not a multiple of %d (%s)", p->count, per[p->type],
                 type_spellings[p->type]);
        return param_fail(t, err, directive, p->name, what);
    }
    if (p->type == PBRT_SPECTRUM && p->numbers && p->count % 2 != 0)
        return param_fail(t, err, directive, p->name, "a spectrum needs (wavelength, value) pairs");
    return true;
}

bool pbrt_read_params(PbrtReader *r, const char *directive, PbrtParams *out, Error *err)
{
    memset(out, 0, sizeof *out);
    PbrtToken t;
    if (!pbrt_peek(r, &t, err))
        return false;
    out->file = t.file;
    out->line = t.line;
    for (;;) {
        if (!pbrt_peek(r, &t, err))
            return false;
        if (t.kind != PBRT_TOKEN_STRING)
            return true;
        PbrtToken declaration = t;
        PbrtParam p = {.line = t.line};
        if (!parse_declaration(&t, &p, err, directive))
            return false;
        pbrt_next(r, &t, err);
        for (int i = 0; i < out->count; i++)
            if (strcmp(out->items[i].name, p.name) == 0)
                return param_fail(&declaration, err, directive, p.name, "given twice");
        PbrtParam *grown = realloc(out->items, (size_t)(out->count + 1) * sizeof *grown);
        if (!grown)
            return param_fail(&declaration, err, directive, p.name, "out of memory");
        out->items = grown;
        out->items[out->count++] = p;
        if (!read_values(r, &out->items[out->count - 1], err, directive) ||
            !check_shape(&declaration, &out->items[out->count - 1], err, directive))
            return false;
    }
}
