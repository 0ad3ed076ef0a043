/* SPDX-License-Identifier: MIT */
/* cli_options.h: the one list of pt's options (cli_options.c). Each row gives an option's name,
 * what its value is and where it goes in Options, the commands that take it and its help lines;
 * cli.c derives from it getopt_long's table, the parser, `pt help` and the refusal of an option
 * that a command would ignore. Adding an option is adding a row (and its Options field). */
#ifndef PT_CLI_OPTIONS_H
#define PT_CLI_OPTIONS_H

#include <stdbool.h>
#include <stddef.h>

#include "app/options.h"
#include "base/error.h"

typedef enum {
    ARG_INT,    /* int field, value in [min, max] */
    ARG_FLOAT,  /* float field, a finite number in [min, max] */
    ARG_NUMBER, /* double field, a finite number in [min, max] */
    ARG_TEXT,   /* const char * field: the value as given */
    ARG_FLAG,   /* bool field set true; no value */
    ARG_SET,    /* int field set to min; no value */
    ARG_CUSTOM, /* parse() reads the value */
    ARG_CUSTOM_FLAG, /* parse() with no value */
    ARG_HELP_ONLY, /* no option: one more help line for the option of the row before */
} ArgKind;

/* Where `pt help` prints a row: the options list, the `pt view` list, or nowhere (the usage lines
 * describe --help, --version and --csv). */
typedef enum { HELP_OPTIONS, HELP_VIEW, HELP_NONE } HelpSection;

typedef bool (*OptionParser)(const char *arg, const char *value, Options *o, Error *err);

typedef struct {
    const char *name;  /* the long name, without "--" */
    char short_name;   /* 0: none */
    ArgKind kind;
    size_t field;      /* offsetof(Options, ...) */
    double min, max;   /* ARG_INT, ARG_FLOAT, ARG_NUMBER: the range; ARG_SET: the value */
    OptionParser parse; /* ARG_CUSTOM, ARG_CUSTOM_FLAG */
    const char *setting; /* the RenderSettings field it sets, as render/ names it in a message
                          * (error_set_setting); NULL for the others */
    unsigned commands; /* CMD_BIT of each command that takes the option */
    HelpSection section;
    const char *usage; /* the left column of help */
    const char *help;  /* the right column; lines after the first indented to it; NULL: the row
                        * is covered by another's help line (--height by --width's) */
} CliOption;

#define CMD_BIT(c) (1u << (c))

extern const CliOption cli_options[];
extern const size_t cli_option_count;

/* Reads the value of option c (written as arg, for messages) into o. */
bool cli_option_parse(const CliOption *c, const char *arg, const char *value, Options *o,
                      Error *err);

static inline bool cli_option_takes_value(const CliOption *c)
{
    return c->kind != ARG_FLAG && c->kind != ARG_SET && c->kind != ARG_CUSTOM_FLAG;
}

#endif
