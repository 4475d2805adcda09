/* gibench — LDR-FLIP and HDR-FLIP (see flip.h). Equation numbers refer to the FLIP paper (HPG 2020);
 * constants and the separable form of its filters follow the reference implementation, whose means
 * the unit test compares against. The work is spread over the scoring threads (parallel.h), which
 * run after a technique's frames, never beside them. */
#include "flip.h"

#include <math.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "harness/imaging/image.h"

#define FLIP_PI 3.14159265358979f

/* Paper Sec. 4 (colour pipeline) and Sec. 5 (feature pipeline) constants. */
static const float qc = 0.7f, pc = 0.4f, pt = 0.95f, gw = 0.082f, qf = 0.5f;
/* Contrast sensitivity functions, Eq. 2-3: a1, b1 per channel (Y, Cx, Cz) plus the Cz channel's
 * second Gaussian a2, b2 (degrees^2). */
static const float a1[3] = {1.0f, 1.0f, 34.1f}, b1[3] = {0.0047f, 0.0053f, 0.04f};
static const float a2z = 13.5f, b2z = 0.025f;
/* D65 white point used to normalise XYZ before YCxCz / L*a*b*. */
static const float white[3] = {0.950428545f, 1.0f, 1.088900371f};

float gib_flip_default_ppd(void)
{
    return 0.7f * (3840.0f / 0.7f) * (FLIP_PI / 180.0f);
}

static void rgb_to_xyz(const float c[3], float o[3])
{
    o[0] = (10135552.0f * c[0] + 8788810.0f * c[1] + 4435075.0f * c[2]) / 24577794.0f;
    o[1] = (2613072.0f * c[0] + 8788810.0f * c[1] + 887015.0f * c[2]) / 12288897.0f;
    o[2] = (1425312.0f * c[0] + 8788810.0f * c[1] + 70074185.0f * c[2]) / 73733382.0f;
}

static void xyz_to_rgb(const float x[3], float o[3])
{
    o[0] = 3.241003275f * x[0] - 1.537398934f * x[1] - 0.498615861f * x[2];
    o[1] = -0.969224334f * x[0] + 1.875930071f * x[1] + 0.041554224f * x[2];
    o[2] = 0.055639423f * x[0] - 0.204011202f * x[1] + 1.057148933f * x[2];
}

/* Linear RGB -> YCxCz (opponent space of Sec. 4.1; linear in XYZ, no cube root). */
static void rgb_to_ycxcz(const float c[3], float o[3])
{
    float x[3];
    rgb_to_xyz(c, x);
    float X = x[0] / white[0], Y = x[1] / white[1], Z = x[2] / white[2];
    o[0] = 116.0f * Y - 16.0f;
    o[1] = 500.0f * (X - Y);
    o[2] = 200.0f * (Y - Z);
}

/* Filtered YCxCz -> linear RGB clamped to [0,1] -> L*a*b* with the Hunt adjustment (Sec. 4.2). */
static void ycxcz_to_lab_hunt(const float v[3], float o[3])
{
    float Y = (v[0] + 16.0f) / 116.0f;
    float xyz[3] = {(Y + v[1] / 500.0f) * white[0], Y * white[1], (Y - v[2] / 200.0f) * white[2]};
    float rgb[3];
    xyz_to_rgb(xyz, rgb);
    for (int k = 0; k < 3; k++)
        rgb[k] = rgb[k] < 0.0f ? 0.0f : rgb[k] > 1.0f ? 1.0f : rgb[k];
    rgb_to_xyz(rgb, xyz);
    const float d = 6.0f / 29.0f, d3 = d * d * d, f = 1.0f / (3.0f * d * d), t = 4.0f / 29.0f;
    float q[3];
    for (int k = 0; k < 3; k++) {
        float s = xyz[k] / white[k];
        q[k] = s > d3 ? cbrtf(s) : f * s + t;
    }
    float L = 116.0f * q[1] - 16.0f;
    o[0] = L;
    o[1] = 0.01f * L * 500.0f * (q[0] - q[1]);
    o[2] = 0.01f * L * 200.0f * (q[1] - q[2]);
}

/* HyAB distance (Eq. 4): |dL| + Euclidean distance in the (Hunt-adjusted) a*b* plane. */
static float hyab(const float a[3], const float b[3])
{
    float da = a[1] - b[1], db = a[2] - b[2];
    return fabsf(a[0] - b[0]) + sqrtf(da * da + db * db);
}

/* Largest colour difference: between pure green and pure blue (Sec. 4.2), raised to qc. */
static float cmax_value(void)
{
    float g[3] = {0, 1, 0}, b[3] = {0, 0, 1}, yg[3], yb[3], lg[3], lb[3];
    rgb_to_ycxcz(g, yg);
    rgb_to_ycxcz(b, yb);
    ycxcz_to_lab_hunt(yg, lg);
    ycxcz_to_lab_hunt(yb, lb);
    return powf(hyab(lg, lb), qc);
}

/* The CSF filters of Eq. 2-3 sampled at 1/ppd degrees, made separable (separatedConvolutions.pdf):
 * Y and Cx are single Gaussians, normalised to sum 1 per axis; Cz is a sum of two Gaussians, kept
 * as two 1D filters with sqrt weights whose outer products sum to the 2D filter normalised to 1. */
typedef struct csf_filters {
    int radius;
    float *y, *cx, *cz1, *cz2;
} csf_filters;

static float gauss_alt(float x2, float a, float b)
{
    return a * sqrtf(FLIP_PI / b) * expf(-FLIP_PI * FLIP_PI * x2 / b);
}

static int csf_make(csf_filters *f, float ppd)
{
    float bmax = fmaxf(fmaxf(b1[0], b1[1]), fmaxf(b1[2], b2z));
    f->radius = (int)ceilf(3.0f * sqrtf(bmax / (2.0f * FLIP_PI * FLIP_PI)) * ppd);
    int n = 2 * f->radius + 1;
    f->y = malloc(4 * (size_t)n * sizeof(float));
    if (!f->y)
        return -1;
    f->cx = f->y + n;
    f->cz1 = f->cx + n;
    f->cz2 = f->cz1 + n;
    float sy = 0, sx = 0, s1 = 0, s2 = 0;
    for (int i = 0; i < n; i++) {
        float x = (float)(i - f->radius) / ppd, x2 = x * x;
        f->y[i] = gauss_alt(x2, a1[0], b1[0]);
        f->cx[i] = gauss_alt(x2, a1[1], b1[1]);
        f->cz1[i] = sqrtf(a1[2] * sqrtf(FLIP_PI / b1[2])) * expf(-FLIP_PI * FLIP_PI * x2 / b1[2]);
        f->cz2[i] = sqrtf(a2z * sqrtf(FLIP_PI / b2z)) * expf(-FLIP_PI * FLIP_PI * x2 / b2z);
        sy += f->y[i];
        sx += f->cx[i];
        s1 += f->cz1[i];
        s2 += f->cz2[i];
    }
    float nz = 1.0f / sqrtf(s1 * s1 + s2 * s2);
    for (int i = 0; i < n; i++) {
        f->y[i] /= sy;
        f->cx[i] /= sx;
        f->cz1[i] *= nz;
        f->cz2[i] *= nz;
    }
    return 0;
}

/* Feature filters (Sec. 5.1): Gaussian of sigma = 0.5 gw ppd pixels and its first and second
 * derivatives; the Gaussian sums to 1, each derivative's positive and negative weights to +-1. */
typedef struct feat_filters {
    int radius;
    float *g, *dg, *ddg;
} feat_filters;

static int feat_make(feat_filters *f, float ppd)
{
    float sd = 0.5f * gw * ppd;
    f->radius = (int)ceilf(3.0f * sd);
    int n = 2 * f->radius + 1;
    f->g = malloc(3 * (size_t)n * sizeof(float));
    if (!f->g)
        return -1;
    f->dg = f->g + n;
    f->ddg = f->dg + n;
    float gs = 0, dp = 0, dn = 0, ddp = 0, ddn = 0;
    for (int i = 0; i < n; i++) {
        float x = (float)(i - f->radius);
        float g = expf(-(x * x) / (2.0f * sd * sd));
        float dg = -x * g, ddg = (x * x / (sd * sd) - 1.0f) * g;
        f->g[i] = g;
        f->dg[i] = dg;
        f->ddg[i] = ddg;
        gs += g;
        if (dg > 0) dp += dg; else dn -= dg;
        if (ddg > 0) ddp += ddg; else ddn -= ddg;
    }
    for (int i = 0; i < n; i++) {
        f->g[i] /= gs;
        f->dg[i] /= f->dg[i] > 0 ? dp : dn;
        f->ddg[i] /= f->ddg[i] > 0 ? ddp : ddn;
    }
    return 0;
}

static inline int clampi(int v, int lo, int hi)
{
    return v < lo ? lo : v > hi ? hi : v;
}

/* out[x] = sum_i f[i] * in[x + i - r] for one row, edges clamped: the row is copied into pad with
 * r clamped samples on each side, then accumulated tap by tap so the inner loop vectorises. */
static void row_filter(const float *in, int w, const float *f, int r, float *pad, float *out)
{
    for (int x = 0; x < r; x++) {
        pad[x] = in[0];
        pad[r + w + x] = in[w - 1];
    }
    memcpy(pad + r, in, (size_t)w * sizeof(float));
    memset(out, 0, (size_t)w * sizeof(float));
    for (int i = 0; i <= 2 * r; i++) {
        const float fi = f[i], *p = pad + i;
        for (int x = 0; x < w; x++)
            out[x] += fi * p[x];
    }
}

/* Column pass: out row y = sum_i f[i] * row (y + i - r) of the plane, edges clamped. */
static void col_filter(const float *plane, int w, int h, int y, const float *f, int r, float *out)
{
    memset(out, 0, (size_t)w * sizeof(float));
    for (int i = 0; i <= 2 * r; i++) {
        const float fi = f[i], *p = plane + (size_t)clampi(y + i - r, 0, h - 1) * w;
        for (int x = 0; x < w; x++)
            out[x] += fi * p[x];
    }
}

/* ---- one evaluation: a pair of images mapped to [0,1], filtered and compared ----
 *
 * Two steps over bands of rows, each band an item for the scoring threads (parallel.h): the rows'
 * colour conversion and horizontal filters (per image and band), then the vertical filters and the
 * per-pixel error (per band, both images). Every pixel's value comes from the same operations in
 * the same order whatever the thread that computes it, and the mean is summed in pixel order
 * afterwards, so the results do not depend on the thread count. */

#define FLIP_BAND 8
#define FLIP_PLANES 7 /* per image: CSF Y, Cx, Cz (first filter), Cz (second); features dG, ddG, G */

/* An image's linear RGB: `stride` floats per pixel, R, G, B first. */
typedef struct flip_src {
    const float *px;
    int stride;
} flip_src;

/* ACES filmic curve fit (Narkowicz) as HDR-FLIP uses it, with its 0.6 pre-exposure folded into
 * the coefficients: (c0 x^2 + c1 x + c2) / (c3 x^2 + c4 x + c5). */
static const float aces[6] = {0.6f * 0.6f * 2.51f, 0.6f * 0.03f, 0.0f,
                              0.6f * 0.6f * 2.43f, 0.6f * 0.59f, 0.14f};

static float tonemap(float x)
{
    float v = (x * x * aces[0] + x * aces[1] + aces[2]) / (x * x * aces[3] + x * aces[4] + aces[5]);
    return fminf(fmaxf(v, 0.0f), 1.0f);
}

typedef struct flip_eval {
    flip_src img[2]; /* reference, test */
    int w, h, rmax;
    int hdr;     /* 0: LDR, samples clamp(scale * v, 0, 1); 1: tonemap(v * scale) */
    float scale; /* LDR: the exposure; HDR: this exposure's multiplier */
    csf_filters cf;
    feat_filters ff;
    float cmax;
    float *planes; /* 2 images x FLIP_PLANES planes of w*h */
    float *out;    /* per-pixel error (LDR), or its running maximum over exposures (HDR) */
    atomic_int failed; /* an item's scratch could not be allocated */
} flip_eval;

/* Linear RGB of pixel i of image k, mapped to [0,1] as the evaluation says. */
static void load_rgb(const flip_eval *e, int k, size_t i, float rgb[3])
{
    const float *p = e->img[k].px + i * (size_t)e->img[k].stride;
    for (int c = 0; c < 3; c++)
        rgb[c] = e->hdr ? tonemap(p[c] * e->scale) : fminf(fmaxf(e->scale * p[c], 0.0f), 1.0f);
}

/* Item: one band of one image's rows to YCxCz (Sec. 4.1), through the CSF's horizontal filters
 * (Eq. 2-3: Y, Cx, and Cz with each of its two) and, on the achromatic channel normalised to
 * [0,1], (Y + 16) / 116, the features' (Sec. 5.1: d/dx, d2/dx2, Gaussian). */
static void rows_horizontal(void *ctx, int item)
{
    flip_eval *e = ctx;
    const int w = e->w, k = item & 1, y0 = (item >> 1) * FLIP_BAND;
    const int y1 = y0 + FLIP_BAND < e->h ? y0 + FLIP_BAND : e->h;
    const size_t n = (size_t)w * e->h;
    float *pad = malloc(((size_t)w + 2 * (size_t)e->rmax + 4 * (size_t)w) * sizeof(float));
    if (!pad) {
        atomic_store(&e->failed, 1);
        return;
    }
    float *Y = pad + w + 2 * e->rmax, *Cx = Y + w, *Cz = Cx + w, *yn = Cz + w;
    float *P = e->planes + (size_t)k * FLIP_PLANES * n;
    const int rc = e->cf.radius, rf = e->ff.radius;
    for (int y = y0; y < y1; y++) {
        size_t o = (size_t)y * w;
        for (int x = 0; x < w; x++) {
            float rgb[3], v[3];
            load_rgb(e, k, o + x, rgb);
            rgb_to_ycxcz(rgb, v);
            Y[x] = v[0];
            Cx[x] = v[1];
            Cz[x] = v[2];
        }
        row_filter(Y, w, e->cf.y, rc, pad, P + o);
        row_filter(Cx, w, e->cf.cx, rc, pad, P + n + o);
        row_filter(Cz, w, e->cf.cz1, rc, pad, P + 2 * n + o);
        row_filter(Cz, w, e->cf.cz2, rc, pad, P + 3 * n + o);
        for (int x = 0; x < w; x++)
            yn[x] = Y[x] / 116.0f + 16.0f / 116.0f;
        row_filter(yn, w, e->ff.dg, rf, pad, P + 4 * n + o);
        row_filter(yn, w, e->ff.ddg, rf, pad, P + 5 * n + o);
        row_filter(yn, w, e->ff.g, rf, pad, P + 6 * n + o);
    }
    free(pad);
}

/* Row y of image k's vertical filters: its CSF-filtered YCxCz (3 rows of w; the blue-yellow
 * channel the sum of its two separable terms) and feature magnitudes. s: 6 rows of scratch. */
static void row_vertical(const flip_eval *e, int k, int y, float *csf, float *edge, float *point,
                         float *s)
{
    const int w = e->w, h = e->h, rc = e->cf.radius, rf = e->ff.radius;
    const size_t n = (size_t)w * h;
    const float *P = e->planes + (size_t)k * FLIP_PLANES * n;
    col_filter(P, w, h, y, e->cf.y, rc, csf);
    col_filter(P + n, w, h, y, e->cf.cx, rc, csf + w);
    col_filter(P + 2 * n, w, h, y, e->cf.cz1, rc, s);
    col_filter(P + 3 * n, w, h, y, e->cf.cz2, rc, s + w);
    for (int x = 0; x < w; x++)
        csf[2 * w + x] = s[x] + s[w + x];
    /* Features: Gaussian across the first two, d/dy and d2/dy2 of the third. */
    float *dx = s + 2 * w, *ddx = s + 3 * w, *dy = s + 4 * w, *ddy = s + 5 * w;
    col_filter(P + 4 * n, w, h, y, e->ff.g, rf, dx);
    col_filter(P + 5 * n, w, h, y, e->ff.g, rf, ddx);
    col_filter(P + 6 * n, w, h, y, e->ff.dg, rf, dy);
    col_filter(P + 6 * n, w, h, y, e->ff.ddg, rf, ddy);
    for (int x = 0; x < w; x++) {
        edge[x] = sqrtf(dx[x] * dx[x] + dy[x] * dy[x]);
        point[x] = sqrtf(ddx[x] * ddx[x] + ddy[x] * ddy[x]);
    }
}

/* The per-pixel error of one pixel from both images' filtered values (index x of the rows). */
static float pixel_error(const flip_eval *e, const float *csf_r, const float *csf_t,
                         const float *ef, int x)
{
    const int w = e->w;
    const float cmax = e->cmax, pccmax = pc * cmax;
    float lr[3], lt[3], vr[3] = {csf_r[x], csf_r[w + x], csf_r[2 * w + x]};
    float vt[3] = {csf_t[x], csf_t[w + x], csf_t[2 * w + x]};
    ycxcz_to_lab_hunt(vr, lr);
    ycxcz_to_lab_hunt(vt, lt);
    /* Colour error (Eq. 5): HyAB^qc, compressed so that [0, pc cmax] maps to [0, pt] and the rest
     * to (pt, 1]. */
    float de = powf(hyab(lr, lt), qc);
    de = de < pccmax ? de * pt / pccmax : pt + (de - pccmax) / (cmax - pccmax) * (1.0f - pt);
    /* Feature error (Eq. 8) and the combination (Eq. 9): dE_c ^ (1 - dE_f). ef: the reference's
     * edge and point rows, then the test's. */
    float fe = fmaxf(fabsf(ef[x] - ef[2 * w + x]), fabsf(ef[w + x] - ef[3 * w + x]));
    fe = qf == 0.5f ? sqrtf(fe / sqrtf(2.0f)) : powf(fe / sqrtf(2.0f), qf);
    return powf(de, 1.0f - fe);
}

/* Item: one band's vertical filters for both images and its per-pixel errors into e->out. */
static void rows_vertical(void *ctx, int item)
{
    flip_eval *e = ctx;
    const int w = e->w, y0 = item * FLIP_BAND;
    const int y1 = y0 + FLIP_BAND < e->h ? y0 + FLIP_BAND : e->h;
    float *csf_r = malloc(16 * (size_t)w * sizeof(float));
    if (!csf_r) {
        atomic_store(&e->failed, 1);
        return;
    }
    float *csf_t = csf_r + 3 * w, *ef = csf_t + 3 * w, *s = ef + 4 * w;
    for (int y = y0; y < y1; y++) {
        row_vertical(e, 0, y, csf_r, ef, ef + w, s);
        row_vertical(e, 1, y, csf_t, ef + 2 * w, ef + 3 * w, s);
        float *out = e->out + (size_t)y * w;
        for (int x = 0; x < w; x++) {
            float v = pixel_error(e, csf_r, csf_t, ef, x);
            out[x] = e->hdr ? fmaxf(out[x], v) : v;
        }
    }
    free(csf_r);
}

/* Filters and plane memory for a w x h pair (e->out left to the caller). */
static int eval_init(flip_eval *e, const flip_src *ref, const flip_src *test, int w, int h,
                     float ppd, gib_error *err)
{
    memset(e, 0, sizeof *e);
    e->img[0] = *ref;
    e->img[1] = *test;
    e->w = w;
    e->h = h;
    e->rmax = 3 * (int)ceilf(ppd) + 8; /* above both filters' radii (10 and 9 at 67 ppd) */
    e->cmax = cmax_value();
    e->planes = malloc(2 * FLIP_PLANES * (size_t)w * h * sizeof(float));
    if (!e->planes || csf_make(&e->cf, ppd) < 0 || feat_make(&e->ff, ppd) < 0) {
        free(e->planes);
        free(e->cf.y);
        return gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY,
                             "FLIP: out of memory for a %dx%d image", w, h);
    }
    if (e->cf.radius > e->rmax || e->ff.radius > e->rmax) {
        free(e->planes);
        free(e->cf.y);
        free(e->ff.g);
        return gib_fail(err, "FLIP: %g pixels per degree gives filters wider than planned", ppd);
    }
    return 0;
}

static void eval_free(flip_eval *e)
{
    free(e->planes);
    free(e->cf.y);
    free(e->ff.g);
    memset(e, 0, sizeof *e);
}

/* One evaluation into e->out. Returns -1 (err set) when an item ran out of memory. */
static int eval_run(gib_team *team, flip_eval *e, gib_error *err)
{
    const int bands = (e->h + FLIP_BAND - 1) / FLIP_BAND;
    gib_team_run(team, 2 * bands, rows_horizontal, e);
    if (!atomic_load(&e->failed))
        gib_team_run(team, bands, rows_vertical, e);
    if (atomic_load(&e->failed))
        return gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY,
                             "FLIP: out of memory for a %dx%d image", e->w, e->h);
    return 0;
}

static int check_inputs(const flip_src *ref, const flip_src *test, int w, int h, gib_error *err)
{
    if (w < 1 || h < 1)
        return gib_fail(err, "FLIP: empty image (%dx%d)", w, h);
    size_t n = (size_t)w * h;
    for (size_t i = 0; i < n; i++)
        for (int c = 0; c < 3; c++) {
            float r = ref->px[i * ref->stride + c], t = test->px[i * test->stride + c];
            if (!isfinite(r) || !isfinite(t))
                return gib_fail_code(err, GIB_ERR_NON_FINITE,
                                     "FLIP: non-finite sample in the %s image at pixel %zu",
                                     isfinite(r) ? "test" : "reference", i);
        }
    return 0;
}

static double mean_of(const float *v, size_t n)
{
    double s = 0;
    for (size_t i = 0; i < n; i++)
        s += v[i];
    return s / (double)n;
}

/* LDR-FLIP of clamp(exposure * rgb) (inputs already checked); map: w*h floats or NULL. */
static double ldr_on(gib_team *team, const flip_src *ref, const flip_src *test, int w, int h,
                     float ppd, float exposure, float *map, gib_error *err)
{
    flip_eval e;
    if (eval_init(&e, ref, test, w, h, ppd, err) < 0)
        return NAN;
    const size_t n = (size_t)w * h;
    e.scale = exposure;
    e.out = map ? map : malloc(n * sizeof(float));
    double mean = NAN;
    if (!e.out)
        gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY, "FLIP: out of memory for a %dx%d image", w, h);
    else if (eval_run(team, &e, err) == 0)
        mean = mean_of(e.out, n);
    if (e.out != map)
        free(e.out);
    eval_free(&e);
    return mean;
}

double gib_flip_ldr(const float *ref, const float *test, int w, int h, float ppd, float *map,
                    gib_error *err)
{
    const flip_src r = {ref, 3}, t = {test, 3};
    if (check_inputs(&r, &t, w, h, err) < 0)
        return NAN;
    gib_team *team = gib_team_start(0);
    double mean = ldr_on(team, &r, &t, w, h, ppd, 1.0f, map, err);
    gib_team_stop(team);
    return mean;
}

/* Exposure range (HDR-FLIP Sec. 3.2): x_max solves tonemap(x) = t = 0.85 (a quadratic), Y_max and
 * Y_median are the reference's luminance maximum and median (element n/2 of the sorted
 * luminances, as the reference implementation's nth_element). Returns -1 (err set) when the
 * reference is black or memory runs out. */
static int hdr_range(const flip_src *ref, size_t n, float *start, float *stop, gib_error *err)
{
    const float t = 0.85f;
    float qa = aces[0] - t * aces[3], qb = aces[1] - t * aces[4], qcc = aces[2] - t * aces[5];
    float d1 = -0.5f * (qb / qa), xmax = d1 + sqrtf(d1 * d1 - qcc / qa);
    float *lum = malloc(n * sizeof(float));
    if (!lum)
        return gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY, "FLIP: out of memory for %zu pixels", n);
    float ymax = -INFINITY;
    size_t dark = 0; /* luminances not above 0 */
    for (size_t i = 0; i < n; i++) {
        const float *p = ref->px + i * (size_t)ref->stride;
        lum[i] = 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2];
        ymax = fmaxf(ymax, lum[i]);
        dark += !(lum[i] > 0.0f);
    }
    float ymed = gib_float_kth(lum, n, n / 2);
    /* Choice: where over half the reference is black (an AO or indirect-only image with empty
     * sky), log2(x_max / 0) is infinite and the reference implementation has no range; we take
     * the median of the positive luminances instead. */
    if (!(ymed > 0.0f))
        ymed = dark < n ? gib_float_kth(lum, n, dark + (n - dark) / 2) : 0.0f;
    free(lum);
    if (!(ymax > 0.0f) || !(ymed > 0.0f))
        return gib_fail(err, "HDR-FLIP: the reference is black, so it defines no exposure range");
    *start = log2f(xmax / ymax);
    *stop = log2f(xmax / ymed);
    return 0;
}

/* HDR-FLIP (inputs already checked): the per-pixel maximum of LDR-FLIP over the exposures. */
static double hdr_on(gib_team *team, const flip_src *ref, const flip_src *test, int w, int h,
                     float ppd, float *map, float *start_out, float *stop_out, gib_error *err)
{
    const size_t n = (size_t)w * h;
    float start = 0.0f, stop = 0.0f;
    if (hdr_range(ref, n, &start, &stop, err) < 0)
        return NAN;
    int count = (int)fmaxf(2.0f, ceilf(stop - start));
    if (start_out)
        *start_out = start;
    if (stop_out)
        *stop_out = stop;
    flip_eval e;
    if (eval_init(&e, ref, test, w, h, ppd, err) < 0)
        return NAN;
    e.hdr = 1;
    e.out = calloc(n, sizeof(float));
    int rc = e.out ? 0 : gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY,
                                       "FLIP: out of memory for a %dx%d image", w, h);
    float step = (stop - start) / (float)(count - 1);
    for (int k = 0; k < count && rc == 0; k++) {
        e.scale = powf(2.0f, start + (float)k * step);
        rc = eval_run(team, &e, err);
    }
    double mean = rc == 0 ? mean_of(e.out, n) : NAN;
    if (rc == 0 && map)
        memcpy(map, e.out, n * sizeof(float));
    free(e.out);
    eval_free(&e);
    return mean;
}

double gib_flip_hdr(const float *ref, const float *test, int w, int h, float ppd, float *map,
                    float *start_out, float *stop_out, gib_error *err)
{
    const flip_src r = {ref, 3}, t = {test, 3};
    if (check_inputs(&r, &t, w, h, err) < 0)
        return NAN;
    gib_team *team = gib_team_start(0);
    double mean = hdr_on(team, &r, &t, w, h, ppd, map, start_out, stop_out, err);
    gib_team_stop(team);
    return mean;
}

int gib_flip_pair_on(gib_team *team, const gib_image *ref, const gib_image *test, float exposure,
                     float *ldr_map, double *ldr, double *hdr, gib_error *err)
{
    *ldr = *hdr = NAN;
    const int w = ref->width, h = ref->height;
    if (test->width != w || test->height != h || ref->channels < 3 || test->channels < 3)
        return 0; /* gib_metrics_compute reports the mismatch */
    const flip_src r = {ref->px, ref->channels}, t = {test->px, test->channels};
    /* A NaN mean (non-finite samples, black reference) is the answer: the row's nonfinite count
     * and status already say what is wrong with the image, so the message is not needed. The LDR
     * pair is clamped (NaN to 0, infinities to 0 or 1), so only HDR-FLIP checks the samples. */
    gib_error ferr = {0};
    const float ppd = gib_flip_default_ppd();
    *ldr = ldr_on(team, &r, &t, w, h, ppd, exposure, ldr_map, &ferr);
    if (!isnan(*ldr) && check_inputs(&r, &t, w, h, &ferr) == 0)
        *hdr = hdr_on(team, &r, &t, w, h, ppd, NULL, NULL, NULL, &ferr);
    if (isnan(*ldr + *hdr) && ferr.code == GIB_ERR_OUT_OF_MEMORY)
        return gib_fail_code(err, ferr.code, "%s", ferr.msg);
    return 0;
}

/* Every 16th entry of matplotlib's magma (sRGB), the map FLIP's tool uses, linearly interpolated. */
static const float magma[17][3] = {
    {0.001462f, 0.000466f, 0.013866f}, {0.039608f, 0.031090f, 0.133515f},
    {0.113094f, 0.065492f, 0.276784f}, {0.211718f, 0.061992f, 0.418647f},
    {0.316654f, 0.071690f, 0.485380f}, {0.414709f, 0.110431f, 0.504662f},
    {0.512831f, 0.148179f, 0.507648f}, {0.613617f, 0.181811f, 0.498536f},
    {0.716387f, 0.214982f, 0.475290f}, {0.816914f, 0.255895f, 0.436461f},
    {0.904281f, 0.319610f, 0.388137f}, {0.960949f, 0.418323f, 0.359630f},
    {0.986700f, 0.535582f, 0.382210f}, {0.996096f, 0.653659f, 0.446213f},
    {0.996898f, 0.769591f, 0.534892f}, {0.992440f, 0.884330f, 0.640099f},
    {0.987053f, 0.991438f, 0.749504f}};

void gib_flip_magma(float t, unsigned char rgb[3])
{
    t = isfinite(t) ? fminf(fmaxf(t, 0.0f), 1.0f) : 0.0f;
    float s = t * 16.0f; /* the last entry is index 255, close enough to 256 for a ramp */
    int i = (int)s;
    if (i > 15)
        i = 15;
    float f = s - (float)i;
    for (int c = 0; c < 3; c++)
        rgb[c] = (unsigned char)lrintf(255.0f * (magma[i][c] + f * (magma[i + 1][c] - magma[i][c])));
}

int gib_flip_write_png(const char *path, const float *map, int w, int h, gib_error *err)
{
    unsigned char *rgb = malloc(3 * (size_t)w * h);
    if (!rgb)
        return gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY, "png '%s': out of memory", path);
    for (size_t i = 0; i < (size_t)w * h; i++)
        gib_flip_magma(map[i], rgb + 3 * i);
    int rc = gib_png_write8(path, w, h, 3, rgb, err);
    free(rgb);
    return rc;
}
