/* vct's memory plan (techniques/vct/vct.h) and its out-of-memory status.
 *  - The plan's formula: RGBA16F radiance and normal at res^3, 6 RGBA16F anisotropic textures of
 *    (res/2)^3 with full chains. 256^3: 383,479,216 bytes (the "383 MB"); 512^3:
 *    3,067,833,776 bytes (the paper's "3 GB"), planned only, never allocated here. The default
 *    front_faces adds 3 RGBA16F textures alike (the emission lobes, half the anisotropic ones):
 *    441,001,096 and 3,528,008,840 bytes. The shared occlusion voxels the occupancy comes from add
 *    gib_voxels_bytes + their work list.
 *  - After a run at voxel_res 64 the ledger's counted bytes per structure equal the plan exactly.
 *  - A budget below the plan (memory_budget_mb 1 at 64^3, 1000 at 512^3): the runner's row has
 *    status out_of_memory (from the error's code), nothing was allocated, and the plan by
 *    structure (the row's mem_planned_by_structure, which Table 2 reads) equals the formula's. */
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness/app/runner.h"
#include "techniques/vct/vct.h"
#include "tests/common/gl_fixture.h"
#include "tests/common/check.h"

static int failures;
static char check_msg[512]; /* what a CHECK_TRUE line says */

/* Sum of the ledger summary's entries whose label starts with `prefix`. */
static uint64_t label_bytes(const char *summary, const char *prefix)
{
    uint64_t sum = 0;
    const char *s = summary;
    while (s && *s) {
        const char *eq = strchr(s, '=');
        if (!eq)
            break;
        if (!strncmp(s, prefix, strlen(prefix)))
            sum += strtoull(eq + 1, NULL, 10);
        s = strchr(eq, ';');
        s = s ? s + 1 : NULL;
    }
    return sum;
}

static int run(gib_gl_fixture *fx, const char *res, const char *budget, gib_run_result *r)
{
    const gib_technique *t = gib_technique_find("vct");
    gib_params p;
    gib_error err;
    gib_params_default(t, &p);
    if (gib_param_set(t, &p, "voxel_res", res, &err) < 0 ||
        gib_param_set(t, &p, "inject_res", "32", &err) < 0 ||
        gib_param_set(t, &p, "memory_budget_mb", budget, &err) < 0) {
        CHECK(0, "%s", err.msg);
        return -1;
    }
    gib_run_technique(&fx->gpu, t, &p, 0, 16, 16, 0, 1, r);
    return 0;
}

int main(void)
{
    vct_plan p256, p512, p64, l256, l512;
    gib_gl_fixture fx;
    if (gib_fixture_open(&fx, "cornell") < 0)
        return 1;
    const long long tris = (long long)fx.scene.triangle_count;
    vct_plan_bytes(256, -1, false, &p256);
    vct_plan_bytes(512, -1, false, &p512);
    vct_plan_bytes(256, -1, true, &l256);
    vct_plan_bytes(512, -1, true, &l512);
    vct_plan_bytes(64, tris, true, &p64);
    printf("plan 256^3: %" PRIu64 " bytes (%.1f MB), 512^3: %" PRIu64 " bytes (%.2f GB)\n",
           p256.total, p256.total / 1e6, p512.total, p512.total / 1e9);
    printf("with the emission lobes (front_faces): %" PRIu64 " and %" PRIu64 " bytes\n",
           l256.total, l512.total);
    if (p256.total != 383479216ull || p512.total != 3067833776ull ||
        l256.total != 441001096ull || l512.total != 3528008840ull) {
        CHECK(0, "the plan's formula (expected 383479216 and 3067833776 bytes, with the lobes "
              "441001096 and 3528008840)");
        failures++;
    }

    gib_run_result r;
    if (run(&fx, "64", "0", &r) < 0)
        return 1;
    uint64_t rad = label_bytes(r.memory_by_label, "radiance."),
             nrm = label_bytes(r.memory_by_label, "normal."),
             ani = label_bytes(r.memory_by_label, "aniso."),
             lob = label_bytes(r.memory_by_label, "lobes"),
             vox = label_bytes(r.memory_by_label, "voxels.") +
                   label_bytes(r.memory_by_label, "voxels_work.");
    printf("run at 64^3: status %s; ledger radiance %" PRIu64 ", normal %" PRIu64 ", aniso %" PRIu64
           ", voxels %" PRIu64 "; plan %" PRIu64 ", %" PRIu64 ", %" PRIu64 ", %" PRIu64 "\n",
           r.status, rad, nrm, ani, vox, p64.radiance, p64.normal, p64.aniso, p64.voxels);
    if (!r.ok || rad != p64.radiance || nrm != p64.normal || ani != p64.aniso ||
        lob != p64.lobes || vox != p64.voxels) {
        CHECK(0, "the ledger's bytes differ from the plan (or the run failed: %s)", r.err.msg);
        failures++;
    }
    gib_run_result_free(&r);

    const char *cases[2][2] = {{"64", "1"}, {"512", "1000"}};
    for (int i = 0; i < 2; i++) {
        if (run(&fx, cases[i][0], cases[i][1], &r) < 0)
            return 1;
        vct_plan pl;
        vct_plan_bytes(atoi(cases[i][0]), tris, true, &pl);
        char planned[32];
        snprintf(planned, sizeof planned, "%" PRIu64, pl.total);
        char structures[256];
        snprintf(structures, sizeof structures,
                 "radiance=%" PRIu64 ";normal=%" PRIu64 ";aniso=%" PRIu64 ";lobes=%" PRIu64
                 ";voxels=%" PRIu64,
                 pl.radiance, pl.normal, pl.aniso, pl.lobes, pl.voxels);
        int good = !strcmp(r.status, "out_of_memory") && r.err.code == GIB_ERR_OUT_OF_MEMORY &&
                   r.technique_bytes == 0 && r.memory_by_label[0] == 0 &&
                   strstr(r.err.msg, planned) && !strcmp(r.planned_structures, structures);
        printf("  planned by structure: '%s' (formula '%s')\n", r.planned_structures, structures);
        snprintf(check_msg, sizeof check_msg,
                 "voxel_res %s, budget %s MB: status %s, %" PRIu64 " bytes allocated: %.200s",
                 cases[i][0], cases[i][1], r.status, r.technique_bytes, r.err.msg);
        CHECK_TRUE(check_msg, good, "");
        gib_run_result_free(&r);
    }
    printf("%s: vct memory plan and out_of_memory\n", failures ? "FAIL" : "PASS");
    gib_fixture_close(&fx);
    return failures != 0;
}
