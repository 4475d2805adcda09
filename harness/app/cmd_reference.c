/* gibench reference — renders one light-transport component with the Embree path tracer and
 * writes it as EXR with its metadata (and a PNG preview beside it), directly (--out) or through
 * the reference cache (--cache DIR, --force to render again); or a list of components of one view
 * together (gib_reference_render_set), one file or cache entry each. */
#include <limits.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

#include "harness/base/cone_set.h"
#include "app.h"
#include "options.h"

static const gib_command_doc doc = {
    "reference", "--scene S --component C[:N][,C[:N]...] (--out F.exr | --cache DIR) [options]",
    "Components (paths in Heckbert notation, reference/reference.h):\n"
    "  ao        ambient occlusion within --dmax (default, 0 and inf: unbounded); --obscurance 1\n"
    "            weights an occluder at distance d by min(d / dmax, 1) (Zhukov et al. 1998; needs\n"
    "            a finite --dmax)\n"
    "  direct    L D E, L S E            indirect  L D D E         glossy  L D S E\n"
    "  caustic   L S+ D E with at most --max-specular S vertices (default 1), light traced\n"
    "  full      all paths of at most --max-depth vertices (default 8), Russian roulette from\n"
    "            --min-depth (default 3; none when it is not below --max-depth)\n"
    "  higher    what full has beyond direct + indirect + glossy + caustic\n"
    "  albedo, normal, depth   auxiliary images of the visible point\n"
    "  indirect --cone I (0-5): only the cap of diffuse cone I of the cone techniques' set (one\n"
    "            along the normal, five 60 degrees from it; harness/base/cone_set.h) with\n"
    "            --cone-aperture DEG (default 60): rho_d times the cap's mean radiance, what\n"
    "            `lrsm` and `vct` render with --param cone=I\n"
    "\n"
    "A list of components (--component direct,indirect:64,glossy) renders them together from\n"
    "one world and one primary ray a pixel, each with its own spp (N, else --spp) and rounds,\n"
    "each image the bits of its render alone: one cache entry each (the key a request of it\n"
    "alone has), or with --out F.exr one file F.C.exr each (and --stderr likewise).\n"
    "\n"
    "--spp N (default 16) is the sample count, or with --target-noise X the first round's:\n"
    "rounds are added until the noise RMSE is at most X times the image mean, or --max-spp\n"
    "(default 65536) is reached. Random components need spp >= 2 (the variance of one sample is\n"
    "unknown); deterministic ones (direct with only point,\n"
    "spot and directional lights - not with a sky -, the auxiliary images) take one sample.\n"
    "Ctrl-C during a --target-noise render, once a round is finished, stops at once and writes\n"
    "the rounds finished (header stop: interrupted; exit status 130; during the first round it\n"
    "ends the process). Through --cache they go beside the entry, not as it (they missed its\n"
    "target).\n"
    "The EXR header records component, parameters, spp, seconds, scene hash, renderer version,\n"
    "the cache key, the image's noise RMSE (standard error from the per-pixel variance), why\n"
    "sampling stopped, and a seal of pixels and header (a changed cache entry is rendered again).\n"
    "--stderr writes the standard error of each pixel, its header marked image: standard_error.\n"
    "--out and --stderr are EXR files, checked to be writable before rendering.\n"
    "--time T (seconds, default 0) renders a moving scene (scenes/FORMAT.md, Motion) as it is at\n"
    "T; the cache key and header include it. A static scene is the same at every T.\n"
    "--sampler picks the camera samples' numbers: sobol (default; Owen-scrambled Sobol, noise from\n"
    "8 independently scrambled batches) or random (PCG32, the renderer before version 6). With\n"
    "--out only: the cache holds sobol renders. The header records it.\n"
    "--strategies picks full's and higher's paths: auto (default; a pilot chooses per image),\n"
    "camera (camera paths with next-event estimation, the renderer before light vertices) or\n"
    "light-vertices (also a light vertex per sample, weighted by the balance heuristic). The\n"
    "cache key and header record it.\n"};

/* Ctrl-C: once a round is done, the first one asks the renderer to stop and keep the rounds
 * finished (reference.h, gib_ref_interrupt); before that, or a second time, it ends the process
 * as it would have. Not installed where the caller ignores SIGINT (a background job of a script,
 * nohup): that choice is kept. */
static gib_ref_interrupt interrupt_req;
static struct sigaction interrupt_prev;
static int interrupt_installed;

static void on_interrupt(int sig)
{
    if (atomic_load(&interrupt_req.rounds_done) > 0 &&
        atomic_exchange(&interrupt_req.requested, 1) == 0) {
        static const char msg[] = "\ngibench reference: interrupted: writing the rounds "
                                  "finished (Ctrl-C again to quit without them)\n";
        ssize_t wr = write(STDERR_FILENO, msg, sizeof msg - 1);
        (void)wr;
        return;
    }
    signal(sig, SIG_DFL);
    raise(sig);
}

static void interrupt_install(void)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_interrupt;
    sigemptyset(&sa.sa_mask);
    if (sigaction(SIGINT, NULL, &interrupt_prev) == 0 && interrupt_prev.sa_handler != SIG_IGN &&
        sigaction(SIGINT, &sa, NULL) == 0)
        interrupt_installed = 1;
}

/* After the render: SIGINT as the caller had it (the files are then written or not at all). */
static void interrupt_restore(void)
{
    if (interrupt_installed)
        sigaction(SIGINT, &interrupt_prev, NULL);
    interrupt_installed = 0;
}

/* The path with its folder resolved (gib_check_output has made sure the folder exists). */
#define RESOLVED_MAX (PATH_MAX + NAME_MAX + 2)
static void resolved_path(const char *path, char out[RESOLVED_MAX])
{
    char dir[PATH_MAX], real[PATH_MAX];
    const char *slash = strrchr(path, '/'), *base = slash ? slash + 1 : path;
    gib_path_folder(path, dir, sizeof dir);
    if (realpath(dir, real))
        snprintf(out, RESOLVED_MAX, "%s/%s", real, base);
    else
        snprintf(out, RESOLVED_MAX, "%s", path);
}

/* 1 when a and b name the same file: the same resolved path, or the same existing file. */
static int same_file(const char *a, const char *b)
{
    char ra[RESOLVED_MAX], rb[RESOLVED_MAX];
    struct stat sa, sb;
    resolved_path(a, ra);
    resolved_path(b, rb);
    return !strcmp(ra, rb) || (stat(a, &sa) == 0 && stat(b, &sb) == 0 &&
                               sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino);
}

static int write_png_beside(const char *exr, const gib_image *img, float exposure, gib_error *err)
{
    char png[4096];
    snprintf(png, sizeof png, "%s", exr);
    char *dot = strrchr(png, '.');
    if (dot && !strcasecmp(dot, ".exr"))
        *dot = 0;
    strncat(png, ".png", sizeof png - strlen(png) - 1);
    return gib_png_write_preview(png, img, exposure, err);
}

/* What the command line asks for. */
typedef struct ref_opts {
    const char *scene_name, *comp, *out, *cache, *se_out, *size;
    long spp, camera, seed, threads, obsc, max_depth, min_depth, max_spec, max_spp, cone;
    int sampler, strategies, force, quiet;
    double dmax, target, time, cone_aperture;
    int component, w, h; /* from comp and size (check_args) */
    /* --component C[:N],C[:N],...: a set of one view, rendered together (ncomp > 1, or a
     * component given its own spp); component is comps[0] */
    int ncomp, comps[GIB_REF_SET_MAX];
    long spps[GIB_REF_SET_MAX];
} ref_opts;

#define PROCEED GIB_OPTIONS_PROCEED /* parse_args, check_args: go on (else the exit status) */

/* --cone I: the cap of diffuse cone I (stored as I + 1: gib_ref_params.cone's 0 is the whole
 * hemisphere). */
static int parse_cone(const gib_option *o, const char *v, gib_error *err)
{
    long *cone = o->dest;
    if (gib_parse_int(o->name, v, 0, GIB_DIFFUSE_CONES - 1, cone, err) < 0)
        return -1;
    *cone += 1;
    return 0;
}

static int parse_sampler(const gib_option *o, const char *v, gib_error *err)
{
    if ((*(int *)o->dest = gib_ref_sampler_parse(v)) < 0)
        return gib_fail(err, "%s '%s': sobol or random", o->name, v);
    return 0;
}

static int parse_strategies(const gib_option *o, const char *v, gib_error *err)
{
    if ((*(int *)o->dest = gib_ref_strategies_parse(v)) < 0)
        return gib_fail(err, "%s '%s': auto, camera or light-vertices", o->name, v);
    return 0;
}

/* --dmax D: a length, or inf / unbounded. */
static int parse_dmax(const gib_option *o, const char *v, gib_error *err)
{
    if (!strcmp(v, "inf") || !strcmp(v, "unbounded")) {
        *(double *)o->dest = INFINITY;
        return 0;
    }
    return gib_parse_float(o->name, v, 0, 1e30, o->dest, err);
}

static int parse_args(int argc, char **argv, ref_opts *o)
{
    const gib_option opts[] = {
        GIB_OPTION_TEXT("--scene", &o->scene_name, "S", "the scene (gibench list)"),
        GIB_OPTION_TEXT("--component", &o->comp, "C[:N][,C[:N]...]",
                        "the component (below); a list renders them together, N its spp"),
        GIB_OPTION_INT("--spp", &o->spp, 1, 1 << 24, "N", "samples per pixel (default 16)"),
        GIB_OPTION_TEXT("--size", &o->size, "WxH", "the image size"),
        GIB_OPTION_TEXT("--out", &o->out, "F.exr", "write the image here"),
        GIB_OPTION_TEXT("--cache", &o->cache, "DIR", "look the image up in, or add it to, a cache"),
        GIB_OPTION_FLAG("--force", &o->force, "render again what the cache holds"),
        GIB_OPTION_CUSTOM("--dmax", &o->dmax, parse_dmax, "D", "ao's range (inf: unbounded)"),
        GIB_OPTION_INT("--obscurance", &o->obsc, 0, 1, "0|1", "ao as Zhukov's obscurance"),
        GIB_OPTION_INT("--max-depth", &o->max_depth, 1, 1024, "N", "full's longest path"),
        GIB_OPTION_INT("--min-depth", &o->min_depth, 1, 1024, "N", "Russian roulette from here"),
        GIB_OPTION_INT("--max-specular", &o->max_spec, 1, 64, "N", "caustic's specular vertices"),
        GIB_OPTION_FLOAT("--target-noise", &o->target, 1e-9, 10, "X",
                         "add rounds until the noise RMSE is X times the mean"),
        GIB_OPTION_INT("--max-spp", &o->max_spp, 2, 1 << 24, "N", "with --target-noise"),
        GIB_OPTION_INT("--camera", &o->camera, 0, 64, "I", "the scene's camera (default 0)"),
        GIB_OPTION_INT("--seed", &o->seed, 0, 1L << 30, "N", "with --out only (default 1)"),
        GIB_OPTION_INT("--threads", &o->threads, 0, 1024, "N", "0: every core"),
        GIB_OPTION_TEXT("--stderr", &o->se_out, "F.exr", "each pixel's standard error"),
        GIB_OPTION_FLAG("--quiet", &o->quiet, "print the image's path alone"),
        GIB_OPTION_FLOAT("--time", &o->time, -1e6, 1e6, "T", "the instant, seconds"),
        GIB_OPTION_CUSTOM("--sampler", &o->sampler, parse_sampler, "sobol|random",
                          "the camera samples' numbers"),
        GIB_OPTION_CUSTOM("--strategies", &o->strategies, parse_strategies,
                          "auto|camera|light-vertices", "full's and higher's paths"),
        GIB_OPTION_CUSTOM("--cone", &o->cone, parse_cone, "I", "indirect: diffuse cone I's cap"),
        GIB_OPTION_FLOAT("--cone-aperture", &o->cone_aperture, 1, 179, "DEG",
                         "the cap's aperture (default 60)"),
        {0}};
    return gib_options_parse(&doc, opts, argc, argv, NULL, NULL, 0);
}

/* --component's list: each name, and its spp after a colon (else --spp); a name twice is
 * refused (one entry each). -1 after saying why. */
static int parse_components(ref_opts *o)
{
    char list[512];
    snprintf(list, sizeof list, "%s", o->comp);
    o->ncomp = 0;
    for (char *save = NULL, *tok = strtok_r(list, ",", &save); tok;
         tok = strtok_r(NULL, ",", &save)) {
        char *colon = strchr(tok, ':'), *end = NULL;
        long spp = o->spp;
        if (colon) {
            *colon = '\0';
            spp = strtol(colon + 1, &end, 10);
        }
        int c = gib_component_parse(tok);
        if (c < 0 || (colon && (*end || spp < 1 || spp > (1 << 24))) ||
            o->ncomp == GIB_REF_SET_MAX) {
            fprintf(stderr, "gibench reference: --component '%s': components (ao, direct, "
                            "indirect, glossy, caustic, full, higher, albedo, normal, depth), "
                            "each with an optional :SPP, at most %d\n", o->comp, GIB_REF_SET_MAX);
            return -1;
        }
        for (int i = 0; i < o->ncomp; i++)
            if (o->comps[i] == c) {
                fprintf(stderr, "gibench reference: --component names %s twice\n", tok);
                return -1;
            }
        o->comps[o->ncomp] = c;
        o->spps[o->ncomp++] = spp;
    }
    if (o->ncomp == 0) {
        fprintf(stderr, "gibench reference: --component names no component\n");
        return -1;
    }
    o->component = o->comps[0];
    o->spp = o->spps[0]; /* one component: its own spp, or --spp */
    return 0;
}

/* What the cache cannot hold, and the component and size; sets component, w and h. */
static int check_cache_args(ref_opts *o)
{
    gib_error err = {0};
    if (o->cache && o->seed != 1) {
        fprintf(stderr, "gibench reference: the cache holds seed 1 renders: --seed goes with "
                        "--out only\n");
        return 2;
    }
    if (o->cache && o->sampler == GIB_REF_SAMPLER_RANDOM) {
        fprintf(stderr, "gibench reference: the cache holds sobol renders: --sampler random goes "
                        "with --out only\n");
        return 2;
    }
    if (o->cache && o->se_out) {
        fprintf(stderr, "gibench reference: --stderr needs a fresh render: use --out without "
                        "--cache\n");
        return 2;
    }
    if (parse_components(o) < 0)
        return 2;
    int has_indirect = 0;
    for (int i = 0; i < o->ncomp; i++)
        has_indirect |= o->comps[i] == GIB_COMP_INDIRECT;
    if ((o->cone || o->cone_aperture > 0) && !has_indirect) {
        fprintf(stderr, "gibench reference: --cone and --cone-aperture go with --component "
                        "indirect (one diffuse cone's share of it), not %s\n", o->comp);
        return 2;
    }
    if (o->cone_aperture > 0 && !o->cone) {
        fprintf(stderr, "gibench reference: --cone-aperture needs --cone I\n");
        return 2;
    }
    if (gib_parse_size("--size", o->size, &o->w, &o->h, &err) < 0) {
        fprintf(stderr, "gibench reference: %s\n", err.msg);
        return 2;
    }
    return PROCEED;
}

/* The options' combinations; sets component, w and h. */
static int check_args(ref_opts *o)
{
    gib_error err = {0};
    if (!o->scene_name || !o->comp || (!o->out && !o->cache)) {
        fputs("gibench reference: --scene, --component and --out or --cache are required\n",
              stderr);
        gib_options_usage(stderr, &doc, NULL);
        return 2;
    }
    if (o->force && !o->cache) {
        fprintf(stderr, "gibench reference: --force re-renders a cache entry: give --cache DIR\n");
        return 2;
    }
    if (o->target > 0 && o->max_spp > 0 && o->max_spp < o->spp) {
        fprintf(stderr, "gibench reference: --max-spp %ld is below --spp %ld (the first round's "
                        "count)\n", o->max_spp, o->spp);
        return 2;
    }
    if ((o->out && gib_check_output("--out", o->out, ".exr", &err) < 0) ||
        (o->se_out && gib_check_output("--stderr", o->se_out, ".exr", &err) < 0)) {
        fprintf(stderr, "gibench reference: %s\n", err.msg);
        return 2;
    }
    if (o->out && o->se_out && same_file(o->out, o->se_out)) {
        fprintf(stderr, "gibench reference: --stderr %s is the --out file: the image and its "
                        "standard-error map need two files\n", o->se_out);
        return 2;
    }
    return check_cache_args(o);
}

/* The render and its outcome, shared by the steps after the options. */
typedef struct ref_job {
    const ref_opts *o;
    gib_scene scene;
    gib_ref_params p;
    gib_image img, se;
    gib_ref_stats st;
    gib_ref_result res; /* through the cache */
    const char *where;  /* the image's EXR: --out, or the cache entry (res.path) */
} ref_job;

/* The job's request of the cache. */
static gib_ref_request job_request(const ref_job *j)
{
    const ref_opts *o = j->o;
    return (gib_ref_request){.scene = &j->scene, .camera = (int)o->camera, .width = o->w,
                             .height = o->h, .component = o->component, .spp = (int)o->spp,
                             .dmax = (float)o->dmax, .obscurance = (int)o->obsc,
                             .max_depth = (int)o->max_depth, .min_depth = (int)o->min_depth,
                             .max_specular = (int)o->max_spec, .cone = (int)o->cone,
                             .cone_aperture = (float)o->cone_aperture, .target_noise = o->target,
                             .max_spp = (int)o->max_spp, .cache_dir = o->cache, .force = o->force,
                             .quiet = o->quiet, .threads = (int)o->threads,
                             .interrupt = j->p.interrupt, .time = (float)o->time};
}

/* What the cache gave (j->res): the image, its figures, its PNG preview when just rendered, and
 * the line saying where it is. */
static void take_result(ref_job *j)
{
    const ref_opts *o = j->o;
    gib_error err = {0};
    gib_ref_result *res = &j->res;
    j->img = res->image;
    j->st.spp = res->spp;
    j->st.seconds = res->seconds;
    j->st.noise_rmse = res->noise_rmse;
    if (!res->from_cache && write_png_beside(res->path, &j->img, j->scene.exposure, &err) < 0)
        fprintf(stderr, "gibench reference: %s\n", err.msg);
    printf("%s %s %dx%d: %s %s (%d spp, noise RMSE %.4g)\n", j->scene.name, o->comp, o->w, o->h,
           res->from_cache ? "from cache" : "rendered into cache", res->path, res->spp,
           res->noise_rmse);
    j->where = res->path;
}

/* Through the cache: the entry, rendered when missing (and its PNG preview then). 0, or the exit
 * status. */
static int render_through_cache(ref_job *j)
{
    gib_error err = {0};
    gib_ref_request rq = job_request(j);
    int grc = gib_reference_get(&rq, &j->res, &err);
    interrupt_restore();
    if (grc < 0) {
        fprintf(stderr, "gibench reference: %s\n", err.msg);
        return j->res.interrupted ? 130 : 1;
    }
    take_result(j);
    return 0;
}

/* The cache entry's own values (time, rounds, mean, ...) for the header's keys. */
static void take_cache_attrs(const char *entry, gib_kv *attrs, int n)
{
    gib_error err = {0};
    gib_kv *ca = NULL;
    int cn = 0;
    gib_image tmp;
    if (gib_exr_read(entry, &tmp, &ca, &cn, &err) == 0) {
        gib_image_free(&tmp);
        for (int i = 0; i < n; i++) {
            const char *v = gib_kv_get(ca, cn, attrs[i].key);
            if (v)
                snprintf(attrs[i].value, sizeof attrs[i].value, "%s", v);
        }
    }
    free(ca);
}

/* The standard-error map's header: the render's, marked, and no cache key (it is no reference
 * image); sealed. Returns its count. */
static int stderr_attrs(const gib_kv *attrs, int n, gib_image *se, gib_kv *se_attrs)
{
    memcpy(se_attrs, attrs, (size_t)n * sizeof attrs[0]);
    int sn = n;
    for (int i = 0; i < sn; i++)
        if (!strcmp(se_attrs[i].key, "cache_key"))
            snprintf(se_attrs[i].value, sizeof se_attrs[i].value, "none");
    snprintf(se_attrs[sn].key, sizeof se_attrs[sn].key, "image");
    snprintf(se_attrs[sn].value, sizeof se_attrs[sn].value, "standard_error");
    return gib_ref_seal(se, se_attrs, sn + 1, GIB_REF_ATTR_COUNT + 2);
}

/* A fresh render's summary line, and what became of its target. Returns the exit status. */
static int report_render(const ref_job *j)
{
    const ref_opts *o = j->o;
    const gib_ref_stats *st = &j->st;
    printf("%s %s %dx%d: %d spp%s in %.2f s (%.2f Mrays/s), mean %.6g, noise RMSE %.4g "
           "(%.3g%% of the mean) -> %s\n",
           j->scene.name, o->comp, o->w, o->h, st->spp,
           st->deterministic ? " (deterministic)" : "", st->seconds,
           st->seconds > 0 ? st->rays / st->seconds / 1e6 : 0.0, st->mean, st->noise_rmse,
           st->mean > 0 ? 100.0 * st->noise_rmse / st->mean : 0.0, o->out);
    if (st->interrupted) {
        printf("interrupted: the %d spp of the rounds finished are in %s (target noise "
               "%.3g not reached)\n", st->spp, o->out, o->target);
        return 130;
    } else if (o->target > 0 && !st->target_reached) {
        printf("warning: target noise %.3g not reached within --max-spp\n", o->target);
    }
    return 0;
}

/* --out (with its PNG preview) and --stderr, sealed. Returns the exit status. */
static int write_outputs(ref_job *j)
{
    const ref_opts *o = j->o;
    gib_error err = {0};
    gib_kv attrs[GIB_REF_ATTR_COUNT + 1], se_attrs[GIB_REF_ATTR_COUNT + 2];
    int n = gib_reference_attrs(&j->scene, &j->p, &j->st, attrs, GIB_REF_ATTR_COUNT);
    if (o->cache)
        take_cache_attrs(j->where, attrs, n);
    int sn = o->se_out ? stderr_attrs(attrs, n, &j->se, se_attrs) : 0;
    n = gib_ref_seal(&j->img, attrs, n, GIB_REF_ATTR_COUNT + 1);
    if (gib_exr_write(o->out, &j->img, attrs, n, &err) < 0 ||
        write_png_beside(o->out, &j->img, j->scene.exposure, &err) < 0 ||
        (o->se_out && gib_exr_write(o->se_out, &j->se, se_attrs, sn, &err) < 0)) {
        fprintf(stderr, "gibench reference: %s\n", err.msg);
        return 1;
    }
    return o->cache ? 0 : report_render(j);
}

/* The render's parameters. */
static gib_ref_params job_params(const ref_opts *o)
{
    return (gib_ref_params){.component = o->component, .width = o->w, .height = o->h,
                            .spp = (int)o->spp, .dmax = (float)o->dmax, .obscurance = (int)o->obsc,
                            .max_depth = (int)o->max_depth, .min_depth = (int)o->min_depth,
                            .max_specular = (int)o->max_spec, .cone = (int)o->cone,
                            .cone_aperture = (float)o->cone_aperture, .target_noise = o->target,
                            .max_spp = (int)o->max_spp, .seed = (uint64_t)o->seed,
                            .threads = (int)o->threads, .camera = (int)o->camera,
                            .time = (float)o->time, .sampler = o->sampler,
                            .strategies = o->strategies, .quiet = o->quiet};
}

/* F.exr with ".C" before its extension: a set's file for component C. */
static void set_path(const char *path, const char *comp, char *out, size_t cap)
{
    snprintf(out, cap, "%.*s.%s.exr", (int)strlen(path) - 4, path, comp);
}

/* A set (--component with a list): every component of the view rendered together, through the
 * cache (each its own entry) or into --out's and --stderr's files with ".C" inserted. Returns
 * the exit status. */
static int run_set(ref_job *j)
{
    const ref_opts *o = j->o;
    const int n = o->ncomp;
    gib_error err = {0};
    ref_opts ko[GIB_REF_SET_MAX];
    ref_job kj[GIB_REF_SET_MAX];
    gib_ref_params p[GIB_REF_SET_MAX];
    gib_ref_request rq[GIB_REF_SET_MAX];
    gib_ref_result res[GIB_REF_SET_MAX];
    gib_image img[GIB_REF_SET_MAX] = {{0}}, se[GIB_REF_SET_MAX] = {{0}};
    gib_ref_stats st[GIB_REF_SET_MAX];
    char outs[GIB_REF_SET_MAX][1100], ses[GIB_REF_SET_MAX][1100];
    int rc = 0;
    for (int k = 0; k < n; k++) {
        ko[k] = *o;
        ko[k].comp = gib_component_name(o->comps[k]);
        ko[k].component = o->comps[k];
        ko[k].spp = o->spps[k];
        ko[k].ncomp = 1;
        if (o->out)
            set_path(o->out, ko[k].comp, outs[k], sizeof outs[k]), ko[k].out = outs[k];
        if (o->se_out)
            set_path(o->se_out, ko[k].comp, ses[k], sizeof ses[k]), ko[k].se_out = ses[k];
        kj[k] = (ref_job){.o = &ko[k], .scene = j->scene, .where = ko[k].out};
        kj[k].p = p[k] = job_params(&ko[k]);
        rq[k] = job_request(&kj[k]);
    }
    if (o->cache ? gib_reference_get_set(rq, n, res, &err) < 0
                 : gib_reference_render_set(&j->scene, p, n, img, o->se_out ? se : NULL, st,
                                            &err) < 0) {
        fprintf(stderr, "gibench reference: %s\n", err.msg);
        return 1;
    }
    for (int k = 0; k < n; k++) {
        if (o->cache) {
            kj[k].res = res[k];
            take_result(&kj[k]);
        } else {
            kj[k].img = img[k], kj[k].se = se[k], kj[k].st = st[k];
        }
    }
    for (int k = 0; k < n; k++) {
        if (o->out && rc == 0)
            rc = write_outputs(&kj[k]);
        gib_image_free(&kj[k].img);
        gib_image_free(&kj[k].se);
    }
    return rc;
}

/* The render, through the cache or not, and the files. Returns the exit status. */
static int run_reference(ref_job *j)
{
    const ref_opts *o = j->o;
    gib_error err = {0};
    if (o->ncomp > 1)
        return run_set(j);
    j->p = job_params(o);
    j->where = o->out;
    if (o->target > 0) { /* rounds: Ctrl-C keeps the rounds done */
        atomic_init(&interrupt_req.requested, 0);
        atomic_init(&interrupt_req.rounds_done, 0);
        j->p.interrupt = &interrupt_req;
        interrupt_install();
    }
    if (o->cache) {
        int rc = render_through_cache(j);
        if (rc)
            return rc;
    } else {
        int rrc = gib_reference_render(&j->scene, &j->p, &j->img, o->se_out ? &j->se : NULL,
                                       &j->st, &err);
        interrupt_restore();
        if (rrc < 0) {
            fprintf(stderr, "gibench reference: %s\n", err.msg);
            return 1;
        }
    }
    return o->out ? write_outputs(j) : 0;
}

int gib_cmd_reference(int argc, char **argv)
{
    ref_opts o = {.size = "256x256", .spp = 16, .seed = 1, .sampler = GIB_REF_SAMPLER_DEFAULT,
                  .dmax = INFINITY};
    int rc = parse_args(argc, argv, &o);
    if (rc == PROCEED)
        rc = check_args(&o);
    if (rc != PROCEED)
        return rc;
    ref_job j = {.o = &o};
    rc = gib_cli_load_scene("reference", o.scene_name, o.camera, &j.scene);
    if (rc)
        return rc;
    rc = run_reference(&j);
    gib_image_free(&j.img);
    gib_image_free(&j.se);
    gib_scene_free(&j.scene);
    return rc;
}
