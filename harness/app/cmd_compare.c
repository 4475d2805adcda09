/* gibench compare — metrics between two EXR images, like idiff: exit 0 when within the --fail
 * thresholds, 1 when not (or when any pixel is NaN/Inf), 2 on bad usage or unreadable files. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app.h"
#include "options.h"

static const gib_command_doc doc = {
    "compare", "REF.exr TEST.exr [options]",
    "Prints RMSE, relative RMSE, PSNR and SSIM (Wang et al. 2004 for SSIM) of TEST against REF.\n"
    "--exposure scales the linear images before the SSIM channel (default: the reference's\n"
    "`exposure` header attribute, else 1). --json prints one JSON object.\n"
    "Exit status: 0 within thresholds, 1 above a threshold or any non-finite pixel, 2 on error.\n"};

static void json_num(const char *key, double v, int last)
{
    if (isfinite(v))
        printf("\"%s\": %.9g%s", key, v, last ? "" : ", ");
    else
        printf("\"%s\": %s%s", key, isnan(v) ? "null" : v > 0 ? "1e999" : "-1e999",
               last ? "" : ", ");
}

typedef struct compare_opts {
    const char *paths[2], *map;
    double exposure, fail_rmse, fail_rel, fail_ssim;
    int json;
} compare_opts;

/* Returns -1 to go on, 0 after --help, 2 on bad usage. */
static int parse_compare_options(int argc, char **argv, compare_opts *o)
{
    *o = (compare_opts){.exposure = -1, .fail_rmse = INFINITY, .fail_rel = INFINITY,
                        .fail_ssim = -INFINITY};
    const gib_option opts[] = {
        GIB_OPTION_FLOAT("--exposure", &o->exposure, 0, 1e30, "E",
                         "scale before SSIM (default: REF's exposure attribute, else 1)"),
        GIB_OPTION_FLAG("--json", &o->json, "one JSON object"),
        GIB_OPTION_TEXT("--map", &o->map, "ERR.png", "write the false-colour error map"),
        GIB_OPTION_FLOAT("--fail-rmse", &o->fail_rmse, 0, 1e30, "X", "exit 1 above this RMSE"),
        GIB_OPTION_FLOAT("--fail-rel-rmse", &o->fail_rel, 0, 1e30, "X",
                         "exit 1 above this relative RMSE"),
        GIB_OPTION_FLOAT("--fail-ssim", &o->fail_ssim, -1, 1, "X", "exit 1 below this SSIM"),
        {0}};
    int np = 0;
    int rc = gib_options_parse(&doc, opts, argc, argv, o->paths, &np, 2);
    if (rc != GIB_OPTIONS_PROCEED)
        return rc;
    if (np != 2) {
        fputs("gibench compare: needs REF.exr and TEST.exr\n", stderr);
        gib_options_usage(stderr, &doc, opts);
        return 2;
    }
    return -1;
}

static void print_json(const gib_metrics *m, double noise, const gib_rmse_bounds *b, int fail)
{
    printf("{");
    json_num("rmse", m->rmse, 0);
    json_num("rel_rmse", m->rel_rmse, 0);
    json_num("mean_ratio", m->mean_ratio, 0);
    json_num("black_rmse", m->black_rmse, 0);
    json_num("rmse_over_black", m->rmse / m->black_rmse, 0);
    json_num("ref_noise_rmse", noise, 0);
    json_num("rmse_denoised", b->denoised, 0);
    json_num("rmse_lo", b->lo, 0);
    json_num("rmse_hi", b->hi, 0);
    json_num("psnr", m->psnr, 0);
    json_num("ssim", m->ssim, 0);
    json_num("flip", m->flip, 0);
    json_num("hdrflip", m->hdrflip, 0);
    printf("\"nonfinite\": %ld, \"pass\": %s}\n", m->nonfinite, fail ? "false" : "true");
}

static void print_text(const gib_metrics *m, double noise, int noise_known,
                       const gib_rmse_bounds *b, int fail)
{
    printf("rmse %.6g  rel_rmse %.6g  psnr %.3f dB  ssim %.6f  flip %.6f  hdrflip %.6f  "
           "nonfinite %ld  -> %s\n",
           m->rmse, m->rel_rmse, m->psnr, m->ssim, m->flip, m->hdrflip, m->nonfinite,
           fail ? "FAIL" : "PASS");
    printf("mean %.4g of the reference's\n", m->mean_ratio);
    printf("black image: rmse %.6g; this image scores %.4g of it%s\n", m->black_rmse,
           m->rmse / m->black_rmse, m->rmse > m->black_rmse ? " (WORSE THAN BLACK)" : "");
    printf("reference noise rmse %.6g%s: rmse without it %.6g, 95%% interval [%.6g, %.6g]\n",
           noise, noise_known ? "" : " (not a gibench reference: taken as exact)",
           b->denoised, b->lo, b->hi);
}

/* Scores test against ref and prints the result. Returns the exit status. */
static int score(const compare_opts *o, const gib_image *ref, const gib_image *test,
                 const char *noise_attr)
{
    /* A reference of ours names its own noise; any other image is taken as exact. */
    const double noise = noise_attr ? strtod(noise_attr, NULL) : 0.0;
    gib_score s;
    gib_error err = {0};
    if (gib_score_image(ref, noise, test, (float)o->exposure, NULL, NULL, &s, &err) < 0) {
        fprintf(stderr, "gibench compare: %s vs %s: %s\n", o->paths[0], o->paths[1], err.msg);
        return 2;
    }
    const gib_metrics m = s.m;
    const gib_rmse_bounds b = s.rmse;
    int fail = m.nonfinite > 0 || !(m.rmse <= o->fail_rmse) || !(m.rel_rmse <= o->fail_rel) ||
               !(m.ssim >= o->fail_ssim);
    if (o->json)
        print_json(&m, noise, &b, fail);
    else
        print_text(&m, noise, noise_attr != NULL, &b, fail);
    if (o->map && gib_png_write_error_map(o->map, ref, test, 0.0f, &err) < 0) {
        fprintf(stderr, "gibench compare: %s\n", err.msg);
        return 2;
    }
    return fail;
}

int gib_cmd_compare(int argc, char **argv)
{
    compare_opts o;
    int rc = parse_compare_options(argc, argv, &o);
    if (rc >= 0)
        return rc;
    gib_image ref = {0}, test = {0};
    gib_kv *attrs = NULL;
    int nattrs = 0;
    gib_error err = {0};
    if (gib_exr_read(o.paths[0], &ref, &attrs, &nattrs, &err) < 0 ||
        gib_exr_read(o.paths[1], &test, NULL, NULL, &err) < 0) {
        fprintf(stderr, "gibench compare: %s\n", err.msg);
        gib_image_free(&ref);
        free(attrs);
        return 2;
    }
    if (o.exposure < 0) {
        const char *e = gib_kv_get(attrs, nattrs, "exposure");
        o.exposure = e ? strtod(e, NULL) : 1.0;
    }
    const char *noise_attr = gib_kv_get(attrs, nattrs, "noise_rmse");
    int status = score(&o, &ref, &test, noise_attr);
    free(attrs);
    gib_image_free(&ref);
    gib_image_free(&test);
    return status;
}
