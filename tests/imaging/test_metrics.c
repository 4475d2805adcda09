/* Unit tests for harness/imaging: metrics, sRGB, EXR round trip, PNG output, error messages.
 * Usage: test_metrics [output_dir]. Each check prints expected, measured and tolerance; the exit
 * status is the number of failed checks (capped). */
#include "tests/common/check.h"
#include "harness/imaging/image.h"
#include "harness/imaging/metrics.h"
#include "harness/imaging/oiio_shim.h"

#include <openexr.h>

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static int failures;



static uint32_t rng_state = 12345u;
static uint32_t rng(void)
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 17;
    rng_state ^= rng_state << 5;
    return rng_state;
}

/* Multiples of 1/1024 in [0, 4): adding 0.125 to them is exact in float, so an offset image has
 * an RMSE of exactly 0.125 and the test can demand equality. */
static void fill_grid(gib_image *img)
{
    size_t n = (size_t)img->width * img->height * img->channels;
    for (size_t i = 0; i < n; ++i)
        img->px[i] = (float)(rng() % 4096u) / 1024.0f;
}

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec / 1e6;
}

static void test_srgb(void)
{
    const char *why = "IEC 61966-2-1 closed form, float rounding";
    CHECK_NEAR("srgb_encode(0)", 0.0, gib_srgb_encode(0.0f), 0.0, "exact");
    CHECK_NEAR("srgb_encode(1)", 1.0, gib_srgb_encode(1.0f), 0.0, "exact");
    CHECK_NEAR("srgb_encode(-1) clamps", 0.0, gib_srgb_encode(-1.0f), 0.0, "exact");
    CHECK_NEAR("srgb_encode(5) clamps", 1.0, gib_srgb_encode(5.0f), 0.0, "exact");
    CHECK_NEAR("srgb_encode(NaN) -> 0", 0.0, gib_srgb_encode(NAN), 0.0, "exact");
    CHECK_NEAR("srgb_encode(0.0031308)", 0.0404500, gib_srgb_encode(0.0031308f), 1e-6, why);
    CHECK_NEAR("srgb_encode(0.5)", 1.055 * pow(0.5, 1 / 2.4) - 0.055, gib_srgb_encode(0.5f), 1e-6,
               why);
    CHECK_NEAR("srgb_encode(0.18)", 0.4613561, gib_srgb_encode(0.18f), 1e-6, why);
}

static void test_metrics(void)
{
    gib_error err = {0};
    gib_image ref, test;
    if (gib_image_alloc(&ref, 64, 48, 3, &err) || gib_image_alloc(&test, 64, 48, 4, &err)) {
        CHECK_TRUE("alloc", 0, err.msg);
        return;
    }
    fill_grid(&ref);
    size_t n = (size_t)ref.width * ref.height;
    for (size_t i = 0; i < n; ++i) {
        for (int k = 0; k < 3; ++k)
            test.px[i * 4 + k] = ref.px[i * 3 + k];
        test.px[i * 4 + 3] = 1.0f;
    }
    gib_metrics m;
    int rc = gib_metrics_compute(&ref, &test, 1.0f, &m, &err);
    CHECK_TRUE("identical: compute returns 0", rc == 0, rc ? err.msg : "");
    CHECK_NEAR("identical: rmse", 0.0, m.rmse, 0.0, "exact: every difference is 0");
    CHECK_NEAR("identical: ssim", 1.0, m.ssim, 1e-12, "every map value is 1; double rounding");
    CHECK_TRUE("identical: psnr is +inf", isinf(m.psnr) && m.psnr > 0, "20 log10(peak / 0)");
    CHECK_NEAR("identical: nonfinite", 0, (double)m.nonfinite, 0, "exact");

    const double c = 0.125;
    double sum = 0, peak = 0;
    for (size_t i = 0; i < n; ++i) {
        for (int k = 0; k < 3; ++k) {
            test.px[i * 4 + k] = ref.px[i * 3 + k] + (float)c;
            sum += ref.px[i * 3 + k];
            peak = fmax(peak, ref.px[i * 3 + k]);
        }
        test.px[i * 4 + 3] = 123.0f; /* alpha must be ignored */
    }
    double mean = sum / (double)(n * 3);
    gib_metrics_compute(&ref, &test, 1.0f, &m, &err);
    CHECK_NEAR("offset 0.125: rmse", c, m.rmse, 0.0, "exact: grid values + 2^-3 are exact floats");
    CHECK_NEAR("offset 0.125: ref_mean", mean, m.ref_mean, 1e-12, "double summation order");
    CHECK_NEAR("offset 0.125: rel_rmse = c / mean", c / mean, m.rel_rmse, 1e-12,
               "double summation order");
    CHECK_NEAR("offset 0.125: psnr = 20 log10(peak / c)", 20 * log10(peak / c), m.psnr, 1e-9,
               "log10 rounding");
    CHECK_TRUE("offset 0.125: 0 < ssim < 1", m.ssim > 0 && m.ssim < 1, "structure is kept");

    /* Broken samples are counted (test and reference) and excluded, not averaged. */
    test.px[5 * 4 + 1] = NAN;
    test.px[200 * 4 + 0] = INFINITY;
    ref.px[300 * 3 + 2] = -INFINITY;
    rc = gib_metrics_compute(&ref, &test, 1.0f, &m, &err);
    CHECK_TRUE("nonfinite: compute returns 0", rc == 0, rc ? err.msg : "");
    CHECK_NEAR("nonfinite: count (NaN, +Inf, ref -Inf)", 3, (double)m.nonfinite, 0, "exact");
    CHECK_NEAR("nonfinite: rmse over finite pairs", c, m.rmse, 0.0, "exact, as above");
    CHECK_TRUE("nonfinite: ssim finite", isfinite(m.ssim), "NaN/Inf encode to 0/1 in the channel");
    CHECK_NEAR("count_nonfinite(test)", 2, (double)gib_image_count_nonfinite(&test), 0, "exact");

    gib_image small;
    gib_image_alloc(&small, 10, 48, 3, &err);
    rc = gib_metrics_compute(&ref, &small, 1.0f, &m, &err);
    CHECK_TRUE("size mismatch is an error", rc != 0 && strstr(err.msg, "size mismatch"), err.msg);
    gib_image_free(&small);
    float g[10 * 10] = {0};
    CHECK_TRUE("ssim of a 10x10 image is NaN", isnan(gib_ssim_gray(g, g, 10, 10)),
               "no valid window");

    gib_image_free(&ref);
    gib_image_free(&test);
}

static void test_ssim_speed(void)
{
    const int w = 512, h = 512;
    float *a = malloc(sizeof(float) * w * h), *b = malloc(sizeof(float) * w * h);
    for (int i = 0; i < w * h; ++i) {
        a[i] = (float)(rng() % 1000u) / 1000.0f;
        b[i] = 0.5f * a[i] + 0.5f * (float)(rng() % 1000u) / 1000.0f;
    }
    double best = 1e30, s = 0;
    for (int r = 0; r < 3; ++r) { /* best of 3: a busy machine should not fail the test */
        double t0 = now_ms();
        s = gib_ssim_gray(a, b, w, h);
        best = fmin(best, now_ms() - t0);
    }
    /* Timing is reported, never asserted: the machines are shared and noisy. The check is that a
     * large image gives a valid SSIM. */
    char buf[128];
    snprintf(buf, sizeof buf, "512x512 in %.1f ms (best of 3), ssim %.4f", best, s);
    CHECK_TRUE("ssim 512x512 is finite and in [-1, 1]", isfinite(s) && s >= -1 && s <= 1, buf);
    free(a);
    free(b);
}

static void test_exr(const char *dir)
{
    gib_error err = {0};
    char path[1024];
    snprintf(path, sizeof path, "%s/imaging_roundtrip.exr", dir);
    for (int channels = 1; channels <= 4; ++channels) {
        if (channels == 2)
            continue;
        gib_image img, back;
        gib_image_alloc(&img, 37, 29, channels, &err); /* 29 rows: a partial last ZIP chunk */
        size_t n = (size_t)img.width * img.height * channels;
        for (size_t i = 0; i < n; ++i) {
            uint32_t bits = rng();
            memcpy(&img.px[i], &bits, 4);
            if (!isfinite(img.px[i])) /* keep NaN payloads out of a bit-exact comparison */
                img.px[i] = (float)(bits % 1000u) * -0.001f;
        }
        img.px[0] = 1e-40f; /* a denormal must survive too */
        img.px[1] = 65504.5f;
        gib_kv attrs[2] = {{"gib.scene", "cornell box"}, {"gib.technique", "lpv cascades=3"}};
        int rc = gib_exr_write(path, &img, attrs, 2, &err);
        char what[80];
        snprintf(what, sizeof what, "exr %d-channel write", channels);
        CHECK_TRUE(what, rc == 0, rc ? err.msg : path);
        gib_kv *kv = NULL;
        int nkv = 0;
        rc = gib_exr_read(path, &back, &kv, &nkv, &err);
        snprintf(what, sizeof what, "exr %d-channel read", channels);
        CHECK_TRUE(what, rc == 0, rc ? err.msg : path);
        if (rc != 0) {
            gib_image_free(&img);
            continue;
        }
        int same = back.width == img.width && back.height == img.height && back.channels == 3;
        size_t diff = 0;
        for (size_t p = 0; same && p < (size_t)img.width * img.height; ++p)
            for (int k = 0; k < 3; ++k)
                diff += memcmp(&back.px[p * 3 + k], &img.px[p * channels + (channels == 1 ? 0 : k)],
                               4) != 0;
        snprintf(what, sizeof what, "exr %d-channel pixels bit-exact", channels);
        char buf[128];
        snprintf(buf, sizeof buf, "%zu differing samples, size %dx%dx%d", diff, back.width,
                 back.height, back.channels);
        CHECK_TRUE(what, same && diff == 0, buf);
        const char *s = gib_kv_get(kv, nkv, "gib.scene");
        const char *t = gib_kv_get(kv, nkv, "gib.technique");
        snprintf(what, sizeof what, "exr %d-channel attributes", channels);
        snprintf(buf, sizeof buf, "gib.scene='%s' gib.technique='%s' (%d string attrs)",
                 s ? s : "(null)", t ? t : "(null)", nkv);
        CHECK_TRUE(what, s && t && !strcmp(s, "cornell box") && !strcmp(t, "lpv cascades=3"), buf);
        CHECK_TRUE("kv_get of an absent key is NULL", gib_kv_get(kv, nkv, "nope") == NULL, "");
        free(kv);
        gib_image_free(&back);
        gib_image_free(&img);
    }

    snprintf(path, sizeof path, "%s/does_not_exist/missing.exr", dir);
    gib_image img;
    int rc = gib_exr_read(path, &img, NULL, NULL, &err);
    CHECK_TRUE("missing exr: error names the file", rc != 0 && strstr(err.msg, path) != NULL,
               err.msg);
    gib_image_alloc(&img, 4, 4, 3, &err);
    rc = gib_exr_write(path, &img, NULL, 0, &err);
    gib_image_free(&img);
    CHECK_TRUE("unwritable exr: error names the file", rc != 0 && strstr(err.msg, path) != NULL,
               err.msg);
}

/* Writes a 3x2 RGB half-float EXR with the core API, as another renderer would, so the half
 * conversion path of gib_exr_read is tested. Half bit patterns: 0.5, 1, -2, 65504, 2^-24, 0. */
static const uint16_t half_bits[6] = {0x3800, 0x3C00, 0xC000, 0x7BFF, 0x0001, 0x0000};
static const float half_vals[6] = {0.5f, 1.0f, -2.0f, 65504.0f, 5.9604644775390625e-08f, 0.0f};

static int write_half_exr(const char *path)
{
    uint16_t px[2][3][3]; /* row, column, channel: channel k of pixel p is half_bits[(p + k) % 6] */
    for (int p = 0; p < 6; ++p)
        for (int k = 0; k < 3; ++k)
            px[p / 3][p % 3][k] = half_bits[(p + k) % 6];
    exr_context_t ctxt = NULL;
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    int part = 0;
    exr_result_t rv = exr_start_write(&ctxt, path, EXR_WRITE_FILE_DIRECTLY, &init);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_add_part(ctxt, "", EXR_STORAGE_SCANLINE, &part);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_initialize_required_attr_simple(ctxt, part, 3, 2, EXR_COMPRESSION_NONE);
    const char *names[3] = {"R", "G", "B"};
    for (int k = 0; k < 3 && rv == EXR_ERR_SUCCESS; ++k)
        rv = exr_add_channel(ctxt, part, names[k], EXR_PIXEL_HALF, EXR_PERCEPTUALLY_LINEAR, 1, 1);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_write_header(ctxt);
    for (int y = 0; y < 2 && rv == EXR_ERR_SUCCESS; ++y) { /* uncompressed: 1 line per chunk */
        exr_chunk_info_t cinfo;
        exr_encode_pipeline_t enc;
        memset(&enc, 0, sizeof enc);
        rv = exr_write_scanline_chunk_info(ctxt, part, y, &cinfo);
        if (rv == EXR_ERR_SUCCESS)
            rv = exr_encoding_initialize(ctxt, part, &cinfo, &enc);
        for (int c = 0; rv == EXR_ERR_SUCCESS && c < enc.channel_count; ++c) {
            int k = enc.channels[c].channel_name[0] == 'R' ? 0
                    : enc.channels[c].channel_name[0] == 'G' ? 1 : 2;
            enc.channels[c].user_pixel_stride = 6;
            enc.channels[c].user_line_stride = 18;
            enc.channels[c].user_data_type = EXR_PIXEL_HALF;
            enc.channels[c].user_bytes_per_element = 2;
            enc.channels[c].encode_from_ptr = (const uint8_t *)&px[y][0][k];
        }
        if (rv == EXR_ERR_SUCCESS)
            rv = exr_encoding_choose_default_routines(ctxt, part, &enc);
        if (rv == EXR_ERR_SUCCESS)
            rv = exr_encoding_run(ctxt, part, &enc);
        exr_encoding_destroy(ctxt, &enc);
    }
    exr_result_t frv = exr_finish(&ctxt);
    return rv == EXR_ERR_SUCCESS && frv == EXR_ERR_SUCCESS ? 0 : -1;
}

static void test_exr_half(const char *dir)
{
    char path[1024], buf[160];
    snprintf(path, sizeof path, "%s/imaging_half.exr", dir);
    CHECK_TRUE("half exr written with the core API", write_half_exr(path) == 0, path);
    gib_error err = {0};
    gib_image img;
    int rc = gib_exr_read(path, &img, NULL, NULL, &err);
    CHECK_TRUE("half exr read", rc == 0 && img.width == 3 && img.height == 2, rc ? err.msg : path);
    if (rc != 0)
        return;
    int bad = 0;
    for (int p = 0; p < 6; ++p)
        for (int k = 0; k < 3; ++k)
            bad += img.px[p * 3 + k] != half_vals[(p + k) % 6];
    snprintf(buf, sizeof buf, "%d of 18 samples differ; first pixel (%g, %g, %g)", bad, img.px[0],
             img.px[1], img.px[2]);
    CHECK_TRUE("half exr values exact (row 0 on top)", bad == 0, buf);
    gib_image_free(&img);
}

static void test_png(const char *dir)
{
    gib_error err = {0};
    char path[1024], buf[256];
    gib_image img, other;
    gib_image_alloc(&img, 16, 8, 3, &err);
    gib_image_alloc(&other, 16, 8, 3, &err);
    for (int i = 0; i < 16 * 8 * 3; ++i) {
        img.px[i] = 0.25f; /* exposure 2 -> 0.5 linear -> sRGB 0.7354 -> 188 */
        other.px[i] = 0.25f + 0.01f * (float)(i % 7);
    }
    img.px[3] = 10.0f; /* over range: must clamp to 255 */
    snprintf(path, sizeof path, "%s/imaging_preview.png", dir);
    int rc = gib_png_write_preview(path, &img, 2.0f, &err);
    CHECK_TRUE("png preview write", rc == 0, rc ? err.msg : path);
    int w = 0, h = 0;
    float *rgba = NULL;
    rc = gib_oiio_read_rgba(path, &w, &h, &rgba, buf, (int)sizeof buf);
    CHECK_TRUE("png preview read back (OIIO shim)", rc == 0 && w == 16 && h == 8, rc ? buf : path);
    if (rc == 0) {
        CHECK_NEAR("png preview: 0.25 at exposure 2", 188.0 / 255.0, rgba[0], 1e-6, "8-bit");
        CHECK_NEAR("png preview: 10.0 clamps", 1.0, rgba[4], 1e-6, "8-bit");
        CHECK_NEAR("png preview: alpha filled with 1", 1.0, rgba[3], 0.0, "exact");
    }
    free(rgba);

    other.px[5 * 3 + 1] = NAN;
    snprintf(path, sizeof path, "%s/imaging_errmap.png", dir);
    rc = gib_png_write_error_map(path, &img, &other, 0.0f, &err);
    CHECK_TRUE("error map write", rc == 0, rc ? err.msg : path);
    rgba = NULL;
    rc = gib_oiio_read_rgba(path, &w, &h, &rgba, buf, (int)sizeof buf);
    CHECK_TRUE("error map read back", rc == 0 && w == 16 && h == 8, rc ? buf : path);
    if (rc == 0) {
        snprintf(buf, sizeof buf, "pixel 5 = (%g, %g, %g)", rgba[20], rgba[21], rgba[22]);
        CHECK_TRUE("error map: NaN pixel is magenta",
                   rgba[20] == 1.0f && rgba[21] == 0.0f && rgba[22] == 1.0f, buf);
    }
    free(rgba);

    snprintf(path, sizeof path, "%s/no_such_dir/x.png", dir);
    rc = gib_png_write_preview(path, &img, 1.0f, &err);
    CHECK_TRUE("unwritable png: error names the file", rc != 0 && strstr(err.msg, path) != NULL,
               err.msg);
    rc = gib_oiio_read_rgba(path, &w, &h, &rgba, buf, (int)sizeof buf);
    CHECK_TRUE("missing image read: error names the file", rc != 0 && strstr(buf, path) != NULL,
               buf);

    /* A 69-byte PNG whose header claims 60000x60000 RGBA (58 GB as floats): refused by size before
     * any pixel is allocated. The IHDR and IDAT are valid, CRCs included. */
    static const unsigned char huge_png[] = {
        0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44,
        0x52, 0x00, 0x00, 0xea, 0x60, 0x00, 0x00, 0xea, 0x60, 0x08, 0x06, 0x00, 0x00, 0x00, 0x80,
        0xd2, 0x75, 0x42, 0x00, 0x00, 0x00, 0x0c, 0x49, 0x44, 0x41, 0x54, 0x78, 0x9c, 0x63, 0x60,
        0xa0, 0x3d, 0x00, 0x00, 0x00, 0x64, 0x00, 0x01, 0x86, 0x64, 0x3c, 0x35, 0x00, 0x00, 0x00,
        0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};
    snprintf(path, sizeof path, "%s/imaging_huge.png", dir);
    FILE *f = fopen(path, "wb");
    if (f) {
        fwrite(huge_png, 1, sizeof huge_png, f);
        fclose(f);
    }
    rc = gib_oiio_read_rgba(path, &w, &h, &rgba, buf, (int)sizeof buf);
    CHECK_TRUE("60000x60000 PNG header: refused by size, naming the file",
               rc != 0 && strstr(buf, path) && strstr(buf, "60000x60000") && strstr(buf, "limit"),
               buf);
    gib_image_free(&img);
    gib_image_free(&other);
}

int main(int argc, char **argv)
{
    const char *dir = argc > 1 ? argv[1] : ".";
    test_srgb();
    test_metrics();
    test_ssim_speed();
    test_exr(dir);
    test_exr_half(dir);
    test_png(dir);
    printf("%d check(s) failed\n", failures);
    return failures > 100 ? 100 : failures;
}
