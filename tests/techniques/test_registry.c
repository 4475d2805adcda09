/* Every technique's descriptor against the contract of techniques/technique.h: parameter specs
 * that the CLI and matrices can rely on, reference bindings that name real parameters, passes,
 * presets and constraints (gib_check_descriptor, harness/app/technique_check.c, which `gibench
 * check-technique` runs too), and
 * gib_param_int/float stopping the process on an undeclared name in every build (this test is
 * compiled with NDEBUG in the release build, where the old assert did nothing). The test-only
 * techniques (the template) are held to the same rules, and stay out of what gibench runs: not
 * in gib_techniques(), not found by name. Presets set what they say and are named back. Choices,
 * multiples and rules between parameters are refused before any GL. No GL needed. */
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "harness/app/technique_check.h"
#include "techniques/technique.h"
#include "tests/techniques/every_technique.h"

static int failures;
#include "tests/common/check.h"

/* Runs f in a child and reports whether it died of SIGABRT with the expected message. */
static int aborts_naming(const gib_technique *t, int as_float, const char *name)
{
    int fds[2];
    if (pipe(fds) < 0)
        return 0;
    pid_t pid = fork();
    if (pid == 0) {
        dup2(fds[1], 2);
        gib_params p;
        gib_params_default(t, &p);
        volatile double v = as_float ? gib_param_float(t, &p, name) : gib_param_int(t, &p, name);
        (void)v;
        _exit(0);
    }
    close(fds[1]);
    char msg[512] = "";
    ssize_t got = read(fds[0], msg, sizeof msg - 1);
    msg[got > 0 ? got : 0] = 0;
    close(fds[0]);
    int status = 0;
    waitpid(pid, &status, 0);
    return WIFSIGNALED(status) && WTERMSIG(status) == SIGABRT && strstr(msg, t->name) &&
           strstr(msg, name);
}

/* A test-only technique is checked like the others but gibench never sees it. */
static void check_test_only(void)
{
    int count = 0, n = 0;
    const gib_technique *const *tests = gib_techniques_test_only(&count);
    const gib_technique *const *run = gib_techniques(&n);
    CHECK(count > 0, "no test-only technique (the template)");
    for (int i = 0; i < count; i++) {
        CHECK(!gib_technique_find(tests[i]->name), "test-only '%s' is found by name",
              tests[i]->name);
        for (int k = 0; k < n; k++)
            CHECK(run[k] != tests[i] && strcmp(run[k]->name, tests[i]->name),
                  "test-only '%s' is among the techniques gibench runs", tests[i]->name);
    }
}

/* The three kinds of constraint, each refused with no GL and no scene, the error naming the
 * parameter(s), the value(s) and what they break: a value outside an enumeration, an integer no
 * multiple of its step, a combination a rule forbids. */
static void refused(const char *tech, const char *const *kv, const char *want1, const char *want2)
{
    const gib_technique *t = gib_technique_find(tech);
    CHECK_TRUE("technique registered", t != NULL, tech);
    if (!t)
        return;
    gib_params p;
    gib_error err = {0};
    gib_params_default(t, &p);
    int rc = 0;
    for (int i = 0; kv[i] && rc == 0; i += 2)
        rc = gib_param_set(t, &p, kv[i], kv[i + 1], &err);
    if (rc == 0)
        rc = gib_params_check(t, &p, &err);
    char what[96];
    snprintf(what, sizeof what, "%s %s=%s refused", tech, kv[0], kv[1]);
    CHECK_TRUE(what, rc < 0 && strstr(err.msg, want1) && strstr(err.msg, want2), err.msg);
}

static void check_refusals(void)
{
    refused("ispm_caustics", (const char *const[]){"layers", "2", NULL}, "'layers' = 2",
            "lists = 0, peeled = 4");
    refused("lrsm", (const char *const[]){"hits", "rays", NULL}, "'hits'", "algorithm1 = 0");
    refused("lrsm", (const char *const[]){"rsm_res", "513", NULL}, "'rsm_res' = 513",
            "multiple of 2");
    refused("lrsm", (const char *const[]){"hits", "planes", "backface", "cosine", NULL},
            "backface = 0 (cosine)", "act only with hits = algorithm1");
    refused("lrsm", (const char *const[]){"coverage", "0", NULL}, "coverage = 0",
            "act only with hits = algorithm1");
    refused("ispm_caustics", (const char *const[]){"rsm_res", "16", "mask_level", "5", NULL},
            "mask_level = 5", "rsm_res >> mask_level >= 1");
    refused("ldm_ao", (const char *const[]){"obscurance", "1", NULL}, "dmax = inf",
            "finite dmax > 0");
    /* the same values the rule forbids with hits = planes are fine with hits = algorithm1 */
    const gib_technique *t = gib_technique_find("lrsm");
    gib_params p;
    gib_error err = {0};
    gib_params_default(t, &p);
    CHECK_TRUE("lrsm hits=algorithm1 backface=cosine accepted",
               gib_param_set(t, &p, "hits", "algorithm1", &err) == 0 &&
                   gib_param_set(t, &p, "backface", "cosine", &err) == 0 &&
                   gib_params_check(t, &p, &err) == 0 && p.values[gib_param_index(t, "hits")] == 0,
               err.msg);
}

int main(void)
{
    const gib_technique *all[EVERY_TECHNIQUE_MAX];
    int count = every_technique(all, EVERY_TECHNIQUE_MAX), run = 0;
    gib_techniques(&run);
    CHECK(run > 0, "empty registry");
    CHECK(count <= EVERY_TECHNIQUE_MAX, "%d techniques, the test holds %d", count,
          EVERY_TECHNIQUE_MAX);
    for (int i = 0; i < count && i < EVERY_TECHNIQUE_MAX; i++) {
        const gib_technique *t = all[i];
        /* the descriptor's own checks, shared with `gibench check-technique` */
        failures += gib_check_descriptor(t, stdout, 0);
        if (!t->name)
            continue;
        if (i < run)
            CHECK(gib_technique_find(t->name) == t, "%s: not found by its name", t->name);
        for (int k = 0; k < i; k++)
            CHECK(strcmp(all[k]->name, t->name), "technique '%s' registered twice", t->name);
    }
    check_test_only();
    check_refusals();
    /* An undeclared name stops the process (the release build has NDEBUG: no assert). */
    const gib_technique *t = all[0];
    CHECK(aborts_naming(t, 0, "no_such_parameter"), "gib_param_int on an unknown name went on");
    CHECK(aborts_naming(t, 1, "no_such_parameter"), "gib_param_float on an unknown name went on");
    if (t->params && t->params[0].name)
        CHECK(!aborts_naming(t, 1, t->params[0].name), "a declared name stopped the process");
    printf("%d techniques checked (%d test-only): %s\n", count, count - run,
           failures ? "FAILED" : "ok");
    return failures ? 1 : 0;
}
