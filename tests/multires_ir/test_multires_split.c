/* Algorithm 3.1 (multires_ir's region splitting, techniques/multires_ir/multires.h) on a synthetic
 * depth and normal image with known discontinuities, 100 x 70 pixels (not a multiple of the
 * coarsest region's 8, so regions are clipped at the edges), 4 levels, depth threshold 5%, normal
 * threshold 20 degrees, the camera at the origin looking at points (0, 0, depth):
 *  - a depth step between columns 36 and 37 (10 to 15: 50%);
 *  - a normal step between rows 20 and 21 (30 degrees about x);
 *  - steps that must NOT split: a depth ramp (+0.1% a row: 0.8% over a coarsest region, but
 *    0.08 in depth, so a threshold read as absolute would split it) and a normal step of 10 degrees between
 *    rows 44 and 45;
 *  - no surface in pixels [50, 59) x [9, 17).
 * Both markings (multires.h: the thesis' stencil, and the mask image) are checked.
 * Expected, computed here from those facts alone: a region is discontinuous when it spans 36|37 or
 * 20|21 or holds pixels with and without a surface; valid when it holds a surface, is continuous,
 * and is at the coarsest level or its parent is discontinuous. The stencil of the flattened image
 * must equal that map exactly (every texel of every level), every surface pixel must lie in
 * exactly one valid region, and the pixels beside the two steps are valid at level 0 (the split
 * goes down to single pixels exactly there and nowhere else).
 * On the Cornell box's G-buffer (128 x 128): the two markings agree texel for texel, and the
 * gathering pass shades exactly the marked texels in both (a gathering pass that ignored its mask
 * shaded all 24,576 texels of the flattened image and went unnoticed by the images' bounds). */
#include <glad/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "techniques/common/gbuffer.h"
#include "techniques/multires_ir/multires.h"
#include "tests/common/gl_fixture.h"
#include "tests/common/check.h"

static int failures;

#define W 100
#define H 70
#define LEVELS 4

static int background(int x, int y)
{
    return x >= 50 && x < 59 && y >= 9 && y < 17;
}

/* Region [x0, x1) x [y0, y1) (clipped): discontinuous, and whether it holds a surface. */
static int region_disc(int x0, int y0, int x1, int y1, int *has_surface)
{
    x1 = x1 < W ? x1 : W;
    y1 = y1 < H ? y1 : H;
    int bg = 0, fg = 0;
    for (int y = y0; y < y1; y++)
        for (int x = x0; x < x1; x++)
            background(x, y) ? bg++ : fg++;
    *has_surface = fg > 0;
    int spans_depth = x0 <= 36 && x1 >= 38, spans_normal = y0 <= 20 && y1 >= 22;
    return spans_depth || spans_normal || (bg && fg);
}

/* Splits the synthetic image with the marks in the stencil or the mask and checks them. */
static int check(const unsigned tex[2], int use_stencil)
{
    gib_ledger ledger;
    gib_error err;
    gib_ledger_init(&ledger);
    multires m;
    if (multires_create(&m, W, H, LEVELS, 0.05f, 20.0f, use_stencil, 0, &ledger, &err) < 0) {
        CHECK(0, "set-up: %s", err.msg);
        return 0;
    }
    const char *how = use_stencil ? "stencil" : "mask";
    const float eye[3] = {0, 0, 0};
    multires_split(&m, tex[0], tex[1], eye);
    unsigned char *st = malloc((size_t)m.atlas_w * m.atlas_h);
    multires_read_valid(&m, st);
    int ok = 1, mismatches = 0;
    long valid[LEVELS] = {0};
    int *cover = calloc(W * H, sizeof *cover);
    for (int k = 0; k < LEVELS; k++) {
        int r[4], s = 1 << k;
        multires_rect(&m, k, r);
        for (int j = 0; j < r[3]; j++)
            for (int i = 0; i < r[2]; i++) {
                int fg, pfg;
                int disc = region_disc(i * s, j * s, (i + 1) * s, (j + 1) * s, &fg);
                int parent = k == LEVELS - 1 ||
                             region_disc((i >> 1) * 2 * s, (j >> 1) * 2 * s, ((i >> 1) + 1) * 2 * s,
                                         ((j >> 1) + 1) * 2 * s, &pfg);
                int want = fg && !disc && parent;
                int got = st[(size_t)(r[1] + j) * m.atlas_w + r[0] + i] == 1;
                if (want != got && mismatches++ < 10)
                    printf("  level %d region (%d, %d): stencil %d, expected %d\n", k, i, j, got,
                           want);
                valid[k] += got;
                if (got)
                    for (int y = j * s; y < (j + 1) * s && y < H; y++)
                        for (int x = i * s; x < (i + 1) * s && x < W; x++)
                            cover[y * W + x]++;
            }
    }
    printf("%s %s: marks against the expected valid regions: %d mismatches; valid regions per "
           "level (1, 2, 4, 8 px): %ld %ld %ld %ld\n", mismatches ? "FAIL" : "PASS", how, mismatches, valid[0],
           valid[1], valid[2], valid[3]);
    ok &= !mismatches;
    int badcover = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            badcover += cover[y * W + x] != (background(x, y) ? 0 : 1);
    printf("%s %s: every surface pixel in exactly one valid region, no background pixel in any "
           "(%d pixels wrong)\n", badcover ? "FAIL" : "PASS", how, badcover);
    ok &= !badcover;
    /* The single-pixel regions are exactly the pixels of 2x2 blocks that straddle a step or the
     * background's border: here columns 36 and 37, rows 20 and 21 (both steps are at odd/even
     * boundaries inside a block), and the background's edge blocks. */
    int stray = 0;
    int r0[4];
    multires_rect(&m, 0, r0);
    (void)r0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            int single = st[(size_t)y * m.atlas_w + x] == 1;
            int bx = x & ~1, by = y & ~1, near_bg = 0;
            for (int yy = by; yy < by + 2; yy++)
                for (int xx = bx; xx < bx + 2; xx++)
                    near_bg |= yy < H && xx < W && background(xx, yy);
            int want = !background(x, y) && (bx == 36 || by == 20 || near_bg);
            stray += single != want;
        }
    printf("%s %s: single-pixel regions exactly beside the depth and normal steps and the hole "
           "(%d pixels differ), none at the 10-degree step or on the ramp\n",
           stray ? "FAIL" : "PASS", how, stray);
    ok &= !stray;
    free(cover);
    free(st);
    multires_destroy(&m, &ledger);
    return ok;
}

/* The Cornell box's G-buffer (128 x 128) split with each marking: the same marks. */
static int cornell_marks(gib_gl_fixture *fx)
{
    gib_ledger ledger;
    gib_error err;
    gib_timers timers;
    gib_ledger_init(&ledger);
    gib_timers_init(&timers);
    gib_view view;
    gib_view_make(&fx->scene, &fx->scene.cameras[0], 128, 128, 0, &view);
    gib_gbuffer g;
    if (gib_gbuffer_create(&g, 128, 128, &ledger, &err) < 0) {
        CHECK(0, "%s", err.msg);
        return 0;
    }
    gib_gbuffer_render(&g, &fx->gpu, &view, &timers, "gbuffer");
    unsigned char *marks[2] = {NULL, NULL};
    long counts[2][LEVELS], total[2] = {0, 0};
    int w = 0, h = 0;
    for (int mode = 0; mode < 2; mode++) {
        multires m;
        if (multires_create(&m, 128, 128, LEVELS, 0.05f, 20.0f, mode, 1, &ledger, &err) < 0) {
            CHECK(0, "%s", err.msg);
            return 0;
        }
        multires_split(&m, g.position, g.normal, fx->scene.cameras[0].eye);
        w = m.atlas_w;
        h = m.atlas_h;
        marks[mode] = malloc((size_t)w * h);
        multires_read_valid(&m, marks[mode]);
        total[mode] = multires_count_valid(&m, counts[mode]);
        /* The gathering pass must shade exactly the marked texels (alpha 1 where it ran). */
        multires_gather(&m, 0, 0.05f);
        float *irr = malloc(sizeof(float) * 4 * w * h);
        glGetTextureImage(m.irradiance, 0, GL_RGBA, GL_FLOAT, (GLsizei)(sizeof(float) * 4 * w * h), irr);
        long shaded_wrong = 0;
        for (long i = 0; i < (long)w * h; i++)
            shaded_wrong += (irr[4 * i + 3] > 0.5f) != (marks[mode][i] == 1);
        printf("%s %s: the gathering pass ran at %ld texels that are not marked or skipped marked "
               "ones\n", shaded_wrong ? "FAIL" : "PASS", mode ? "stencil" : "mask", shaded_wrong);
        if (shaded_wrong)
            total[mode] = -1;
        free(irr);
        multires_destroy(&m, &ledger);
    }
    long differ = 0;
    for (long i = 0; i < (long)w * h; i++)
        differ += marks[0][i] != marks[1][i];
    printf("%s: Cornell box 128x128: mask and stencil marks differ at %ld texels; valid regions "
           "(1, 2, 4, 8 px): %ld %ld %ld %ld of %d pixels\n", differ ? "FAIL" : "PASS", differ,
           counts[0][0], counts[0][1], counts[0][2], counts[0][3], 128 * 128);
    free(marks[0]);
    free(marks[1]);
    gib_gbuffer_destroy(&g, &ledger);
    gib_timers_destroy(&timers);
    return differ == 0 && total[0] == total[1];
}

int main(void)
{
    gib_gl_fixture fx;
    if (gib_fixture_open(&fx, "cornell") < 0)
        return 1;
    float *pos = malloc(sizeof(float) * 4 * W * H), *nrm = malloc(sizeof(float) * 4 * W * H);
    const double deg = M_PI / 180;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            float *p = pos + 4 * (y * W + x), *n = nrm + 4 * (y * W + x);
            double d = (x < 37 ? 10.0 : 15.0) * (1 + 0.001 * y);
            double a = (y > 20 ? 30 : 0) + (y > 44 ? 10 : 0);
            p[0] = p[1] = 0;
            p[2] = (float)d;
            p[3] = background(x, y) ? 0.0f : 1.0f;
            n[0] = 0;
            n[1] = (float)sin(a * deg);
            n[2] = (float)-cos(a * deg);
            n[3] = 0;
        }
    unsigned tex[2];
    glCreateTextures(GL_TEXTURE_2D, 2, tex);
    for (int i = 0; i < 2; i++) {
        glTextureStorage2D(tex[i], 1, GL_RGBA32F, W, H);
        glTextureSubImage2D(tex[i], 0, 0, 0, W, H, GL_RGBA, GL_FLOAT, i ? nrm : pos);
    }
    for (int mode = 1; mode >= 0; mode--)
        failures += !(check(tex, mode));
    failures += !(cornell_marks(&fx));
    free(pos);
    free(nrm);
    glDeleteTextures(2, tex);
    gib_fixture_close(&fx);
    printf("%s: Algorithm 3.1 on a synthetic image\n", failures ? "FAIL" : "PASS");
    return failures != 0;
}
