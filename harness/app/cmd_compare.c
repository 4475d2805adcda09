/* gibench compare — metrics between two EXR images, like idiff: exit 0 when within the --fail
 * thresholds, 1 when not (or when any pixel is NaN/Inf), 2 on bad usage or unreadable files. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app.h"

static const char help[] =
    "usage: gibench compare REF.exr TEST.exr [--exposure E] [--json] [--map ERR.png]\n"
    "                       [--fail-rmse X] [--fail-rel-rmse X] [--fail-ssim X]\n"
    "\n"
    "Prints RMSE, relative RMSE, PSNR and SSIM (Wang et al. 2004 for SSIM) of TEST against REF.\n"
    "--exposure scales the linear images before the SSIM channel (default: the reference's\n"
    "`exposure` header attribute, else 1). --json prints one JSON object.\n"
    "Exit status: 0 within thresholds, 1 above a threshold or any non-finite pixel, 2 on error.\n";

static void json_num(const char *key, double v, int last)
{
    if (isfinite(v))
        printf("\"%s\": %.9g%s", key, v, last ? "" : ", ");
    else
        printf("\"%s\": %s%s", key, isnan(v) ? "null" : v > 0 ? "1e999" : "-1e999",
               last ? "" : ", ");
}

int gib_cmd_compare(int argc, char **argv)
{
    const char *paths[2] = {NULL, NULL}, *map = NULL;
    double exposure = -1, fail_rmse = INFINITY, fail_rel = INFINITY, fail_ssim = -INFINITY;
    int json = 0, np = 0;
    gib_error err = {0};
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        int rc = 0;
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            fputs(help, stdout);
            return 0;
        } else if (!strcmp(a, "--json")) {
            json = 1;
            continue;
        } else if (a[0] != '-' || !a[1]) {
            if (np == 2) {
                fprintf(stderr, "gibench compare: expected two images, got a third '%s'\n", a);
                return 2;
            }
            paths[np++] = a;
            continue;
        }
        if (!v) {
            fprintf(stderr, "gibench compare: option %s needs a value\n%s", a, help);
            return 2;
        }
        i++;
        if (!strcmp(a, "--map")) map = v;
        else if (!strcmp(a, "--exposure")) rc = gib_parse_float(a, v, 0, 1e30, &exposure, &err);
        else if (!strcmp(a, "--fail-rmse")) rc = gib_parse_float(a, v, 0, 1e30, &fail_rmse, &err);
        else if (!strcmp(a, "--fail-rel-rmse")) rc = gib_parse_float(a, v, 0, 1e30, &fail_rel, &err);
        else if (!strcmp(a, "--fail-ssim")) rc = gib_parse_float(a, v, -1, 1, &fail_ssim, &err);
        else {
            fprintf(stderr, "gibench compare: unknown option '%s'\n%s", a, help);
            return 2;
        }
        if (rc < 0) {
            fprintf(stderr, "gibench compare: %s\n", err.msg);
            return 2;
        }
    }
    if (np != 2) {
        fprintf(stderr, "gibench compare: needs REF.exr and TEST.exr\n%s", help);
        return 2;
    }
    gib_image ref = {0}, test = {0};
    gib_kv *attrs = NULL;
    int nattrs = 0;
    if (gib_exr_read(paths[0], &ref, &attrs, &nattrs, &err) < 0 ||
        gib_exr_read(paths[1], &test, NULL, NULL, &err) < 0) {
        fprintf(stderr, "gibench compare: %s\n", err.msg);
        gib_image_free(&ref);
        free(attrs);
        return 2;
    }
    if (exposure < 0) {
        const char *e = gib_kv_get(attrs, nattrs, "exposure");
        exposure = e ? strtod(e, NULL) : 1.0;
    }
    /* A reference of ours names its own noise; any other image is taken as exact. */
    const char *noise_attr = gib_kv_get(attrs, nattrs, "noise_rmse");
    const double noise = noise_attr ? strtod(noise_attr, NULL) : 0.0;
    free(attrs);
    gib_metrics m;
    int status = 0;
    if (gib_metrics_compute(&ref, &test, (float)exposure, &m, &err) < 0 ||
        gib_score_flip(&ref, &test, (float)exposure, NULL, &m, &err) < 0) {
        fprintf(stderr, "gibench compare: %s vs %s: %s\n", paths[0], paths[1], err.msg);
        status = 2;
    } else {
        int fail = m.nonfinite > 0 || !(m.rmse <= fail_rmse) || !(m.rel_rmse <= fail_rel) ||
                   !(m.ssim >= fail_ssim);
        gib_rmse_bounds b;
        gib_rmse_interval(m.rmse, noise, (long)ref.width * ref.height, &b);
        if (json) {
            printf("{");
            json_num("rmse", m.rmse, 0);
            json_num("rel_rmse", m.rel_rmse, 0);
            json_num("mean_ratio", m.mean_ratio, 0);
            json_num("black_rmse", m.black_rmse, 0);
            json_num("rmse_over_black", m.rmse / m.black_rmse, 0);
            json_num("ref_noise_rmse", noise, 0);
            json_num("rmse_denoised", b.denoised, 0);
            json_num("rmse_lo", b.lo, 0);
            json_num("rmse_hi", b.hi, 0);
            json_num("psnr", m.psnr, 0);
            json_num("ssim", m.ssim, 0);
            json_num("flip", m.flip, 0);
            json_num("hdrflip", m.hdrflip, 0);
            printf("\"nonfinite\": %ld, \"pass\": %s}\n", m.nonfinite, fail ? "false" : "true");
        } else {
            printf("rmse %.6g  rel_rmse %.6g  psnr %.3f dB  ssim %.6f  flip %.6f  hdrflip %.6f  "
                   "nonfinite %ld  -> %s\n",
                   m.rmse, m.rel_rmse, m.psnr, m.ssim, m.flip, m.hdrflip, m.nonfinite,
                   fail ? "FAIL" : "PASS");
            printf("mean %.4g of the reference's\n", m.mean_ratio);
            printf("black image: rmse %.6g; this image scores %.4g of it%s\n", m.black_rmse,
                   m.rmse / m.black_rmse, m.rmse > m.black_rmse ? " (WORSE THAN BLACK)" : "");
            printf("reference noise rmse %.6g%s: rmse without it %.6g, 95%% interval [%.6g, %.6g]\n",
                   noise, noise_attr ? "" : " (not a gibench reference: taken as exact)",
                   b.denoised, b.lo, b.hi);
        }
        status = fail;
        if (map && gib_png_write_error_map(map, &ref, &test, 0.0f, &err) < 0) {
            fprintf(stderr, "gibench compare: %s\n", err.msg);
            status = 2;
        }
    }
    gib_image_free(&ref);
    gib_image_free(&test);
    return status;
}
