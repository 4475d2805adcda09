/* gibench check-technique — one technique (built-in or from a plugin) held to the contract: the
 * descriptor checks and the contract at run time that tests/techniques/ run over every technique
 * (harness/app/technique_check.c), with a PASS or FAIL line each; exit 1 on any failure. */
#include <stdio.h>

#include "app.h"
#include "options.h"
#include "technique_check.h"

int gib_cmd_check(int argc, char **argv)
{
    static const gib_command_doc doc = {
        "check-technique", "NAME [--backend B] [--no-gl]",
        "Checks technique NAME (a built-in one or one a plugin adds) as tests/techniques/ check\n"
        "every technique: its descriptor (parameters, choices, rules, presets, passes, reference\n"
        "bindings), then the contract at run time: create, two frames and destroy at 32x24 and\n"
        "48x40 on the first of furnace, plane_box_sky and ring it runs on, with no GL error, finite\n"
        "output, only declared passes, a known status, counters that parse and an empty ledger\n"
        "after destroy. Prints PASS/FAIL lines; exits 1 when a check fails (or no scene suits it).\n"};
    int backend = GIB_BACKEND_AUTO, no_gl = 0;
    const gib_option opts[] = {
        GIB_OPTION_BACKEND("--backend", &backend),
        GIB_OPTION_FLAG("--no-gl", &no_gl, "the descriptor checks only (no GL context)"),
        {0},
    };
    const char *name = NULL;
    int npos = 0;
    int rc = gib_options_parse(&doc, opts, argc, argv, &name, &npos, 1);
    if (rc != GIB_OPTIONS_PROCEED)
        return rc;
    if (npos != 1) {
        fprintf(stderr, "gibench check-technique: name one technique\n");
        gib_options_usage(stderr, &doc, opts);
        return 2;
    }
    const gib_technique *t = gib_technique_find(name);
    if (!t) {
        fprintf(stderr, "gibench check-technique: no technique '%s' (gibench list; a plugin's "
                "needs --plugin PATH or $GIBENCH_PLUGINS)\n", name);
        return 2;
    }
    const char *origin = gib_technique_origin(t);
    printf("technique %s (%s)\n", t->name, origin ? origin : "built-in");
    int failures = gib_check_descriptor(t, stdout, 1);
    if (!no_gl) {
        gib_error err;
        gib_gl_info info;
        if (gib_gl_init(backend, &info, &err) < 0) {
            printf("FAIL %s contract at run time: %s\n", t->name, err.msg);
            return 1;
        }
        printf("renderer: %s | %s | %s\n", info.backend, info.renderer, info.version);
        gib_check_scenes scenes = {0};
        int f = gib_check_runtime(t, &scenes, stdout, 1);
        if (f < 0)
            printf("FAIL %s contract at run time: no check scene it runs on\n", t->name);
        failures += f < 0 ? 1 : f;
        gib_check_scenes_free(&scenes);
        gib_gl_shutdown();
    }
    printf("%s %s: %d failed check%s\n", failures ? "FAIL" : "PASS", t->name, failures,
           failures == 1 ? "" : "s");
    return failures ? 1 : 0;
}
