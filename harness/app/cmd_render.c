/* gibench render — one technique on one scene: images, timings, memory, and (with --ref-spp) the
 * metrics against the reference. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "runner.h"
#include "app.h"

static const char help[] =
    "usage: gibench render --scene S --technique T [--param k=v]... --size WxH --out DIR\n"
    "                      [--camera I] [--warmup W] [--frames F] [--backend egl|osmesa|auto]\n"
    "                      [--ref-spp N] [--cache DIR] [--time T] [--dt DT]\n"
    "\n"
    "Renders technique T on scene S and writes DIR/T_<component>.exr and .png. With --ref-spp N,\n"
    "also scores each component against an N-spp reference (cached under --cache, default\n"
    "results/cache) and writes an error map. --time T (seconds, default 0): the instant a moving\n"
    "scene (scenes/FORMAT.md, Motion) is shown at, in the image and in the reference; --dt DT\n"
    "(default 0): the frames before the last are DT apart (frame f of n at T - (n-1-f) DT), so\n"
    "every frame is a new instant.\n"
    "\n"
    "Timing: a cold first frame (shader compiles and first uses; reported apart, with the time\n"
    "from create to its image), then W warm-up frames (default 2), then F timed frames (default\n"
    "5): their median, interquartile range, min and max per pass.\n";

int gib_cmd_render(int argc, char **argv)
{
    const char *scene_name = NULL, *tech_name = NULL, *out = NULL, *size = "256x256";
    const char *cache = GIB_PROJECT_ROOT "/results/cache";
    const char *params[GIB_MAX_PARAMS * 2];
    int nparams = 0, backend = GIB_BACKEND_AUTO;
    long camera = 0, warmup = 2, frames = 5, ref_spp = 0;
    double time = 0.0, dt = 0.0;
    gib_error err = {0};
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            fputs(help, stdout);
            return 0;
        }
        if (!v) {
            fprintf(stderr, "gibench render: option %s needs a value\n%s", a, help);
            return 2;
        }
        i++;
        int rc = 0;
        if (!strcmp(a, "--scene")) scene_name = v;
        else if (!strcmp(a, "--technique")) tech_name = v;
        else if (!strcmp(a, "--out")) out = v;
        else if (!strcmp(a, "--size")) size = v;
        else if (!strcmp(a, "--cache")) cache = v;
        else if (!strcmp(a, "--param") && nparams < GIB_MAX_PARAMS * 2) params[nparams++] = v;
        else if (!strcmp(a, "--camera")) rc = gib_parse_int(a, v, 0, 64, &camera, &err);
        else if (!strcmp(a, "--warmup")) rc = gib_parse_int(a, v, 0, 100, &warmup, &err);
        else if (!strcmp(a, "--frames")) rc = gib_parse_int(a, v, 1, GIB_TIMER_MAX_FRAMES, &frames, &err);
        else if (!strcmp(a, "--ref-spp")) rc = gib_parse_int(a, v, 1, 1 << 20, &ref_spp, &err);
        else if (!strcmp(a, "--time")) rc = gib_parse_float(a, v, -1e6, 1e6, &time, &err);
        else if (!strcmp(a, "--dt")) rc = gib_parse_float(a, v, 0, 1e4, &dt, &err);
        else if (!strcmp(a, "--backend")) {
            if ((backend = gib_backend_parse(v)) < 0)
                rc = gib_fail(&err, "--backend expects egl, osmesa or auto, got '%s'", v);
        } else {
            fprintf(stderr, "gibench render: unknown option '%s'\n%s", a, help);
            return 2;
        }
        if (rc < 0) {
            fprintf(stderr, "gibench render: %s\n", err.msg);
            return 2;
        }
    }
    if (!scene_name || !tech_name || !out) {
        fprintf(stderr, "gibench render: --scene, --technique and --out are required\n%s", help);
        return 2;
    }
    int w, h;
    const gib_technique *t = gib_technique_find(tech_name);
    if (!t) {
        fprintf(stderr, "gibench render: unknown technique '%s' (see gibench list)\n", tech_name);
        return 2;
    }
    gib_params p;
    gib_params_default(t, &p);
    for (int i = 0; i < nparams; i++) {
        char kv[256];
        snprintf(kv, sizeof kv, "%s", params[i]);
        char *eq = strchr(kv, '=');
        if (!eq) {
            fprintf(stderr, "gibench render: --param expects name=value, got '%s'\n", params[i]);
            return 2;
        }
        *eq = 0;
        if (gib_param_set(t, &p, kv, eq + 1, &err) < 0) {
            fprintf(stderr, "gibench render: %s\n", err.msg);
            return 2;
        }
    }
    if (gib_parse_size("--size", size, &w, &h, &err) < 0) {
        fprintf(stderr, "gibench render: %s\n", err.msg);
        return 2;
    }
    gib_scene scene;
    int rc = gib_cli_load_scene("render", scene_name, camera, &scene);
    if (rc)
        return rc;
    gib_gl_info info;
    gib_gpu_scene gpu;
    if (gib_gl_init(backend, &info, &err) < 0 || gib_gpu_scene_upload(&scene, &gpu, &err) < 0 ||
        gib_mkdirs(out, &err) < 0) {
        fprintf(stderr, "gibench render: %s\n", err.msg);
        gib_scene_free(&scene);
        return 1;
    }
    printf("renderer: %s | %s | %s\n", info.backend, info.renderer, info.version);
    gib_run_result r;
    gib_run(&(gib_run_request){.scene = &gpu, .technique = t, .params = &p, .camera = (int)camera,
                               .width = w, .height = h, .warmup = (int)warmup,
                               .frames = (int)frames, .time = time, .dt = dt},
            &r);
    int status = 0;
    if (!r.ok) {
        fprintf(stderr, "gibench render: %s: status %s: %s\n", t->name, r.status, r.err.msg);
        status = 1;
    } else {
        printf("%s on %s at %dx%d, %d timed frames after %ld warm-up: gpu %.3f ms (IQR %.3f, "
               "min %.3f, max %.3f), cpu %.3f ms (IQR %.3f)\n",
               t->name, scene.name, w, h, r.frames, warmup, r.gpu_total.median_ms,
               r.gpu_total.iqr_ms, r.gpu_total.min_ms, r.gpu_total.max_ms, r.cpu_total.median_ms,
               r.cpu_total.iqr_ms);
        printf("  cold first frame: %.3f ms to the first image (create included), gpu %.3f ms\n",
               r.first_frame_ms, r.gpu_total.first_ms);
        for (int i = 0; i < r.pass_count; i++)
            printf("  pass %-12s %.3f ms (IQR %.3f, min %.3f, max %.3f; cold %.3f)\n",
                   r.passes[i].name, r.passes[i].median_ms, r.passes[i].iqr_ms,
                   r.passes[i].min_ms, r.passes[i].max_ms, r.passes[i].first_ms);
        printf("  memory: technique %.3f MB (%s), scene %.3f MB\n", r.technique_bytes / 1e6,
               r.memory_by_label, gpu.ledger.peak_bytes / 1e6);
        if (r.counters[0])
            printf("  counters: %s\n", r.counters);
    }
    for (int i = 0; r.ok && i < r.output_count; i++) {
        const char *comp = gib_output_name(r.output_components[i]);
        char name[256];
        snprintf(name, sizeof name, "%s_%s", t->name, comp);
        if (ref_spp > 0) {
            gib_ref_request rq = {.scene = &scene, .camera = (int)camera, .width = w, .height = h,
                                  .time = (float)time,
                                  .component = gib_component_parse(comp), .spp = (int)ref_spp,
                                  .cache_dir = cache};
            gib_ref_request_match(&rq, t, &p, r.output_components[i]);
            gib_ref_result ref;
            gib_metrics m;
            if (rq.component < 0 || gib_reference_get(&rq, &ref, &err) < 0 ||
                gib_score_and_save(&ref.image, &r.images[i], scene.exposure, out, name, &m,
                                   &err) < 0) {
                fprintf(stderr, "gibench render: %s\n",
                        rq.component < 0 ? "no reference for this component" : err.msg);
                status = 1;
                continue;
            }
            gib_rmse_bounds b;
            gib_rmse_interval(m.rmse, ref.noise_rmse, (long)w * h, &b);
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
        } else {
            char path[4096];
            snprintf(path, sizeof path, "%s/%s.exr", out, name);
            if (gib_exr_write(path, &r.images[i], NULL, 0, &err) < 0) {
                fprintf(stderr, "gibench render: %s\n", err.msg);
                status = 1;
            }
            snprintf(path, sizeof path, "%s/%s.png", out, name);
            if (gib_png_write_preview(path, &r.images[i], scene.exposure, &err) < 0) {
                fprintf(stderr, "gibench render: %s\n", err.msg);
                status = 1;
            }
            long nf = gib_image_count_nonfinite(&r.images[i]);
            if (nf) {
                fprintf(stderr, "gibench render: %s image has %ld non-finite values\n", comp, nf);
                status = 1;
            }
        }
    }
    gib_run_result_free(&r);
    gib_gpu_scene_free(&gpu);
    gib_gl_shutdown();
    gib_scene_free(&scene);
    return status;
}
