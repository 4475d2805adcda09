/* gibench render — one technique on one scene: images, timings, memory, and (with --ref-spp) the
 * metrics against the reference. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "runner.h"
#include "app.h"
#include "options.h"
#include "refrank.h"

/* What the command line asks for. */
typedef struct render_opts {
    const char *scene_name, *tech_name, *out, *size, *cache;
    const char *params[GIB_MAX_PARAMS * 2]; /* --param name=value, as given */
    int nparams, backend;
    long camera, warmup, frames, ref_spp;
    double time, dt;
    const gib_technique *t; /* from tech_name, params and size (resolve_args) */
    gib_params p;
    int w, h;
} render_opts;

#define PROCEED GIB_OPTIONS_PROCEED /* parse_args, resolve_args: go on (else the exit status) */

static const gib_command_doc doc = {
    "render", "--scene S --technique T [--param k=v]... --size WxH --out DIR [options]",
    "Renders technique T on scene S and writes DIR/T_<component>.exr and .png. With --ref-spp N,\n"
    "also scores each component against an N-spp reference (cached under --cache, default\n"
    "results/cache; deepened as `gibench run` deepens one too noisy to rank the image) and writes\n"
    "an error map. --time T (seconds, default 0): the instant a moving scene (scenes/FORMAT.md,\n"
    "Motion) is shown at, in the image and in the reference; --dt DT (default 0): the frames\n"
    "before the last are DT apart (frame f of n at T - (n-1-f) DT), so every frame is a new\n"
    "instant.\n"
    "\n"
    "Timing: a cold first frame (shader compiles and first uses; reported apart, with the time\n"
    "from create to its image), then W warm-up frames (default 2), then F timed frames (default\n"
    "5): their median, interquartile range, min and max per pass.\n"};

static int parse_args(int argc, char **argv, render_opts *o)
{
    const gib_option opts[] = {
        GIB_OPTION_TEXT("--scene", &o->scene_name, "S", "the scene (gibench list)"),
        GIB_OPTION_TEXT("--technique", &o->tech_name, "T", "the technique (gibench list)"),
        GIB_OPTION_LIST("--param", o->params, GIB_MAX_PARAMS * 2, &o->nparams, "k=v",
                        "a parameter of the technique (repeatable)"),
        GIB_OPTION_TEXT("--size", &o->size, "WxH", "the image size (default 256x256)"),
        GIB_OPTION_TEXT("--out", &o->out, "DIR", "where the images go"),
        GIB_OPTION_INT("--camera", &o->camera, 0, 64, "I", "the scene's camera (default 0)"),
        GIB_OPTION_INT("--warmup", &o->warmup, 0, 100, "W", "warm-up frames (default 2)"),
        GIB_OPTION_INT("--frames", &o->frames, 1, GIB_TIMER_MAX_FRAMES, "F",
                       "timed frames (default 5)"),
        GIB_OPTION_BACKEND("--backend", &o->backend),
        GIB_OPTION_INT("--ref-spp", &o->ref_spp, 1, 1 << 20, "N",
                       "score against an N-spp reference"),
        GIB_OPTION_TEXT("--cache", &o->cache, "DIR", "the references' cache (results/cache)"),
        GIB_OPTION_FLOAT("--time", &o->time, -1e6, 1e6, "T", "the instant, seconds (default 0)"),
        GIB_OPTION_FLOAT("--dt", &o->dt, 0, 1e4, "DT", "seconds between frames (default 0)"),
        {0}};
    return gib_options_parse(&doc, opts, argc, argv, NULL, NULL, 0);
}

/* The technique, its parameters and the size from their names. */
static int resolve_args(render_opts *o)
{
    gib_error err = {0};
    if (!o->scene_name || !o->tech_name || !o->out) {
        fputs("gibench render: --scene, --technique and --out are required\n", stderr);
        gib_options_usage(stderr, &doc, NULL);
        return 2;
    }
    const gib_technique *t = o->t = gib_technique_find(o->tech_name);
    if (!t) {
        fprintf(stderr, "gibench render: unknown technique '%s' (see gibench list)\n",
                o->tech_name);
        return 2;
    }
    gib_params_default(t, &o->p);
    unsigned char named[GIB_MAX_PARAMS] = {0};
    for (int i = 0; i < o->nparams; i++) {
        char kv[256];
        snprintf(kv, sizeof kv, "%s", o->params[i]);
        char *eq = strchr(kv, '=');
        if (!eq) {
            fprintf(stderr, "gibench render: --param expects name=value, got '%s'\n",
                    o->params[i]);
            return 2;
        }
        *eq = 0;
        if (gib_param_set(t, &o->p, kv, eq + 1, &err) < 0) {
            fprintf(stderr, "gibench render: %s\n", err.msg);
            return 2;
        }
        named[gib_param_index(t, kv)] = 1;
    }
    if (gib_params_apply_preset(t, &o->p, named, &err) < 0 ||
        gib_params_check(t, &o->p, &err) < 0) {
        fprintf(stderr, "gibench render: %s\n", err.msg);
        return 2;
    }
    if (gib_parse_size("--size", o->size, &o->w, &o->h, &err) < 0) {
        fprintf(stderr, "gibench render: %s\n", err.msg);
        return 2;
    }
    return PROCEED;
}

static void print_timings(const render_opts *o, const gib_scene *scene, const gib_gpu_scene *gpu,
                          const gib_run_result *r)
{
    printf("%s on %s at %dx%d, %d timed frames after %ld warm-up: gpu %.3f ms (IQR %.3f, "
           "min %.3f, max %.3f), cpu %.3f ms (IQR %.3f)\n",
           o->t->name, scene->name, o->w, o->h, r->frames, o->warmup, r->gpu_total.median_ms,
           r->gpu_total.iqr_ms, r->gpu_total.min_ms, r->gpu_total.max_ms, r->cpu_total.median_ms,
           r->cpu_total.iqr_ms);
    printf("  cold first frame: %.3f ms to the first image (create included), gpu %.3f ms\n",
           r->first_frame_ms, r->gpu_total.first_ms);
    for (int i = 0; i < r->pass_count; i++)
        printf("  pass %-12s %.3f ms (IQR %.3f, min %.3f, max %.3f; cold %.3f)\n",
               r->passes[i].name, r->passes[i].median_ms, r->passes[i].iqr_ms,
               r->passes[i].min_ms, r->passes[i].max_ms, r->passes[i].first_ms);
    printf("  memory: technique %.3f MB (%s), scene %.3f MB\n", r->technique_bytes / 1e6,
           r->memory_by_label, gpu->ledger.peak_bytes / 1e6);
    if (r->counters[0])
        printf("  counters: %s\n", r->counters);
}

/* Output i scored against its reference (images and error map saved as `name`). Returns the
 * exit status it asks for. */
static int score_output(const render_opts *o, const gib_scene *scene, const gib_run_result *r,
                        int i, const char *name)
{
    gib_error err = {0};
    const char *comp = gib_output_name(r->output_components[i]);
    gib_ref_request rq = {.scene = scene, .camera = (int)o->camera, .width = o->w,
                          .height = o->h, .time = (float)o->time,
                          .component = gib_component_parse(comp), .spp = (int)o->ref_spp,
                          .cache_dir = o->cache};
    gib_ref_request_match(&rq, o->t, &o->p, r->output_components[i]);
    gib_ref_result ref;
    gib_score s;
    if (rq.component < 0 ||
        gib_reference_to_rank(&rq, &r->images[i], scene->exposure, GIB_REF_SPP_GROWTH_DEFAULT,
                              &ref, &err) < 0) {
        fprintf(stderr, "gibench render: %s\n",
                rq.component < 0 ? "no reference for this component" : err.msg);
        return 1;
    }
    if (gib_score_image(&ref.image, ref.noise_rmse, &r->images[i], scene->exposure, o->out, name,
                        &s, &err) < 0) {
        fprintf(stderr, "gibench render: %s\n", err.msg);
        gib_image_free(&ref.image);
        return 1;
    }
    const gib_metrics m = s.m;
    const gib_rmse_bounds b = s.rmse;
    printf("  %s: rmse %.6g rel_rmse %.6g mean %.4g of the reference's psnr %.3f ssim %.6f "
           "nonfinite %ld (reference %d spp, noise rmse %.3g)\n", comp, m.rmse, m.rel_rmse,
           m.mean_ratio, m.psnr, m.ssim,
           m.nonfinite, ref.spp, ref.noise_rmse);
    if (m.black_rmse > 0)
        printf("  %s: a black image scores rmse %.6g (this image %.3g of it%s)", comp,
               m.black_rmse, m.rmse / m.black_rmse,
               m.rmse > m.black_rmse ? ": WORSE THAN BLACK" : "");
    else
        printf("  %s: the reference is black (any light here is error)", comp);
    printf("; without the reference's noise rmse %.6g [%.6g, %.6g] (95%%)\n", b.denoised,
           b.lo, b.hi);
    gib_image_free(&ref.image);
    return 0;
}

/* Output i written as OUT/name.exr and .png, checked for non-finite values. Returns the exit
 * status it asks for. */
static int write_output(const render_opts *o, const gib_scene *scene, const gib_run_result *r,
                        int i, const char *name)
{
    gib_error err = {0};
    int status = 0;
    char path[4096];
    snprintf(path, sizeof path, "%s/%s.exr", o->out, name);
    if (gib_exr_write(path, &r->images[i], NULL, 0, &err) < 0) {
        fprintf(stderr, "gibench render: %s\n", err.msg);
        status = 1;
    }
    snprintf(path, sizeof path, "%s/%s.png", o->out, name);
    if (gib_png_write_preview(path, &r->images[i], scene->exposure, &err) < 0) {
        fprintf(stderr, "gibench render: %s\n", err.msg);
        status = 1;
    }
    long nf = gib_image_count_nonfinite(&r->images[i]);
    if (nf) {
        fprintf(stderr, "gibench render: %s image has %ld non-finite values\n",
                gib_output_name(r->output_components[i]), nf);
        status = 1;
    }
    return status;
}

/* The run on the uploaded scene, its timings and its outputs. Returns the exit status. */
static int render_and_report(const render_opts *o, const gib_scene *scene, gib_gpu_scene *gpu)
{
    gib_run_result r;
    gib_run(&(gib_run_request){.scene = gpu, .technique = o->t, .params = &o->p,
                               .camera = (int)o->camera, .width = o->w, .height = o->h,
                               .warmup = (int)o->warmup, .frames = (int)o->frames,
                               .time = o->time, .dt = o->dt},
            &r);
    int status = 0;
    if (!r.ok) {
        fprintf(stderr, "gibench render: %s: status %s: %s\n", o->t->name, r.status, r.err.msg);
        status = 1;
    } else {
        print_timings(o, scene, gpu, &r);
    }
    for (int i = 0; r.ok && i < r.output_count; i++) {
        char name[256];
        snprintf(name, sizeof name, "%s_%s", o->t->name, gib_output_name(r.output_components[i]));
        int rc = o->ref_spp > 0 ? score_output(o, scene, &r, i, name)
                                : write_output(o, scene, &r, i, name);
        if (rc)
            status = rc;
    }
    gib_run_result_free(&r);
    return status;
}

int gib_cmd_render(int argc, char **argv)
{
    render_opts o = {.size = "256x256", .cache = GIB_PROJECT_ROOT "/results/cache",
                     .backend = GIB_BACKEND_AUTO, .warmup = 2, .frames = 5};
    int rc = parse_args(argc, argv, &o);
    if (rc == PROCEED)
        rc = resolve_args(&o);
    if (rc != PROCEED)
        return rc;
    gib_scene scene;
    rc = gib_cli_load_scene("render", o.scene_name, o.camera, &scene);
    if (rc)
        return rc;
    gib_error err = {0};
    gib_gl_info info;
    gib_gpu_scene gpu;
    if (gib_gl_init(o.backend, &info, &err) < 0 || gib_gpu_scene_upload(&scene, &gpu, &err) < 0 ||
        gib_mkdirs(o.out, &err) < 0) {
        fprintf(stderr, "gibench render: %s\n", err.msg);
        gib_scene_free(&scene);
        return 1;
    }
    printf("renderer: %s | %s | %s\n", info.backend, info.renderer, info.version);
    if (info.device[0])
        printf("EGL %s\n", info.device);
    int status = render_and_report(&o, &scene, &gpu);
    gib_gpu_scene_free(&gpu);
    gib_gl_shutdown();
    gib_scene_free(&scene);
    return status;
}
