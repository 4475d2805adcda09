/* gibench — the reference renderer's texture lookups.
 *
 * Why mip maps: the GL techniques sample albedo textures with GL_LINEAR_MIPMAP_LINEAR
 * (harness/gl/gpu_scene.c) at the pixel's footprint. A reference that took level 0 at the pixel
 * centre would alias wherever a texture is minified (Crytek Sponza's floors and walls), and the
 * `direct` error would measure texture aliasing, not lighting. So at PRIMARY hits the reference
 * filters the albedo exactly as GL does — a box-filtered pyramid built once per texture, trilinear
 * between levels, with GL's isotropic LOD (OpenGL 4.5 core spec, Sec. 8.14.1, Eq. 8.7-8.9) from
 * ray differentials (Igehy 1999, "Tracing Ray Differentials", SIGGRAPH; see
 * ref_hit_differentials) — so both sides see the same filtered albedo. Secondary hits take level 0
 * bilinear: a bounce ray has no pixel footprint worth filtering over, and its noise averages out. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ref_internal.h"


/* Bilinear lookup of one level: texel centres at (i + 0.5) / size, as in GL, so a lookup at a
 * texel centre returns that texel exactly; repeat wrap in both directions; row 0 is the top of the
 * image (scene.h). */
static void ref_bilinear(const float *px, int w, int h, float u, float v, float out[4])
{
    if (!isfinite(u))
        u = 0.0f;
    if (!isfinite(v))
        v = 0.0f;
    float s = u - floorf(u);
    float tt = 1.0f - v;
    tt -= floorf(tt);
    float x = s * (float)w - 0.5f, y = tt * (float)h - 0.5f;
    float xf = floorf(x), yf = floorf(y);
    float ax = x - xf, ay = y - yf;
    /* s, tt in [0, 1] put xf in [-1, w - 1]: repeat wrap without a division */
    int x0 = (int)xf, y0 = (int)yf, x1 = x0 + 1, y1 = y0 + 1;
    x0 = x0 < 0 ? w - 1 : x0 >= w ? x0 - w : x0;
    x1 = x1 >= w ? x1 - w : x1;
    y0 = y0 < 0 ? h - 1 : y0 >= h ? y0 - h : y0;
    y1 = y1 >= h ? y1 - h : y1;
    const float *p00 = px + ((size_t)y0 * (size_t)w + (size_t)x0) * 4;
    const float *p10 = px + ((size_t)y0 * (size_t)w + (size_t)x1) * 4;
    const float *p01 = px + ((size_t)y1 * (size_t)w + (size_t)x0) * 4;
    const float *p11 = px + ((size_t)y1 * (size_t)w + (size_t)x1) * 4;
    for (int c = 0; c < 4; c++) {
        float top = p00[c] + (p10[c] - p00[c]) * ax;
        float bot = p01[c] + (p11[c] - p01[c]) * ax;
        out[c] = top + (bot - top) * ay;
    }
}

void ref_tex_sample(const gib_texture *t, float u, float v, float out[4])
{
    if (!t || !t->rgba || t->width <= 0 || t->height <= 0) {
        out[0] = out[1] = out[2] = out[3] = 1.0f;
        return;
    }
    ref_bilinear(t->rgba, t->width, t->height, u, v, out);
}

/* One box-filtered level from the previous: each texel averages the 2x2 texels it covers. A level
 * of odd size floor(n/2) would drop the last row or column; its last texel averages three instead,
 * so every texel of the finer level contributes (a non-power-of-two texture's mip chain is
 * implementation-defined in GL; Crytek Sponza's textures are powers of two). */
static void ref_downsample(const float *src, int sw, int sh, float *dst, int dw, int dh)
{
    for (int y = 0; y < dh; y++) {
        int y0 = 2 * y, y1 = (y == dh - 1 && sh > 2 * dh) ? 2 * y + 2 : 2 * y + 1;
        if (y1 >= sh)
            y1 = sh - 1;
        for (int x = 0; x < dw; x++) {
            int x0 = 2 * x, x1 = (x == dw - 1 && sw > 2 * dw) ? 2 * x + 2 : 2 * x + 1;
            if (x1 >= sw)
                x1 = sw - 1;
            float acc[4] = {0, 0, 0, 0};
            int n = 0;
            for (int yy = y0; yy <= y1; yy++)
                for (int xx = x0; xx <= x1; xx++, n++)
                    for (int c = 0; c < 4; c++)
                        acc[c] += src[((size_t)yy * (size_t)sw + (size_t)xx) * 4 + c];
            for (int c = 0; c < 4; c++)
                dst[((size_t)y * (size_t)dw + (size_t)x) * 4 + c] = acc[c] / (float)n;
        }
    }
}

int ref_mip_build(ref_mip *m, const gib_texture *t, gib_error *err)
{
    memset(m, 0, sizeof *m);
    if (!t || !t->rgba || t->width <= 0 || t->height <= 0)
        return 0;
    int w = t->width, h = t->height, levels = 1;
    size_t total = 0;
    while ((w > 1 || h > 1) && levels < REF_MAX_MIPS) {
        w = w > 1 ? w / 2 : 1;
        h = h > 1 ? h / 2 : 1;
        total += (size_t)w * (size_t)h * 4;
        levels++;
    }
    if (total > 0) {
        m->owned = malloc(total * sizeof(float));
        if (!m->owned)
            return gib_fail(err, "out of memory building the mip maps of texture '%s'", t->path);
    }
    m->levels = levels;
    m->w[0] = t->width;
    m->h[0] = t->height;
    m->lv[0] = t->rgba;
    float *next = m->owned;
    for (int l = 1; l < levels; l++) {
        m->w[l] = m->w[l - 1] > 1 ? m->w[l - 1] / 2 : 1;
        m->h[l] = m->h[l - 1] > 1 ? m->h[l - 1] / 2 : 1;
        ref_downsample(m->lv[l - 1], m->w[l - 1], m->h[l - 1], next, m->w[l], m->h[l]);
        m->lv[l] = next;
        next += (size_t)m->w[l] * (size_t)m->h[l] * 4;
    }
    return 0;
}

void ref_mip_free(ref_mip *m)
{
    free(m->owned);
    memset(m, 0, sizeof *m);
}

float ref_mip_lod(const ref_mip *m, const float duv[4])
{
    float w = (float)m->w[0], h = (float)m->h[0];
    float ax = duv[0] * w, ay = duv[1] * h, bx = duv[2] * w, by = duv[3] * h;
    float rho2 = fmaxf(ax * ax + ay * ay, bx * bx + by * by);
    if (!(rho2 > 0.0f))
        return -INFINITY;
    if (!isfinite(rho2))
        return INFINITY;
    return 0.5f * log2f(rho2);
}

void ref_mip_sample(const ref_mip *m, float u, float v, const float *duv, float out[4])
{
    float lod = duv ? ref_mip_lod(m, duv) : -INFINITY;
    if (!(lod > 0.0f) || m->levels <= 1) { /* magnification: GL_LINEAR on level 0 */
        ref_bilinear(m->lv[0], m->w[0], m->h[0], u, v, out);
        return;
    }
    int q = m->levels - 1;
    float lf = fminf(lod, (float)q);
    int d1 = (int)floorf(lf);
    float tau = lf - (float)d1;
    int d2 = d1 + 1 > q ? q : d1 + 1;
    float a[4], b[4];
    ref_bilinear(m->lv[d1], m->w[d1], m->h[d1], u, v, a);
    if (tau == 0.0f || d2 == d1) {
        memcpy(out, a, sizeof a);
        return;
    }
    ref_bilinear(m->lv[d2], m->w[d2], m->h[d2], u, v, b);
    for (int c = 0; c < 4; c++)
        out[c] = (1.0f - tau) * a[c] + tau * b[c];
}
