#include "options.h"

#include <string.h>

#include "app.h"
#include "harness/gl/context.h"

void gib_options_usage(FILE *f, const gib_command_doc *doc, const gib_option *opts)
{
    fprintf(f, "usage: gibench %s%s%s\n\noptions:\n", doc->name, doc->synopsis[0] ? " " : "",
            doc->synopsis);
    for (int i = 0; opts && opts[i].name; i++) {
        char head[64];
        snprintf(head, sizeof head, "%s%s%s", opts[i].name, opts[i].value ? " " : "",
                 opts[i].value ? opts[i].value : "");
        fprintf(f, "  %-22s %s\n", head, opts[i].help);
    }
    fputs("  --help                 this text\n", f);
    if (doc->about)
        fprintf(f, "\n%s", doc->about);
}

static const gib_option *find(const gib_option *opts, const char *name)
{
    for (int i = 0; opts && opts[i].name; i++)
        if (!strcmp(opts[i].name, name))
            return &opts[i];
    return NULL;
}

/* Stores v into o's destination: 0, or -1 with err naming the option. */
static int store(const gib_option *o, const char *v, gib_error *err)
{
    switch (o->kind) {
    case GIB_OPT_TEXT:
        *(const char **)o->dest = v;
        return 0;
    case GIB_OPT_INT:
        return gib_parse_int(o->name, v, (long)o->min, (long)o->max, (long *)o->dest, err);
    case GIB_OPT_FLOAT:
        return gib_parse_float(o->name, v, o->min, o->max, (double *)o->dest, err);
    case GIB_OPT_LIST:
        if (*o->count >= (int)o->max)
            return gib_fail(err, "%s given more than %d times", o->name, (int)o->max);
        ((const char **)o->dest)[(*o->count)++] = v;
        return 0;
    case GIB_OPT_BACKEND:
        if ((*(int *)o->dest = gib_backend_parse(v)) < 0)
            return gib_fail(err, "%s expects egl, egl-device, osmesa or auto, got '%s'", o->name,
                            v);
        return 0;
    case GIB_OPT_CUSTOM:
        return o->parse(o, v, err);
    case GIB_OPT_FLAG:
    case GIB_OPT_END:
        break;
    }
    return gib_fail(err, "%s: no value expected", o->name);
}

static int usage_error(const gib_command_doc *doc, const gib_option *opts, const char *msg)
{
    fprintf(stderr, "gibench %s: %s\n", doc->name, msg);
    gib_options_usage(stderr, doc, opts);
    return 2;
}

int gib_options_parse(const gib_command_doc *doc, const gib_option *opts, int argc, char **argv,
                      const char **positional, int *npositional, int max_positional)
{
    char msg[512];
    if (npositional)
        *npositional = 0;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            gib_options_usage(stdout, doc, opts);
            return 0;
        }
        if (a[0] != '-' || !a[1]) {
            if (!npositional || *npositional >= max_positional) {
                snprintf(msg, sizeof msg, "unexpected argument '%s'", a);
                return usage_error(doc, opts, msg);
            }
            positional[(*npositional)++] = a;
            continue;
        }
        const gib_option *o = find(opts, a);
        if (!o) {
            snprintf(msg, sizeof msg, "unknown option '%s'", a);
            return usage_error(doc, opts, msg);
        }
        if (o->kind == GIB_OPT_FLAG) {
            *(int *)o->dest = 1;
            continue;
        }
        if (i + 1 >= argc) {
            snprintf(msg, sizeof msg, "option %s needs a value", a);
            return usage_error(doc, opts, msg);
        }
        gib_error err = {0};
        if (store(o, argv[++i], &err) < 0) {
            fprintf(stderr, "gibench %s: %s\n", doc->name, err.msg);
            return 2;
        }
    }
    return GIB_OPTIONS_PROCEED;
}
