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
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "ref_internal.h"


/* Bilinear lookup of one level: texel centres at (i + 0.5) / size, as in GL, so a lookup at a
 * texel centre returns that texel exactly; repeat wrap in both directions; row 0 is the top of the
 * image (scene.h). */
/* The four texels and weights of a bilinear lookup at (u, v) in a w x h level (both lookups below). */
typedef struct ref_bilerp {
    int x0, x1, y0, y1;
    float ax, ay;
} ref_bilerp;

static inline ref_bilerp ref_bilerp_at(int w, int h, float u, float v)
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
    ref_bilerp b = {.ax = x - xf, .ay = y - yf};
    /* s, tt in [0, 1] put xf in [-1, w - 1]: repeat wrap without a division */
    b.x0 = (int)xf, b.y0 = (int)yf, b.x1 = b.x0 + 1, b.y1 = b.y0 + 1;
    b.x0 = b.x0 < 0 ? w - 1 : b.x0 >= w ? b.x0 - w : b.x0;
    b.x1 = b.x1 >= w ? b.x1 - w : b.x1;
    b.y0 = b.y0 < 0 ? h - 1 : b.y0 >= h ? b.y0 - h : b.y0;
    b.y1 = b.y1 >= h ? b.y1 - h : b.y1;
    return b;
}

static void ref_bilinear(const float *px, int w, int h, float u, float v, float out[4])
{
    const ref_bilerp b = ref_bilerp_at(w, h, u, v);
    const int x0 = b.x0, x1 = b.x1, y0 = b.y0, y1 = b.y1;
    const float ax = b.ax, ay = b.ay;
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

/* ---- cut-out masks ----
 * The alpha test runs inside Embree's traversal (ref_world.c's filter), for the path tracer and
 * for every ray of the bench alike, so it cannot be prefetched; what it can do is touch less
 * memory: one byte a texel instead of sixteen, in 8x8 tiles. The bytes index the first channel's
 * distinct values (at most 256 in a texture read from an 8-bit file), found by their bit
 * patterns, so the lookup interpolates exactly the floats ref_bilinear would. Sponza's three
 * masks shrink from 16 MB of floats each to 1 MB (reference/PERFORMANCE.md has the measurement;
 * images bit-identical; tests/reference/ref_texture.c checks the lookup against the floats). */
#define REF_MASK_SLOTS 1024

static size_t ref_mask_index(int tw, int x, int y)
{
    return (((size_t)(y >> 3) * (size_t)tw + (size_t)(x >> 3)) << 6) |
           (size_t)(((y & 7) << 3) | (x & 7));
}

int ref_mask_build(ref_mask *m, const gib_texture *t, gib_error *err)
{
    memset(m, 0, sizeof *m);
    m->tex = t;
    if (!t || !t->rgba || t->width <= 0 || t->height <= 0)
        return 0;
    m->w = t->width, m->h = t->height;
    const int tw = (m->w + 7) / 8, th = (m->h + 7) / 8;
    uint32_t key[REF_MASK_SLOTS];
    int16_t slot_code[REF_MASK_SLOTS];
    for (int k = 0; k < REF_MASK_SLOTS; k++)
        slot_code[k] = -1;
    m->code = malloc((size_t)tw * (size_t)th * 64);
    if (!m->code)
        return gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY,
                             "out of memory for the cut-out mask '%s'", t->path);
    memset(m->code, 0, (size_t)tw * (size_t)th * 64);
    int distinct = 0;
    for (int y = 0; y < m->h; y++)
        for (int x = 0; x < m->w; x++) {
            float f = t->rgba[((size_t)y * (size_t)m->w + (size_t)x) * 4];
            uint32_t bits;
            memcpy(&bits, &f, sizeof bits);
            unsigned h = (bits * 2654435761u) >> 22; /* 10 bits: REF_MASK_SLOTS */
            while (slot_code[h] >= 0 && key[h] != bits)
                h = (h + 1) & (REF_MASK_SLOTS - 1);
            if (slot_code[h] < 0) {
                if (distinct == 256) { /* not 8-bit: keep reading the floats */
                    free(m->code);
                    m->code = NULL;
                    return 0;
                }
                key[h] = bits;
                slot_code[h] = (int16_t)distinct;
                m->value[distinct++] = f;
            }
            m->code[ref_mask_index(tw, x, y)] = (uint8_t)slot_code[h];
        }
    return 0;
}

void ref_mask_free(ref_mask *m)
{
    free(m->code);
    memset(m, 0, sizeof *m);
}

float ref_mask_sample(const ref_mask *m, float u, float v)
{
    if (!m->code) {
        float out[4];
        ref_tex_sample(m->tex, u, v, out);
        return out[0];
    }
    const ref_bilerp b = ref_bilerp_at(m->w, m->h, u, v);
    const int tw = (m->w + 7) / 8;
    const float p00 = m->value[m->code[ref_mask_index(tw, b.x0, b.y0)]];
    const float p10 = m->value[m->code[ref_mask_index(tw, b.x1, b.y0)]];
    const float p01 = m->value[m->code[ref_mask_index(tw, b.x0, b.y1)]];
    const float p11 = m->value[m->code[ref_mask_index(tw, b.x1, b.y1)]];
    float top = p00 + (p10 - p00) * b.ax;
    float bot = p01 + (p11 - p01) * b.ax;
    return top + (bot - top) * b.ay;
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

/* ---- sRGB8 storage ----
 * The scene's textures come from 8-bit files: every colour value is exactly the sRGB decode of
 * some k / 255 (scenes/textures.c). Such a texture is stored as GL stores it (harness/gl/
 * gpu_scene.c uploads GL_SRGB8_ALPHA8 and generates its mips): 8-bit sRGB, decoded to linear
 * before filtering, each mip level averaged in linear and rounded back to 8 bits. That gives the
 * reference the very values GL filters, and a quarter of the memory traffic: texels are kept in
 * 4x4 tiles of one 64-byte cache line, so a bilinear footprint mostly touches one line. Textures
 * with values that are not 8-bit (built in C by tests) keep floats. */

static float ref_srgb_lut[256];
static float ref_alpha_lut[256]; /* alpha decodes as (float)k / 255.0f: those very floats */
/* linear value of the encoded midpoint (k + 0.5) / 255; [255] is +inf, no code lies above 255 */
static double ref_srgb_mid[256];
static uint8_t ref_srgb_bucket[1 << 16]; /* by the top 16 bits of a float: its smallest code */
static pthread_once_t ref_lut_once = PTHREAD_ONCE_INIT;

static unsigned ref_srgb_search(double v)
{
    unsigned lo = 0, hi = 255; /* answer in [lo, hi] */
    while (lo < hi) {
        unsigned mid = (lo + hi) / 2; /* is v at or past the midpoint between mid and mid + 1? */
        if (v >= ref_srgb_mid[mid])
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo;
}

static double ref_srgb_decode(double c)
{
    return c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4);
}

/* The loader's decode, evaluated the same way (scenes/textures.c), so lut[k] is its output. */
static void ref_lut_init(void)
{
    for (int k = 0; k < 256; k++) {
        float c = (float)k / 255.0f;
        ref_srgb_lut[k] = c <= 0.04045f ? c / 12.92f : powf((c + 0.055f) / 1.055f, 2.4f);
    }
    for (int k = 0; k < 255; k++)
        ref_srgb_mid[k] = ref_srgb_decode((k + 0.5) / 255.0);
    ref_srgb_mid[255] = INFINITY;
    for (uint32_t b = 0; b < (1u << 16); b++) {
        uint32_t bits = b << 16;
        float v;
        memcpy(&v, &bits, sizeof v);
        ref_srgb_bucket[b] = (uint8_t)(v > 0.0f && isfinite(v) ? ref_srgb_search(v) : 0);
    }
}

/* The 8-bit code GL's upload would store for a linear value: round(encode(v) * 255), i.e. the
 * number of encoded midpoints at or below v (the encode is monotonic). Found without a pow: the
 * float's top 16 bits give the code of the bottom of its bucket (buckets are 2^-7 wide in
 * relative terms; midpoints are at least 0.89% apart, 2.4 / 255 / 1.055 at the top), then a step
 * up if v is past the next midpoint: an add, not a branch, since whether it is past is a coin toss
 * for filtered values. The loop after it never steps and is there for the argument's sake. */
static unsigned ref_srgb_code(float v)
{
    if (!(v > 0.0f))
        return 0;
    if (v >= 1.0f)
        return 255;
    uint32_t bits;
    memcpy(&bits, &v, sizeof bits);
    unsigned k = ref_srgb_bucket[bits >> 16];
    k += (double)v >= ref_srgb_mid[k];
    while ((double)v >= ref_srgb_mid[k])
        k++;
    return k;
}

static unsigned ref_unorm_code(float v)
{
    long k = lrintf(ref_fminf(ref_fmaxf(v, 0.0f), 1.0f) * 255.0f);
    return (unsigned)k;
}

static size_t ref_tiled_size(int w, int h)
{
    return (size_t)((w + 3) / 4) * (size_t)((h + 3) / 4) * 16;
}

static inline size_t ref_tiled_index(int tw, int x, int y)
{
    return (((size_t)(y >> 2) * (size_t)tw + (size_t)(x >> 2)) << 4) |
           (size_t)(((y & 3) << 2) | (x & 3));
}

/* The 8-bit sRGB code of a level-0 colour value, or -1 if the value is not the decode of one.
 * "Is the decode" allows 2e-6 relative: the loader decodes 8-bit values that the image library
 * scaled by 1/255 in its own rounding, which can move them by an ulp or two from decode(k / 255). */
static int ref_exact_code(float v)
{
    unsigned c = ref_srgb_code(v);
    return fabsf(ref_srgb_lut[c] - v) <= 2e-6f * v + 1e-9f ? (int)c : -1;
}

/* ref_exact_code through a direct-mapped memo of the float bits: a texture holds a few hundred
 * distinct values, so nearly every lookup is a hit, and a hit returns what the call returned. */
#define REF_MEMO_SLOTS 1024
typedef struct ref_code_memo {
    uint32_t bits[REF_MEMO_SLOTS];
    int16_t code[REF_MEMO_SLOTS];
} ref_code_memo;

static inline int ref_memo_code(ref_code_memo *memo, float v)
{
    uint32_t bits;
    memcpy(&bits, &v, sizeof bits);
    const unsigned h = (bits * 2654435761u) >> 22; /* 10 bits: REF_MEMO_SLOTS */
    if (memo->bits[h] != bits) {
        memo->bits[h] = bits;
        memo->code[h] = (int16_t)ref_exact_code(v);
    }
    return memo->code[h];
}

static void ref_memo_init(ref_code_memo *memo)
{
    for (int i = 0; i < REF_MEMO_SLOTS; i++) /* bits 0: +0, whose code is 0 */
        memo->bits[i] = 0, memo->code[i] = 0;
}

/* Level 0's texel p as sRGB8, or -1 if some value is not the decode of an 8-bit code (colour:
 * ref_exact_code; alpha: within 1e-6 of k / 255). */
static inline int64_t ref_texel_code(ref_code_memo *memo, const float *p)
{
    int c[4];
    for (int k = 0; k < 3; k++)
        if ((c[k] = ref_memo_code(memo, p[k])) < 0)
            return -1;
    c[3] = p[3] == 1.0f ? 255 : (int)ref_unorm_code(p[3]);
    if (!(fabsf(ref_alpha_lut[c[3]] - p[3]) <= 1e-6f))
        return -1;
    return (uint32_t)c[0] | (uint32_t)c[1] << 8 | (uint32_t)c[2] << 16 | (uint32_t)c[3] << 24;
}

/* Packs level 0's linear RGBA into sRGB8 tiles at dst, or, given want instead, checks that want
 * holds exactly that packing; returns 0 if some value is not 8-bit or some texel differs. */
static int ref_pack8(const float *src, int w, int h, uint32_t *dst, const uint32_t *want)
{
    ref_code_memo memo;
    ref_memo_init(&memo);
    int tw = (w + 3) / 4;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            int64_t c = ref_texel_code(&memo, src + ((size_t)y * (size_t)w + (size_t)x) * 4);
            size_t i = ref_tiled_index(tw, x, y);
            if (c < 0 || (want && want[i] != (uint32_t)c))
                return 0;
            if (dst)
                dst[i] = (uint32_t)c;
        }
    return 1;
}

/* ref_average8's result for n copies of one code, by channel kind (0: sRGB, 1: alpha) and n:
 * the same sums and division, done once at start-up, so a flat block costs one lookup. */
static uint8_t ref_flat_code[2][10][256];

/* One channel of one filtered texel: the n codes decoded, summed in order, divided by n and
 * rounded back to 8 bits, the float operations of unpack -> ref_downsample -> pack exactly. */
static unsigned ref_average8(const uint32_t *t, int n, int sh, int alpha)
{
    const float *lut = alpha ? ref_alpha_lut : ref_srgb_lut;
    float acc = 0.0f;
    for (int i = 0; i < n; i++)
        acc += lut[(t[i] >> sh) & 255u];
    float v = acc / (float)n;
    return alpha ? ref_unorm_code(v) : ref_srgb_code(v);
}

/* The texel averaging the n packed texels t: each channel through ref_average8, or the flat-block
 * table when its n codes agree. */
static uint32_t ref_filter8(const uint32_t *t, int n)
{
    uint32_t out = 0;
    for (int c = 0; c < 4; c++) {
        const int sh = 8 * c;
        const unsigned k = (t[0] >> sh) & 255u;
        int flat = 1;
        for (int i = 1; i < n; i++)
            flat &= ((t[i] >> sh) & 255u) == k;
        out |= (flat ? ref_flat_code[c == 3][n][k] : ref_average8(t, n, sh, c == 3)) << sh;
    }
    return out;
}

/* The flat-block table and the alpha decode, after the sRGB tables they use. */
static void ref_tables_init(void)
{
    ref_lut_init();
    for (int k = 0; k < 256; k++)
        ref_alpha_lut[k] = (float)k / 255.0f;
    for (int n = 1; n <= 9; n++)
        for (int k = 0; k < 256; k++) {
            uint32_t t[9];
            for (int i = 0; i < n; i++)
                t[i] = (uint32_t)k * 0x01010101u;
            ref_flat_code[0][n][k] = (uint8_t)ref_average8(t, n, 0, 0);
            ref_flat_code[1][n][k] = (uint8_t)ref_average8(t, n, 24, 1);
        }
}

/* ref_downsample's texel footprint along one axis: [*lo, *hi] of the finer level for texel i. */
static void ref_span(int i, int dn, int sn, int *lo, int *hi)
{
    *lo = 2 * i;
    *hi = (i == dn - 1 && sn > 2 * dn) ? 2 * i + 2 : 2 * i + 1;
    if (*hi >= sn)
        *hi = sn - 1;
}

/* ref_filter8 for the 2x2 footprint of almost every texel, unrolled. The sum starts at the
 * first texel rather than at 0 + it: every decoded value is +0 or positive, so that add is exact. */
static uint32_t ref_filter8_2x2(uint32_t a, uint32_t b, uint32_t c, uint32_t d)
{
    uint32_t out = 0;
    for (int ch = 0; ch < 4; ch++) {
        const int sh = 8 * ch, alpha = ch == 3;
        const unsigned ka = (a >> sh) & 255u, kb = (b >> sh) & 255u, kc = (c >> sh) & 255u,
                       kd = (d >> sh) & 255u;
        unsigned code;
        if (ka == kb && ka == kc && ka == kd) {
            code = ref_flat_code[alpha][4][ka];
        } else {
            const float *lut = alpha ? ref_alpha_lut : ref_srgb_lut;
            float v = (((lut[ka] + lut[kb]) + lut[kc]) + lut[kd]) / 4.0f;
            code = alpha ? ref_unorm_code(v) : ref_srgb_code(v);
        }
        out |= code << sh;
    }
    return out;
}

/* One texel of an sRGB8 level from the finer level's tiles (src, stw tiles wide). */
static uint32_t ref_texel8(const uint32_t *src, int stw, int x0, int x1, int y0, int y1)
{
    if (x1 == x0 + 1 && y1 == y0 + 1)
        return ref_filter8_2x2(src[ref_tiled_index(stw, x0, y0)], src[ref_tiled_index(stw, x1, y0)],
                               src[ref_tiled_index(stw, x0, y1)], src[ref_tiled_index(stw, x1, y1)]);
    uint32_t t[9];
    int n = 0;
    for (int yy = y0; yy <= y1; yy++)
        for (int xx = x0; xx <= x1; xx++)
            t[n++] = src[ref_tiled_index(stw, xx, yy)];
    return ref_filter8(t, n);
}

/* One sRGB8 level straight from the previous one's tiles, as glGenerateMipmap makes it: the
 * texels ref_downsample would average, decoded, averaged in linear and rounded to 8 bits, with no
 * float copy of either level. */
static void ref_downsample8(const uint32_t *src, int sw, int sh, uint32_t *dst, int dw, int dh)
{
    const int stw = (sw + 3) / 4, dtw = (dw + 3) / 4;
    for (int y = 0; y < dh; y++) {
        int y0, y1;
        ref_span(y, dh, sh, &y0, &y1);
        for (int x = 0; x < dw; x++) {
            int x0, x1;
            ref_span(x, dw, sw, &x0, &x1);
            dst[ref_tiled_index(dtw, x, y)] = ref_texel8(src, stw, x0, x1, y0, y1);
        }
    }
}

static void ref_bilinear8(const ref_mip *m, int l, float u, float v, float out[4])
{
    const int w = m->w[l], h = m->h[l], tw = (w + 3) / 4;
    const uint32_t *px = m->lv8[l];
    const ref_bilerp b = ref_bilerp_at(w, h, u, v);
    const int x0 = b.x0, x1 = b.x1, y0 = b.y0, y1 = b.y1;
    const float ax = b.ax, ay = b.ay;
    const uint32_t t00 = px[ref_tiled_index(tw, x0, y0)], t10 = px[ref_tiled_index(tw, x1, y0)];
    const uint32_t t01 = px[ref_tiled_index(tw, x0, y1)], t11 = px[ref_tiled_index(tw, x1, y1)];
    for (int c = 0; c < 4; c++) {
        int sh = 8 * c;
        float a, b, cc, d;
        if (c < 3) {
            a = ref_srgb_lut[(t00 >> sh) & 255u], b = ref_srgb_lut[(t10 >> sh) & 255u];
            cc = ref_srgb_lut[(t01 >> sh) & 255u], d = ref_srgb_lut[(t11 >> sh) & 255u];
        } else {
            a = (float)(t00 >> 24) / 255.0f, b = (float)(t10 >> 24) / 255.0f;
            cc = (float)(t01 >> 24) / 255.0f, d = (float)(t11 >> 24) / 255.0f;
        }
        float top = a + (b - a) * ax, bot = cc + (d - cc) * ax;
        out[c] = top + (bot - top) * ay;
    }
}

static void ref_level_sample(const ref_mip *m, int l, float u, float v, float out[4])
{
    if (m->srgb8)
        ref_bilinear8(m, l, u, v, out);
    else
        ref_bilinear(m->lv[l], m->w[l], m->h[l], u, v, out);
}

/* m's level count and sizes for a w x h texture; *total8 is the sRGB8 pyramid's texels in tiles,
 * the result the floats of a float pyramid's levels 1 and up. */
static size_t ref_mip_shape(ref_mip *m, int w, int h, size_t *total8)
{
    size_t total = 0;
    m->levels = 1;
    m->w[0] = w, m->h[0] = h;
    *total8 = ref_tiled_size(w, h);
    while ((w > 1 || h > 1) && m->levels < REF_MAX_MIPS) {
        w = w > 1 ? w / 2 : 1;
        h = h > 1 ? h / 2 : 1;
        m->w[m->levels] = w, m->h[m->levels] = h;
        total += (size_t)w * (size_t)h * 4;
        *total8 += ref_tiled_size(w, h);
        m->levels++;
    }
    return total;
}

/* Whether t's level 0, packed, is exactly the sRGB8 level lv0 of its size. */
int ref_mip_same8(const gib_texture *t, const uint32_t *lv0)
{
    return ref_pack8(t->rgba, t->width, t->height, NULL, lv0);
}

/* The sRGB8 pyramid of t into m (shape set), like glGenerateMipmap on an sRGB8 texture: 1 built,
 * 0 when level 0 is not 8-bit, -1 out of memory. */
static int ref_build8(ref_mip *m, const gib_texture *t, size_t total8, gib_error *err)
{
    uint32_t *p8 = ref_alloc_huge(total8 * sizeof *p8);
    if (!p8)
        return gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY,
                             "out of memory building the mip maps of texture '%s'", t->path);
    if (!ref_pack8(t->rgba, t->width, t->height, p8, NULL)) {
        ref_free_huge(p8, total8 * sizeof *p8);
        return 0;
    }
    m->srgb8 = 1;
    m->owned8 = p8;
    m->owned8_bytes = total8 * sizeof *p8;
    m->lv8[0] = p8;
    size_t off = ref_tiled_size(m->w[0], m->h[0]);
    for (int l = 1; l < m->levels; l++) {
        m->lv8[l] = p8 + off;
        ref_downsample8(m->lv8[l - 1], m->w[l - 1], m->h[l - 1], p8 + off, m->w[l], m->h[l]);
        off += ref_tiled_size(m->w[l], m->h[l]);
    }
    return 1;
}

int ref_mip_build(ref_mip *m, const gib_texture *t, gib_error *err)
{
    memset(m, 0, sizeof *m);
    if (!t || !t->rgba || t->width <= 0 || t->height <= 0)
        return 0;
    pthread_once(&ref_lut_once, ref_tables_init);
    size_t total8, total = ref_mip_shape(m, t->width, t->height, &total8);
    if (ref_share_take(m, t))
        return 0;
    int rc = ref_build8(m, t, total8, err); /* sRGB8 when level 0 is exactly 8-bit */
    if (rc > 0)
        ref_share_put(m, t->path);
    if (rc != 0)
        return rc < 0 ? -1 : 0;
    if (total > 0) {
        m->owned = malloc(total * sizeof(float));
        if (!m->owned)
            return gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY,
                                 "out of memory building the mip maps of texture '%s'", t->path);
    }
    m->lv[0] = t->rgba;
    float *next = m->owned;
    for (int l = 1; l < m->levels; l++) {
        ref_downsample(m->lv[l - 1], m->w[l - 1], m->h[l - 1], next, m->w[l], m->h[l]);
        m->lv[l] = next;
        next += (size_t)m->w[l] * (size_t)m->h[l] * 4;
    }
    return 0;
}

void ref_mip_free(ref_mip *m)
{
    free(m->owned);
    if (m->owned8 && !ref_share_drop(m->owned8))
        ref_free_huge(m->owned8, m->owned8_bytes);
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
        ref_level_sample(m, 0, u, v, out);
        return;
    }
    int q = m->levels - 1;
    float lf = fminf(lod, (float)q);
    int d1 = (int)floorf(lf);
    float tau = lf - (float)d1;
    int d2 = d1 + 1 > q ? q : d1 + 1;
    float a[4], b[4];
    ref_level_sample(m, d1, u, v, a);
    if (tau == 0.0f || d2 == d1) {
        memcpy(out, a, sizeof a);
        return;
    }
    ref_level_sample(m, d2, u, v, b);
    for (int c = 0; c < 4; c++)
        out[c] = (1.0f - tau) * a[c] + tau * b[c];
}

/* All the lines of the level-0 bilinear footprint, not only the one holding the texel under (u, v):
 * a 2x2 footprint leaves its 4x4 tile in x or in y for 7 lookups in 16, and the line missed then
 * cost the whole miss at the load (reference/PERFORMANCE.md, "Texture prefetch"). A line
 * prefetched twice costs next to nothing, so all four texels go as they are. */
void ref_mip_prefetch(const ref_mip *m, float u, float v)
{
    if (m->levels == 0)
        return;
    const ref_bilerp b = ref_bilerp_at(m->w[0], m->h[0], u, v);
    if (m->srgb8) {
        const int tw = (m->w[0] + 3) / 4;
        const uint32_t *px = m->lv8[0];
        __builtin_prefetch(px + ref_tiled_index(tw, b.x0, b.y0));
        __builtin_prefetch(px + ref_tiled_index(tw, b.x1, b.y0));
        __builtin_prefetch(px + ref_tiled_index(tw, b.x0, b.y1));
        __builtin_prefetch(px + ref_tiled_index(tw, b.x1, b.y1));
    } else {
        const size_t w = (size_t)m->w[0];
        const float *px = m->lv[0];
        __builtin_prefetch(px + ((size_t)b.y0 * w + (size_t)b.x0) * 4);
        __builtin_prefetch(px + ((size_t)b.y0 * w + (size_t)b.x1) * 4);
        __builtin_prefetch(px + ((size_t)b.y1 * w + (size_t)b.x0) * 4);
        __builtin_prefetch(px + ((size_t)b.y1 * w + (size_t)b.x1) * 4);
    }
}

/* ---- the pixel footprint at primary hits ---- */

/* The albedo textures' pyramids and the cut-out masks, one texture per task on all cores. */
typedef struct ref_texture_jobs {
    ref_world *w;
    const gib_scene *gs;
    unsigned char *want;
    gib_error *errs;
    int *rc;
} ref_texture_jobs;

static void ref_texture_task(void *ctx, int t)
{
    ref_texture_jobs *j = ctx;
    if (j->want[t] & 1)
        j->rc[t] = ref_mip_build(&j->w->mips[t], &j->gs->textures[t], &j->errs[t]);
    if ((j->want[t] & 2) && j->rc[t] == 0)
        j->rc[t] = ref_mask_build(&j->w->masks[t], &j->gs->textures[t], &j->errs[t]);
}

int ref_world_textures(ref_world *w, const gib_scene *gs, gib_error *err)
{
    const uint32_t n = gs->texture_count;
    w->mips = gib_calloc(n, sizeof *w->mips, err);
    w->masks = w->mips ? gib_calloc(n, sizeof *w->masks, err) : NULL;
    ref_texture_jobs j = {w, gs, gib_calloc(n, 1, err), gib_calloc(n, sizeof *j.errs, err),
                      gib_calloc(n, sizeof *j.rc, err)};
    int rc = w->masks && j.want && j.errs && j.rc ? 0 : -1;
    for (uint32_t m = 0; rc == 0 && m < gs->material_count; m++) {
        if (gs->materials[m].albedo_tex >= 0)
            j.want[gs->materials[m].albedo_tex] |= 1;
        if (gs->materials[m].alpha_tex >= 0)
            j.want[gs->materials[m].alpha_tex] |= 2;
    }
    if (rc == 0)
        ref_parallel((int)sysconf(_SC_NPROCESSORS_ONLN), (int)n, ref_texture_task, &j, NULL);
    for (uint32_t t = 0; rc == 0 && t < n; t++)
        if (j.rc[t] < 0) {
            *err = j.errs[t];
            rc = -1;
        }
    free(j.want);
    free(j.errs);
    free(j.rc);
    return rc;
}

/* Igehy 1999, "Tracing Ray Differentials": the footprint of a pixel on the surface is spanned by
 * the offsets to where the neighbouring pixels' rays meet the tangent plane at the hit. For a
 * pinhole camera those rays are exactly the camera rays through the pixel centres one to the right
 * and one down, and the hit triangle's plane is the tangent plane, so the differentials are finite
 * differences of the triangle's (perspective-correct) uv along that plane — what GL's dFdx/dFdy
 * give for the triangle's interpolated uv. */
void ref_hit_differentials(const ref_world *w, const gib_camera *cam, int width, int height,
                           int px, int py, ref_hit *h)
{
    h->has_duv = 0;
    if (!w->gs->uvs)
        return;
    const ref_tri *tr = &w->tris[h->prim];
    const uint32_t *ix = w->gs->indices + 3 * (size_t)w->rec_tri[h->prim];
    const float *p0 = w->gs->positions + 3 * (size_t)ix[0],
                *p1 = w->gs->positions + 3 * (size_t)ix[1],
                *p2 = w->gs->positions + 3 * (size_t)ix[2];
    const float *t0 = tr->uv[0], *t1 = tr->uv[1], *t2 = tr->uv[2];
    double e1[3], e2[3], nn[3];
    for (int k = 0; k < 3; k++) {
        e1[k] = (double)p1[k] - p0[k];
        e2[k] = (double)p2[k] - p0[k];
    }
    nn[0] = e1[1] * e2[2] - e1[2] * e2[1];
    nn[1] = e1[2] * e2[0] - e1[0] * e2[2];
    nn[2] = e1[0] * e2[1] - e1[1] * e2[0];
    double nn2 = nn[0] * nn[0] + nn[1] * nn[1] + nn[2] * nn[2];
    if (!(nn2 > 0.0))
        return;
    float uvn[2][2];
    for (int k = 0; k < 2; k++) {
        float o[3], d[3];
        gib_camera_ray(cam, width, height, (float)px + 0.5f + (k == 0), (float)py + 0.5f + (k == 1),
                       o, d);
        double dn = d[0] * nn[0] + d[1] * nn[1] + d[2] * nn[2];
        double on = (p0[0] - o[0]) * nn[0] + (p0[1] - o[1]) * nn[1] + (p0[2] - o[2]) * nn[2];
        if (dn == 0.0)
            return;
        double t = on / dn, q[3], c1[3], c2[3];
        if (!(t > 0.0) || !isfinite(t))
            return; /* the neighbour's ray leaves the plane behind the eye: no footprint */
        for (int j = 0; j < 3; j++)
            q[j] = (double)o[j] + t * d[j] - p0[j];
        /* barycentrics of q: b1 = ((q x e2) . n) / |n|^2, b2 = ((e1 x q) . n) / |n|^2 */
        c1[0] = q[1] * e2[2] - q[2] * e2[1];
        c1[1] = q[2] * e2[0] - q[0] * e2[2];
        c1[2] = q[0] * e2[1] - q[1] * e2[0];
        c2[0] = e1[1] * q[2] - e1[2] * q[1];
        c2[1] = e1[2] * q[0] - e1[0] * q[2];
        c2[2] = e1[0] * q[1] - e1[1] * q[0];
        double b1 = (c1[0] * nn[0] + c1[1] * nn[1] + c1[2] * nn[2]) / nn2;
        double b2 = (c2[0] * nn[0] + c2[1] * nn[1] + c2[2] * nn[2]) / nn2;
        double b0 = 1.0 - b1 - b2;
        for (int j = 0; j < 2; j++)
            uvn[k][j] = (float)(b0 * t0[j] + b1 * t1[j] + b2 * t2[j]);
    }
    h->duv[0] = uvn[0][0] - h->uv[0];
    h->duv[1] = uvn[0][1] - h->uv[1];
    h->duv[2] = uvn[1][0] - h->uv[0];
    h->duv[3] = uvn[1][1] - h->uv[1];
    h->has_duv = isfinite(h->duv[0]) && isfinite(h->duv[1]) && isfinite(h->duv[2]) &&
                 isfinite(h->duv[3]);
}
