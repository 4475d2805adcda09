/* The technique contract (techniques/technique.h) at run time, over every technique: the registry
 * walked and the test-only template (tests/techniques/every_technique.h), so a technique is
 * checked the day it is registered. The checks are gib_check_runtime's (harness/app/
 * technique_check.c, which `gibench check-technique` runs too). test_registry checks the
 * descriptors without GL; this drives
 * create / render / status / counters / destroy as the runner does, but with a ledger of its own,
 * which the runner would empty behind a technique's back.
 *
 * Each technique runs on the first of SCENES it accepts (its scene_needs; none: skipped, the
 * reason printed), at two sizes (a technique sized at create must not keep the first size's
 * objects), two frames each (the second finds the first's state), default parameters. Per size:
 *  - create returns a state, render returns 0 both frames, and no GL error is left;
 *  - at least one timed pass, none left open after render;
 *  - every output value finite (no NaN, no Inf);
 *  - every timed pass one of the descriptor's `passes` (the names the report's tables read);
 *  - status one of harness/base/status.h's (the words the CSV's status column can hold);
 *  - counters "" or name=value pairs joined by ';' (name [a-z0-9_]+, value a number);
 *  - after destroy the ledger empty: no object, no byte (what destroy forgot would be freed by
 *    the runner and never show up), and no GL error.
 * Runtime on llvmpipe (2 shared cores): 31-35 s in the release build, 33-43 s under ASan, two
 * thirds of it ldm_ao's and ldm_indirect's LDMs. */
#include <glad/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness/app/technique_check.h"
#include "harness/gl/context.h"
#include "tests/techniques/every_technique.h"

static int failures;
#include "tests/common/check.h"

/* The parser on what it must take and refuse, so a pass means the counters were read. */
static void check_parser(void)
{
    static const char *const good[] = {"", "photons=6954", "a=1;b_2=0.5", "n=-3;m=1e6"};
    static const char *const bad[] = {"photons", "=3", "a=1;", "a=x", "a=1 b=2", "A=1", "a=1;;b=2"};
    for (size_t i = 0; i < sizeof good / sizeof good[0]; i++)
        CHECK(gib_counters_parse(good[i]), "counters parser refuses '%s'", good[i]);
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++)
        CHECK(!gib_counters_parse(bad[i]), "counters parser takes '%s'", bad[i]);
}

int main(void)
{
    check_parser();
    gib_error err;
    gib_gl_info info;
    if (gib_gl_init(GIB_BACKEND_AUTO, &info, &err) < 0) {
        CHECK(0, "set-up: %s", err.msg);
        return 1;
    }
    gib_check_scenes scenes = {0};
    const gib_technique *all[EVERY_TECHNIQUE_MAX];
    int n = every_technique(all, EVERY_TECHNIQUE_MAX);
    CHECK(n <= EVERY_TECHNIQUE_MAX, "%d techniques, the test holds %d", n, EVERY_TECHNIQUE_MAX);
    for (int i = 0; i < n && i < EVERY_TECHNIQUE_MAX; i++) {
        int f = gib_check_runtime(all[i], &scenes, stdout, 0); /* -1: skipped, the reason printed */
        failures += f > 0 ? f : 0;
    }
    gib_check_scenes_free(&scenes);
    gib_gl_shutdown();
    printf("%s: the technique contract at run time (%s)\n", failures ? "FAIL" : "PASS",
           info.renderer);
    return failures ? 1 : 0;
}
