/* SPDX-License-Identifier: MIT */
/* pbrt_parser.h: the syntax of pbrt-v4 scene files (https://pbrt.org/fileformat-v4): a stream of
 * directives (bare words), their quoted-string and number arguments, and typed parameter lists
 * ("float fov" [45], "rgb L" [1 1 1], "string filename" "a.ply", a single value may drop the
 * brackets). Include and Import are followed here: the tokens of the named file take their place
 * (Import's deferred semantics make no difference to a reader that builds one scene), so the scene
 * layer (scene/import_pbrt.c) sees one stream. Every token and parameter carries its file and line,
 * for one-line errors "file:line: directive / parameter: what is wrong". Nothing here knows what a
 * directive means. */
#ifndef PT_PBRT_PARSER_H
#define PT_PBRT_PARSER_H

#include <stdbool.h>
#include <stddef.h>

#include "base/error.h"

typedef enum {
    PBRT_TOKEN_END,    /* end of the main file */
    PBRT_TOKEN_WORD,   /* a directive name, or true/false */
    PBRT_TOKEN_STRING, /* "quoted", escapes decoded */
    PBRT_TOKEN_NUMBER,
    PBRT_TOKEN_OPEN,   /* [ */
    PBRT_TOKEN_CLOSE,  /* ] */
} PbrtTokenKind;

typedef struct {
    PbrtTokenKind kind;
    char *text;    /* WORD and STRING: NUL-terminated, owned by the reader until the next token */
    double number; /* NUMBER */
    const char *file;
    int line;
} PbrtToken;

/* The parameter types: X(enum name, the type's spelling in the file, numbers per element
 * (0: strings), alternative spelling or NULL). bool values are held as numbers 0 / 1. */
#define PBRT_PARAM_TYPES(X)                                                                        \
    X(INTEGER, "integer", 1, NULL)                                                                 \
    X(FLOAT, "float", 1, NULL)                                                                     \
    X(POINT2, "point2", 2, NULL)                                                                   \
    X(VECTOR2, "vector2", 2, NULL)                                                                 \
    X(POINT3, "point3", 3, "point")                                                                \
    X(VECTOR3, "vector3", 3, "vector")                                                             \
    X(NORMAL3, "normal3", 3, "normal")                                                             \
    X(RGB, "rgb", 3, "color")                                                                      \
    X(SPECTRUM, "spectrum", 1, NULL) /* numbers (lambda, value pairs) or one string (a name) */    \
    X(BLACKBODY, "blackbody", 1, NULL)                                                             \
    X(BOOL, "bool", 1, NULL)                                                                       \
    X(STRING, "string", 0, NULL)                                                                   \
    X(TEXTURE, "texture", 0, NULL)
#define PBRT_PARAM_ENUM(name, spelling, per, alt) PBRT_##name,
typedef enum { PBRT_PARAM_TYPES(PBRT_PARAM_ENUM) PBRT_PARAM_TYPE_COUNT } PbrtParamType;
#undef PBRT_PARAM_ENUM

typedef struct {
    PbrtParamType type;
    char name[64];
    double *numbers; /* count numbers, or NULL */
    char **strings;  /* count strings, or NULL */
    int count;       /* values as written (numbers or strings) */
    int line;
    bool used;       /* set by the reader of the parameter: unused ones are warned about */
} PbrtParam;

typedef struct {
    PbrtParam *items;
    int count;
    const char *file;
    int line; /* the directive's */
} PbrtParams;

typedef struct PbrtReader PbrtReader;

/* Opens the main file (a regular file, io/input_file.h). NULL: err set. */
PbrtReader *pbrt_reader_open(const char *path, Error *err);
void pbrt_reader_close(PbrtReader *r);
/* The next token, following Include/Import (whose names must stay inside the main file's folder:
 * base/fs.h fs_resolve_inside). False: err set (a lexical error, or a file that cannot be read). */
bool pbrt_next(PbrtReader *r, PbrtToken *t, Error *err);
/* The next token without consuming it. */
bool pbrt_peek(PbrtReader *r, PbrtToken *t, Error *err);
/* The parameter list that follows a directive's arguments (it ends at the next bare word). */
bool pbrt_read_params(PbrtReader *r, const char *directive, PbrtParams *out, Error *err);
void pbrt_params_free(PbrtParams *p);
/* The main file's path. */
const char *pbrt_reader_path(const PbrtReader *r);

/* The parameter called name (any type; marked used), or NULL. */
PbrtParam *pbrt_param(PbrtParams *p, const char *name);
const char *pbrt_param_type_name(PbrtParamType type);

#endif
