/* The LDMs' memory plan (techniques/ldm/ldm.h) and the out-of-memory status of ldm_ao and
 * ldm_indirect (parameter memory_budget_mb).
 *  - The plan's paging (ldm_plan_bytes, no GL): heads 4 res^2 bytes an LDM, 8 bytes a node, one
 *    node for an empty page, an LDM larger than a buffer planned all the same.
 *  - At a small setting (8 directions of 32^2 on the Cornell box, no budget) the row's planned
 *    structure "ldm" equals what the ledger counted for it, byte for byte.
 *  - A budget below the plan (memory_budget_mb 0.01): status out_of_memory from the error's code,
 *    the same plan recorded, nothing left allocated, and the peak no more than the counting pass's
 *    own buffers (info 48 bytes an LDM, counters 4 an LDM, status 16): no page, no G-buffer, no
 *    photon buffer. */
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness/app/runner.h"
#include "techniques/ldm/ldm.h"
#include "tests/common/gl_fixture.h"
#include "tests/common/check.h"

static int failures;
static char check_msg[512]; /* what a CHECK_TRUE line says */

/* The bytes of structure `name` in a "name=bytes;name=bytes" summary, 0 when absent. */
static uint64_t structure_bytes(const char *summary, const char *name)
{
    size_t n = strlen(name);
    for (const char *s = summary; s && *s;) {
        if (!strncmp(s, name, n) && s[n] == '=')
            return strtoull(s + n + 1, NULL, 10);
        s = strchr(s, ';');
        s = s ? s + 1 : NULL;
    }
    return 0;
}

static int check_paging(void)
{
    ldm_set l;
    memset(&l, 0, sizeof l);
    l.count = 3;
    l.res = 4; /* 64 bytes of heads an LDM */
    const uint64_t cap[3] = {10, 20, 30};
    ldm_plan p;
    /* 200-byte buffers: every LDM a page of its own (80, 160 and 240 bytes of nodes, the last
     * over a buffer and planned all the same). */
    ldm_plan_bytes(&l, cap, 200, &p);
    int ok = p.heads == 192 && p.nodes == 480 && p.info == 144 && p.counters == 12 &&
             p.status == 16 && p.total == 192 + 480 + 144 + 12 + 16;
    const uint64_t empty[3] = {0, 0, 0};
    ldm_plan_bytes(&l, empty, 1 << 20, &p); /* one page, no node: one node all the same */
    ok &= p.nodes == 8 && p.heads == 192;
    CHECK_TRUE("the plan's paging (heads, nodes, info, counters, status)", ok, "");
    return ok;
}

static int run(gib_gl_fixture *fx, const char *tech, const char *budget, gib_run_result *r)
{
    const gib_technique *t = gib_technique_find(tech);
    gib_params p;
    gib_error err;
    gib_params_default(t, &p);
    if (gib_param_set(t, &p, "directions", "8", &err) < 0 ||
        gib_param_set(t, &p, "ldm_res", "32", &err) < 0 ||
        gib_param_set(t, &p, "memory_budget_mb", budget, &err) < 0 ||
        (!strcmp(tech, "ldm_indirect") && gib_param_set(t, &p, "photon_res", "8", &err) < 0)) {
        CHECK(0, "%s", err.msg);
        return -1;
    }
    gib_run_technique(&fx->gpu, t, &p, 0, 16, 16, 0, 1, r);
    return 0;
}

/* One technique: the plan against the ledger, then the budget's refusal. */
static int check_technique(gib_gl_fixture *fx, const char *tech)
{
    gib_run_result r;
    if (run(fx, tech, "0", &r) < 0)
        return 0;
    uint64_t planned = structure_bytes(r.planned_structures, "ldm"),
             counted = structure_bytes(r.memory_by_structure, "ldm");
    int ok = r.ok && planned && planned == counted;
    snprintf(check_msg, sizeof check_msg,
             "%s at 8 x 32^2: status %s, planned ldm %" PRIu64 " bytes, the ledger counted %" PRIu64,
             tech, r.status, planned, counted);
    CHECK_TRUE(check_msg, ok, "");
    gib_run_result_free(&r);

    if (run(fx, tech, "0.01", &r) < 0)
        return 0;
    const uint64_t counting = 48 * 8 + 4 * 8 + 16;
    char want[64];
    snprintf(want, sizeof want, "ldm=%" PRIu64, planned);
    int good = !strcmp(r.status, "out_of_memory") && r.err.code == GIB_ERR_OUT_OF_MEMORY &&
               r.memory_by_label[0] == 0 && r.technique_bytes <= counting &&
               !strcmp(r.planned_structures, want);
    snprintf(check_msg, sizeof check_msg,
             "%s, memory_budget_mb 0.01: status %s, plan '%.64s' (want '%s'), peak %" PRIu64
             " bytes (the counting pass's %" PRIu64 "), still allocated '%.64s': %.160s",
             tech, r.status, r.planned_structures, want, r.technique_bytes, counting,
             r.memory_by_label, r.err.msg);
    CHECK_TRUE(check_msg, good, "");
    gib_run_result_free(&r);
    return ok && good;
}

int main(void)
{
    int ok = check_paging();
    gib_gl_fixture fx;
    if (gib_fixture_open(&fx, "cornell") < 0)
        return 1;
    ok &= check_technique(&fx, "ldm_ao");
    ok &= check_technique(&fx, "ldm_indirect");
    snprintf(check_msg, sizeof check_msg,
             "ldm memory plan and out_of_memory");
    CHECK_TRUE(check_msg, ok, "");
    gib_fixture_close(&fx);
    return failures != 0;
}
