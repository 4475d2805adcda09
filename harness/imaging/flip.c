/* gibench — LDR-FLIP and HDR-FLIP (see flip.h). Equation numbers refer to the FLIP paper (HPG 2020);
 * constants and the separable form of its filters follow the reference implementation, whose means
 * the unit test compares against. Single-threaded: the harness shares its cores with the renderer. */
#include "flip.h"

#include <math.h>
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

/* One image's filtered quantities. ycc: three planes (Y, Cx, Cz). csf_out: three planes of the
 * CSF-filtered YCxCz; edge, point: feature magnitudes. tmp: 4 planes of scratch; pad: a row of
 * w + 2 max(radius) floats; row: 4 rows of w floats. */
static void filter_one(const float *ycc, int w, int h, const csf_filters *cf, const feat_filters *ff,
                       float *tmp, float *pad, float *row, float *csf_out, float *edge, float *point)
{
    size_t n = (size_t)w * h;
    const float *Y = ycc, *Cx = ycc + n, *Cz = ycc + 2 * n;
    int r = cf->radius;
    /* CSF (Eq. 2-3), horizontal: Y, Cx and the Cz channel with each of its two filters. */
    for (int y = 0; y < h; y++) {
        size_t o = (size_t)y * w;
        row_filter(Y + o, w, cf->y, r, pad, tmp + o);
        row_filter(Cx + o, w, cf->cx, r, pad, tmp + n + o);
        row_filter(Cz + o, w, cf->cz1, r, pad, tmp + 2 * n + o);
        row_filter(Cz + o, w, cf->cz2, r, pad, tmp + 3 * n + o);
    }
    /* Vertical; the blue-yellow channel is the sum of its two separable terms. */
    for (int y = 0; y < h; y++) {
        size_t o = (size_t)y * w;
        col_filter(tmp, w, h, y, cf->y, r, csf_out + o);
        col_filter(tmp + n, w, h, y, cf->cx, r, csf_out + n + o);
        col_filter(tmp + 2 * n, w, h, y, cf->cz1, r, row);
        col_filter(tmp + 3 * n, w, h, y, cf->cz2, r, row + w);
        for (int x = 0; x < w; x++)
            csf_out[2 * n + o + x] = row[x] + row[w + x];
    }
    /* Features (Sec. 5.1) on the achromatic channel normalised to [0,1], (Y + 16) / 116.
     * Horizontal: d/dx, d2/dx2 and Gaussian; vertical: Gaussian of the first two, d/dy and d2/dy2
     * of the third. */
    r = ff->radius;
    float *yn = row;
    for (int y = 0; y < h; y++) {
        size_t o = (size_t)y * w;
        for (int x = 0; x < w; x++)
            yn[x] = Y[o + x] / 116.0f + 16.0f / 116.0f;
        row_filter(yn, w, ff->dg, r, pad, tmp + o);
        row_filter(yn, w, ff->ddg, r, pad, tmp + n + o);
        row_filter(yn, w, ff->g, r, pad, tmp + 2 * n + o);
    }
    for (int y = 0; y < h; y++) {
        size_t o = (size_t)y * w;
        float *dx = row, *ddx = row + w, *dy = row + 2 * w, *ddy = row + 3 * w;
        col_filter(tmp, w, h, y, ff->g, r, dx);
        col_filter(tmp + n, w, h, y, ff->g, r, ddx);
        col_filter(tmp + 2 * n, w, h, y, ff->dg, r, dy);
        col_filter(tmp + 2 * n, w, h, y, ff->ddg, r, ddy);
        for (int x = 0; x < w; x++) {
            edge[o + x] = sqrtf(dx[x] * dx[x] + dy[x] * dy[x]);
            point[o + x] = sqrtf(ddx[x] * ddx[x] + ddy[x] * ddy[x]);
        }
    }
}

typedef struct flip_work {
    csf_filters cf;
    feat_filters ff;
    float *ycc_r, *ycc_t, *tmp, *csf_r, *csf_t, *e_r, *e_t, *p_r, *p_t, *err_px, *pad, *row;
} flip_work;

static void work_free(flip_work *k)
{
    free(k->cf.y);
    free(k->ff.g);
    free(k->ycc_r);
    memset(k, 0, sizeof *k);
}

static int work_alloc(flip_work *k, int w, int h, float ppd, gib_error *err)
{
    memset(k, 0, sizeof *k);
    size_t n = (size_t)w * h;
    /* ycc x2, csf x2 (3 planes each), tmp (4), edge/point x2, error (1): 21 floats per pixel;
     * then the padded row and 4 scratch rows. */
    int rmax = 3 * (int)ceilf(ppd) + 8; /* above both filters' radii (10 and 9 at 67 ppd) */
    k->ycc_r = malloc((21 * n + (size_t)w + 2 * (size_t)rmax + 4 * (size_t)w) * sizeof(float));
    if (!k->ycc_r || csf_make(&k->cf, ppd) < 0 || feat_make(&k->ff, ppd) < 0) {
        work_free(k);
        return gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY,
                             "FLIP: out of memory for a %dx%d image", w, h);
    }
    k->ycc_t = k->ycc_r + 3 * n;
    k->csf_r = k->ycc_t + 3 * n;
    k->csf_t = k->csf_r + 3 * n;
    k->tmp = k->csf_t + 3 * n;
    k->e_r = k->tmp + 4 * n;
    k->e_t = k->e_r + n;
    k->p_r = k->e_t + n;
    k->p_t = k->p_r + n;
    k->err_px = k->p_t + n;
    k->pad = k->err_px + n;
    k->row = k->pad + w + 2 * rmax;
    if (k->cf.radius > rmax || k->ff.radius > rmax) {
        work_free(k);
        return gib_fail(err, "FLIP: %g pixels per degree gives filters wider than planned", ppd);
    }
    return 0;
}

/* LDR-FLIP of the pair already converted to YCxCz in k->ycc_r / k->ycc_t; writes k->err_px. */
static void ldr_flip_core(flip_work *k, int w, int h)
{
    filter_one(k->ycc_r, w, h, &k->cf, &k->ff, k->tmp, k->pad, k->row, k->csf_r, k->e_r, k->p_r);
    filter_one(k->ycc_t, w, h, &k->cf, &k->ff, k->tmp, k->pad, k->row, k->csf_t, k->e_t, k->p_t);
    const float cmax = cmax_value(), pccmax = pc * cmax;
    size_t n = (size_t)w * h;
    for (size_t i = 0; i < n; i++) {
        float lr[3], lt[3], vr[3] = {k->csf_r[i], k->csf_r[n + i], k->csf_r[2 * n + i]};
        float vt[3] = {k->csf_t[i], k->csf_t[n + i], k->csf_t[2 * n + i]};
        ycxcz_to_lab_hunt(vr, lr);
        ycxcz_to_lab_hunt(vt, lt);
        /* Colour error (Eq. 5): HyAB^qc, compressed so that [0, pc cmax] maps to [0, pt] and the
         * rest to (pt, 1]. */
        float de = powf(hyab(lr, lt), qc);
        de = de < pccmax ? de * pt / pccmax : pt + (de - pccmax) / (cmax - pccmax) * (1.0f - pt);
        /* Feature error (Eq. 8) and the combination (Eq. 9): dE_c ^ (1 - dE_f). */
        float fe = fmaxf(fabsf(k->e_r[i] - k->e_t[i]), fabsf(k->p_r[i] - k->p_t[i]));
        fe = qf == 0.5f ? sqrtf(fe / sqrtf(2.0f)) : powf(fe / sqrtf(2.0f), qf);
        k->err_px[i] = powf(de, 1.0f - fe);
    }
}

/* Linear RGB pixel i -> YCxCz, into three planes of n floats. */
static void store_ycc(float *planes, size_t n, size_t i, const float rgb[3])
{
    float v[3];
    rgb_to_ycxcz(rgb, v);
    planes[i] = v[0];
    planes[n + i] = v[1];
    planes[2 * n + i] = v[2];
}

static int check_inputs(const float *ref, const float *test, int w, int h, gib_error *err)
{
    if (w < 1 || h < 1)
        return gib_fail(err, "FLIP: empty image (%dx%d)", w, h);
    size_t n = 3 * (size_t)w * h;
    for (size_t i = 0; i < n; i++)
        if (!isfinite(ref[i]) || !isfinite(test[i]))
            return gib_fail_code(err, GIB_ERR_NON_FINITE,
                                 "FLIP: non-finite sample in the %s image at pixel %zu",
                                 isfinite(ref[i]) ? "test" : "reference", i / 3);
    return 0;
}

static double mean_of(const float *v, size_t n)
{
    double s = 0;
    for (size_t i = 0; i < n; i++)
        s += v[i];
    return s / (double)n;
}

double gib_flip_ldr(const float *ref, const float *test, int w, int h, float ppd, float *map,
                    gib_error *err)
{
    flip_work k;
    if (check_inputs(ref, test, w, h, err) < 0 || work_alloc(&k, w, h, ppd, err) < 0)
        return NAN;
    size_t n = (size_t)w * h;
    for (size_t i = 0; i < n; i++) {
        float a[3], b[3];
        for (int c = 0; c < 3; c++) {
            a[c] = fminf(fmaxf(ref[3 * i + c], 0.0f), 1.0f);
            b[c] = fminf(fmaxf(test[3 * i + c], 0.0f), 1.0f);
        }
        store_ycc(k.ycc_r, n, i, a);
        store_ycc(k.ycc_t, n, i, b);
    }
    ldr_flip_core(&k, w, h);
    double mean = mean_of(k.err_px, n);
    if (map)
        memcpy(map, k.err_px, n * sizeof(float));
    work_free(&k);
    return mean;
}

/* ACES filmic curve fit (Narkowicz) as HDR-FLIP uses it, with its 0.6 pre-exposure folded into
 * the coefficients: (c0 x^2 + c1 x + c2) / (c3 x^2 + c4 x + c5). */
static const float aces[6] = {0.6f * 0.6f * 2.51f, 0.6f * 0.03f, 0.0f,
                              0.6f * 0.6f * 2.43f, 0.6f * 0.59f, 0.14f};

static float tonemap(float x)
{
    float v = (x * x * aces[0] + x * aces[1] + aces[2]) / (x * x * aces[3] + x * aces[4] + aces[5]);
    return fminf(fmaxf(v, 0.0f), 1.0f);
}

static int cmp_float(const void *a, const void *b)
{
    float x = *(const float *)a, y = *(const float *)b;
    return (x > y) - (x < y);
}

double gib_flip_hdr(const float *ref, const float *test, int w, int h, float ppd, float *map,
                    float *start_out, float *stop_out, gib_error *err)
{
    if (check_inputs(ref, test, w, h, err) < 0)
        return NAN;
    size_t n = (size_t)w * h;
    /* Exposure range (HDR-FLIP Sec. 3.2): x_max solves tonemap(x) = t = 0.85 (a quadratic), Y_max
     * and Y_median are the reference's luminance maximum and median (element n/2 of the sorted
     * luminances, as the reference implementation's nth_element). */
    const float t = 0.85f;
    float qa = aces[0] - t * aces[3], qb = aces[1] - t * aces[4], qcc = aces[2] - t * aces[5];
    float d1 = -0.5f * (qb / qa), xmax = d1 + sqrtf(d1 * d1 - qcc / qa);
    float *lum = malloc(n * sizeof(float));
    if (!lum) {
        gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY, "FLIP: out of memory for a %dx%d image", w, h);
        return NAN;
    }
    float ymax = -INFINITY;
    for (size_t i = 0; i < n; i++) {
        const float *p = ref + 3 * i;
        lum[i] = 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2];
        ymax = fmaxf(ymax, lum[i]);
    }
    qsort(lum, n, sizeof(float), cmp_float);
    float ymed = lum[n / 2];
    /* Choice: where over half the reference is black (an AO or indirect-only image with empty
     * sky), log2(x_max / 0) is infinite and the reference implementation has no range; we take
     * the median of the positive luminances instead. */
    if (!(ymed > 0.0f)) {
        size_t first = 0;
        while (first < n && !(lum[first] > 0.0f))
            first++;
        ymed = first < n ? lum[first + (n - first) / 2] : 0.0f;
    }
    free(lum);
    if (!(ymax > 0.0f) || !(ymed > 0.0f)) {
        gib_fail(err, "HDR-FLIP: the reference is black, so it defines no exposure range");
        return NAN;
    }
    float start = log2f(xmax / ymax), stop = log2f(xmax / ymed);
    int count = (int)fmaxf(2.0f, ceilf(stop - start));
    if (start_out)
        *start_out = start;
    if (stop_out)
        *stop_out = stop;

    flip_work k;
    float *best = calloc(n, sizeof(float));
    if (!best || work_alloc(&k, w, h, ppd, err) < 0) {
        if (!best)
            gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY,
                          "FLIP: out of memory for a %dx%d image", w, h);
        free(best);
        return NAN;
    }
    float step = (stop - start) / (float)(count - 1);
    for (int e = 0; e < count; e++) {
        float m = powf(2.0f, start + (float)e * step);
        for (size_t i = 0; i < n; i++) {
            float a[3], b[3];
            for (int c = 0; c < 3; c++) {
                a[c] = tonemap(ref[3 * i + c] * m);
                b[c] = tonemap(test[3 * i + c] * m);
            }
            store_ycc(k.ycc_r, n, i, a);
            store_ycc(k.ycc_t, n, i, b);
        }
        ldr_flip_core(&k, w, h);
        for (size_t i = 0; i < n; i++)
            best[i] = fmaxf(best[i], k.err_px[i]);
    }
    work_free(&k);
    double mean = mean_of(best, n);
    if (map)
        memcpy(map, best, n * sizeof(float));
    free(best);
    return mean;
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
