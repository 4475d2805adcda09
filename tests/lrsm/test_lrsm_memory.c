/* Table 2's memory, counted by the ledger: `lrsm` created at the paper's settings (Sec. 6: 256^3
 * occlusion voxels, a 1024^2 RSM, LRSM layers at 512^2, D x N = 2 x 2 and 3 x 2) on a scene with
 * one directional light (one light-view face, as SPONZA's sun), and the bytes the ledger holds
 * compared, exactly, with the formulas computed here level by level:
 *   voxels.occupancy R8 (the voxels' work list, 8 B a triangle, is apart): sum over the chain of (256 / 2^k)^3 x 1 B                  = 19,173,961 B
 *   rsm     two RGBA16F with mips (rsm.radiance_depth, rsm.normal_nl; the paper's packed RSM):
 *           sum of (1024 / 2^k)^2 x 16 B                                    = 22,369,616 B
 *   layers  RGBA16F + RGBA16F + RGBA16: sum of (512 / 2^k)^2 x 24 B x layers = 33,554,400 B (4)
 *                                                                           = 50,331,600 B (6)
 * and the 512^3 voxels of SPONZA through the plan only (153,391,689 B; not allocated on llvmpipe).
 * The paper's figures: 19.2, 156.4 (3.0 MB over its own formats), 22.4, 33.6 and 50.4 MB. */
#include <stdio.h>
#include <string.h>

#include "techniques/common/voxels.h"
#include "techniques/lrsm/lrsm.h"
#include "tests/common/gl_fixture.h"
#include "tests/common/check.h"

static uint64_t structure_bytes(const gib_ledger *l, const char *structure)
{
    uint64_t sum = 0;
    size_t n = strlen(structure);
    for (int i = 0; i < l->count; i++)
        if (!strncmp(l->entries[i].label, structure, n) && l->entries[i].label[n] == '.')
            sum += l->entries[i].bytes;
    return sum;
}

static uint64_t label_bytes(const gib_ledger *l, const char *label)
{
    uint64_t sum = 0;
    for (int i = 0; i < l->count; i++)
        if (!strcmp(l->entries[i].label, label))
            sum += l->entries[i].bytes;
    return sum;
}

static uint64_t voxel_formula(int res)
{
    uint64_t b = 0;
    for (int s = res; s >= 1; s /= 2)
        b += (uint64_t)s * s * s;
    return b;
}

static uint64_t rsm_formula(int side)
{
    uint64_t b = 0;
    for (int s = side; s >= 1; s /= 2)
        b += (uint64_t)s * s * 16;
    return b;
}

static uint64_t layer_formula(int side, int layers)
{
    uint64_t b = 0;
    for (int s = side; s >= 1; s /= 2)
        b += (uint64_t)s * s * 24 * (uint64_t)layers;
    return b;
}

static int failures;
static char check_msg[512]; /* what a CHECK_TRUE line says */

static void expect(const char *what, uint64_t got, uint64_t want)
{
    int ok = got == want;
    snprintf(check_msg, sizeof check_msg,
             "%s: %llu B (%.2f MB), formula %llu B",
             what, (unsigned long long)got, got / 1e6, (unsigned long long)want);
    CHECK_TRUE(check_msg, ok, "");
}

int main(void)
{
    gib_gl_fixture fx;
    if (gib_fixture_open(&fx, "water") < 0)
        return 1;
    const gib_technique *t = gib_technique_find("lrsm");
    if (!t) {
        CHECK(0, "no technique lrsm");
        return 1;
    }
    static const int normal_parts[2] = {2, 2}, depth_parts[2] = {2, 3};
    for (int c = 0; c < 2; c++) {
        gib_params p;
        gib_error err;
        gib_params_default(t, &p);
        char dp[8];
        snprintf(dp, sizeof dp, "%d", depth_parts[c]);
        if (gib_param_set(t, &p, "voxel_res", "256", &err) < 0 ||
            gib_param_set(t, &p, "rsm_res", "1024", &err) < 0 ||
            gib_param_set(t, &p, "layers_depth", dp, &err) < 0) {
            CHECK(0, "%s", err.msg);
            return 1;
        }
        gib_ledger ledger;
        gib_ledger_init(&ledger);
        void *self = t->create(&fx.gpu, &p, 32, 32, &ledger, &err);
        if (!self) {
            CHECK(0, "create: %s", err.msg);
            return 1;
        }
        int layers = depth_parts[c] * normal_parts[c];
        char what[64];
        if (c == 0) {
            expect("voxels.occupancy 256^3", label_bytes(&ledger, "voxels.occupancy"),
                   voxel_formula(256));
            expect("gib_voxels_bytes(256) (the plan)", gib_voxels_bytes(256), voxel_formula(256));
            expect("rsm 1024^2 (radiance_depth + normal_nl)",
                   label_bytes(&ledger, "rsm.radiance_depth") + label_bytes(&ledger, "rsm.normal_nl"),
                   rsm_formula(1024));
        }
        snprintf(what, sizeof what, "layers 512^2 x %d", layers);
        expect(what, structure_bytes(&ledger, "layers"), layer_formula(512, layers));
        snprintf(what, sizeof what, "lrsm_layers_bytes(1024, %d, 1)", layers);
        expect(what, lrsm_layers_bytes(1024, layers, 1), layer_formula(512, layers));
        t->destroy(self);
        gib_ledger_release_all(&ledger);
    }
    expect("gib_voxels_bytes(512) (the plan)", gib_voxels_bytes(512), voxel_formula(512));
    gib_fixture_close(&fx);
    printf("%s: lrsm memory at Table 2's settings\n", failures ? "FAIL" : "PASS");
    return failures ? 1 : 0;
}
