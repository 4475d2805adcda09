/* gibench — one command-line parser for every command: a command declares its options in a table
 * (name, kind, where the value goes, its range, its help line) and gib_options_parse reads argv
 * against it, refusing an unknown option, a missing value or a value out of range with a message
 * naming the command and the option; `--help` prints the usage generated from the same table. */
#ifndef GIB_OPTIONS_H
#define GIB_OPTIONS_H

#include <stdio.h>

#include "harness/base/error.h"

typedef enum gib_option_kind {
    GIB_OPT_END = 0,
    GIB_OPT_TEXT,    /* const char *: the value as given */
    GIB_OPT_INT,     /* long, in [min, max] */
    GIB_OPT_FLOAT,   /* double, in [min, max] */
    GIB_OPT_FLAG,    /* int, set to 1; takes no value */
    GIB_OPT_LIST,    /* const char *[max]: the option repeated, its count in *count */
    GIB_OPT_BACKEND, /* int: egl, egl-device, osmesa or auto (gib_backend_parse) */
    GIB_OPT_CUSTOM,  /* the row's parse function reads the value into dest */
} gib_option_kind;

struct gib_option;
/* A value an option's own rule reads: 0, or -1 with err naming the option. */
typedef int (*gib_option_parse_fn)(const struct gib_option *o, const char *value, gib_error *err);

typedef struct gib_option {
    const char *name;  /* "--scene" */
    gib_option_kind kind;
    void *dest;
    double min, max;   /* INT and FLOAT: the inclusive range; LIST: max = the most values */
    const char *value; /* the value's name in the usage ("S", "WxH"); NULL for a flag */
    const char *help;  /* one line */
    int *count;        /* LIST: how many were given */
    gib_option_parse_fn parse; /* CUSTOM */
} gib_option;

/* The table's rows, sokol-style: what a row does not name is zero. */
#define GIB_OPTION_TEXT(n, d, v, h) \
    {.name = (n), .kind = GIB_OPT_TEXT, .dest = (d), .value = (v), .help = (h)}
#define GIB_OPTION_INT(n, d, lo, hi, v, h) \
    {.name = (n), .kind = GIB_OPT_INT, .dest = (d), .min = (lo), .max = (hi), .value = (v), \
     .help = (h)}
#define GIB_OPTION_FLOAT(n, d, lo, hi, v, h) \
    {.name = (n), .kind = GIB_OPT_FLOAT, .dest = (d), .min = (lo), .max = (hi), .value = (v), \
     .help = (h)}
#define GIB_OPTION_FLAG(n, d, h) {.name = (n), .kind = GIB_OPT_FLAG, .dest = (d), .help = (h)}
#define GIB_OPTION_LIST(n, d, most, cnt, v, h) \
    {.name = (n), .kind = GIB_OPT_LIST, .dest = (d), .max = (most), .count = (cnt), .value = (v), \
     .help = (h)}
#define GIB_OPTION_CUSTOM(n, d, fn, v, h) \
    {.name = (n), .kind = GIB_OPT_CUSTOM, .dest = (d), .parse = (fn), .value = (v), .help = (h)}
#define GIB_OPTION_BACKEND(n, d) \
    {.name = (n), .kind = GIB_OPT_BACKEND, .dest = (d), .value = "B", \
     .help = "the GL context: egl, egl-device, osmesa or auto"}

/* What a command is: its name, the usage line after it, and what it does (printed after the
 * options by --help; may be NULL). */
typedef struct gib_command_doc {
    const char *name, *synopsis, *about;
} gib_command_doc;

/* gib_options_parse's result besides an exit status: go on with the command. */
#define GIB_OPTIONS_PROCEED (-1)

/* Reads argv[1..argc-1] against opts (terminated by {0}). Arguments that are not options go to
 * positional[] (at most max_positional, their count in *npositional; NULL, 0: none allowed).
 * Returns GIB_OPTIONS_PROCEED, 0 after printing --help (or -h) to stdout, or 2 after an error on
 * stderr naming the command and the option, with the usage. */
int gib_options_parse(const gib_command_doc *doc, const gib_option *opts, int argc, char **argv,
                      const char **positional, int *npositional, int max_positional);
/* The usage generated from the table: the synopsis, each option with its value and help, the
 * command's text. */
void gib_options_usage(FILE *f, const gib_command_doc *doc, const gib_option *opts);

#endif
