/* gibench reference — renders one light-transport component with the Embree path tracer and
 * writes it as EXR with its metadata (and a PNG preview beside it), directly (--out) or through
 * the reference cache (--cache DIR, --force to render again). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app.h"

static const char help[] =
    "usage: gibench reference --scene S --component C [--spp N] [--size WxH]\n"
    "                         (--out F.exr | --cache DIR [--force] [--out F.exr])\n"
    "                         [--dmax D] [--obscurance 0|1] [--max-depth N] [--min-depth N]\n"
    "                         [--max-specular N] [--target-noise X] [--max-spp N]\n"
    "                         [--camera I] [--seed N] [--threads N] [--stderr F.exr] [--quiet]\n"
    "\n"
    "Components (paths in Heckbert notation, reference/reference.h):\n"
    "  ao        ambient occlusion within --dmax (default unbounded); --obscurance 1 weights an\n"
    "            occluder at distance d by min(d / dmax, 1) (Zhukov et al. 1998; needs --dmax)\n"
    "  direct    L D E, L S E            indirect  L D D E         glossy  L D S E\n"
    "  caustic   L S+ D E with at most --max-specular S vertices (default 1), light traced\n"
    "  full      all paths of at most --max-depth vertices (default 8), Russian roulette from\n"
    "            --min-depth (default 3)\n"
    "  higher    what full has beyond direct + indirect + glossy + caustic\n"
    "  albedo, normal, depth   auxiliary images of the visible point\n"
    "\n"
    "--spp N (default 16) is the sample count, or with --target-noise X the first round's:\n"
    "rounds are added until the noise RMSE is at most X times the image mean, or --max-spp\n"
    "(default 65536) is reached. Random components need spp >= 2 (the variance of one sample is\n"
    "unknown); deterministic ones (direct with only point,\n"
    "spot and directional lights - not with a sky -, the auxiliary images) take one sample.\n"
    "The EXR header records component, parameters, spp, seconds, scene hash, renderer version,\n"
    "the cache key and the image's noise RMSE (standard error from the per-pixel variance).\n";

static int write_png_beside(const char *exr, const gib_image *img, float exposure, gib_error *err)
{
    char png[4096];
    snprintf(png, sizeof png, "%s", exr);
    char *dot = strrchr(png, '.');
    if (dot && !strcmp(dot, ".exr"))
        *dot = 0;
    strncat(png, ".png", sizeof png - strlen(png) - 1);
    return gib_png_write_preview(png, img, exposure, err);
}

int gib_cmd_reference(int argc, char **argv)
{
    const char *scene_name = NULL, *comp = NULL, *out = NULL, *size = "256x256", *se_out = NULL;
    const char *cache = NULL;
    long spp = 16, camera = 0, seed = 1, threads = 0, obsc = 0, max_depth = 0, min_depth = 0;
    long max_spec = 0, max_spp = 0;
    int force = 0, quiet = 0;
    double dmax = INFINITY, target = 0.0;
    gib_error err = {{0}};
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            fputs(help, stdout);
            return 0;
        }
        if (!strcmp(a, "--force")) {
            force = 1;
            continue;
        }
        if (!strcmp(a, "--quiet")) {
            quiet = 1;
            continue;
        }
        if (!v) {
            fprintf(stderr, "gibench reference: option %s needs a value\n%s", a, help);
            return 2;
        }
        i++;
        int rc = 0;
        if (!strcmp(a, "--scene")) scene_name = v;
        else if (!strcmp(a, "--component")) comp = v;
        else if (!strcmp(a, "--out")) out = v;
        else if (!strcmp(a, "--cache")) cache = v;
        else if (!strcmp(a, "--stderr")) se_out = v;
        else if (!strcmp(a, "--size")) size = v;
        else if (!strcmp(a, "--spp")) rc = gib_parse_int(a, v, 1, 1 << 24, &spp, &err);
        else if (!strcmp(a, "--camera")) rc = gib_parse_int(a, v, 0, 64, &camera, &err);
        else if (!strcmp(a, "--seed")) rc = gib_parse_int(a, v, 0, 1L << 30, &seed, &err);
        else if (!strcmp(a, "--threads")) rc = gib_parse_int(a, v, 0, 1024, &threads, &err);
        else if (!strcmp(a, "--obscurance")) rc = gib_parse_int(a, v, 0, 1, &obsc, &err);
        else if (!strcmp(a, "--max-depth")) rc = gib_parse_int(a, v, 1, 1024, &max_depth, &err);
        else if (!strcmp(a, "--min-depth")) rc = gib_parse_int(a, v, 1, 1024, &min_depth, &err);
        else if (!strcmp(a, "--max-specular")) rc = gib_parse_int(a, v, 1, 64, &max_spec, &err);
        else if (!strcmp(a, "--max-spp")) rc = gib_parse_int(a, v, 2, 1 << 24, &max_spp, &err);
        else if (!strcmp(a, "--target-noise")) rc = gib_parse_float(a, v, 1e-9, 10, &target, &err);
        else if (!strcmp(a, "--dmax")) {
            if (!strcmp(v, "inf") || !strcmp(v, "unbounded"))
                dmax = INFINITY;
            else
                rc = gib_parse_float(a, v, 0, 1e30, &dmax, &err);
        } else {
            fprintf(stderr, "gibench reference: unknown option '%s'\n%s", a, help);
            return 2;
        }
        if (rc < 0) {
            fprintf(stderr, "gibench reference: %s\n", err.msg);
            return 2;
        }
    }
    if (!scene_name || !comp || (!out && !cache)) {
        fprintf(stderr, "gibench reference: --scene, --component and --out or --cache are "
                        "required\n%s", help);
        return 2;
    }
    if (force && !cache) {
        fprintf(stderr, "gibench reference: --force re-renders a cache entry: give --cache DIR\n");
        return 2;
    }
    if (cache && se_out) {
        fprintf(stderr, "gibench reference: --stderr needs a fresh render: use --out without "
                        "--cache\n");
        return 2;
    }
    int component = gib_component_parse(comp);
    if (component < 0) {
        fprintf(stderr, "gibench reference: unknown component '%s' (ao, direct, indirect, glossy, "
                        "caustic, full, higher, albedo, normal, depth)\n", comp);
        return 2;
    }
    int w, h;
    if (gib_parse_size("--size", size, &w, &h, &err) < 0) {
        fprintf(stderr, "gibench reference: %s\n", err.msg);
        return 2;
    }
    gib_scene scene;
    int rc = gib_cli_load_scene("reference", scene_name, camera, &scene);
    if (rc)
        return rc;
    gib_ref_params p = {.component = component, .width = w, .height = h, .spp = (int)spp,
                        .dmax = (float)dmax, .obscurance = (int)obsc, .max_depth = (int)max_depth,
                        .min_depth = (int)min_depth, .max_specular = (int)max_spec,
                        .target_noise = target, .max_spp = (int)max_spp, .seed = (uint64_t)seed,
                        .threads = (int)threads, .camera = (int)camera, .quiet = quiet};
    gib_image img = {0}, se = {0};
    gib_ref_stats st = {0};
    int status = 0;
    gib_ref_result res = {0};
    const char *where = out;
    if (cache) {
        if (seed != 1 || threads != 0) {
            fprintf(stderr, "gibench reference: the cache holds seed 1 renders on all cores: "
                            "--seed and --threads go with --out only\n");
            gib_scene_free(&scene);
            return 2;
        }
        gib_ref_request rq = {.scene = &scene, .camera = (int)camera, .width = w, .height = h,
                              .component = component, .spp = (int)spp, .dmax = (float)dmax,
                              .obscurance = (int)obsc, .max_depth = (int)max_depth,
                              .min_depth = (int)min_depth, .max_specular = (int)max_spec,
                              .target_noise = target, .max_spp = (int)max_spp,
                              .cache_dir = cache, .force = force, .quiet = quiet};
        if (gib_reference_get(&rq, &res, &err) < 0) {
            fprintf(stderr, "gibench reference: %s\n", err.msg);
            gib_scene_free(&scene);
            return 1;
        }
        img = res.image;
        st.spp = res.spp;
        st.seconds = res.seconds;
        st.noise_rmse = res.noise_rmse;
        if (!res.from_cache && write_png_beside(res.path, &img, scene.exposure, &err) < 0)
            fprintf(stderr, "gibench reference: %s\n", err.msg);
        printf("%s %s %dx%d: %s %s (%d spp, noise RMSE %.4g)\n", scene.name, comp, w, h,
               res.from_cache ? "from cache" : "rendered into cache", res.path, res.spp,
               res.noise_rmse);
        where = res.path;
    } else if (gib_reference_render(&scene, &p, &img, se_out ? &se : NULL, &st, &err) < 0) {
        fprintf(stderr, "gibench reference: %s\n", err.msg);
        gib_scene_free(&scene);
        return 1;
    }
    if (out) {
        gib_kv attrs[GIB_REF_ATTR_COUNT];
        int n = gib_reference_attrs(&scene, &p, &st, attrs, GIB_REF_ATTR_COUNT);
        if (cache) { /* the entry's own values (time, rounds, mean, ...) for our keys */
            gib_kv *ca = NULL;
            int cn = 0;
            gib_image tmp;
            if (gib_exr_read(where, &tmp, &ca, &cn, &err) == 0) {
                gib_image_free(&tmp);
                for (int i = 0; i < n; i++) {
                    const char *v = gib_kv_get(ca, cn, attrs[i].key);
                    if (v)
                        snprintf(attrs[i].value, sizeof attrs[i].value, "%s", v);
                }
            }
            free(ca);
        }
        if (gib_exr_write(out, &img, attrs, n, &err) < 0 ||
            write_png_beside(out, &img, scene.exposure, &err) < 0 ||
            (se_out && gib_exr_write(se_out, &se, attrs, n, &err) < 0)) {
            fprintf(stderr, "gibench reference: %s\n", err.msg);
            status = 1;
        } else if (!cache) {
            printf("%s %s %dx%d: %d spp%s in %.2f s (%.2f Mrays/s), mean %.6g, noise RMSE %.4g "
                   "(%.3g%% of the mean) -> %s\n",
                   scene.name, comp, w, h, st.spp,
                   st.deterministic ? " (deterministic)" : "", st.seconds,
                   st.seconds > 0 ? st.rays / st.seconds / 1e6 : 0.0, st.mean, st.noise_rmse,
                   st.mean > 0 ? 100.0 * st.noise_rmse / st.mean : 0.0, out);
            if (target > 0 && !st.target_reached)
                printf("warning: target noise %.3g not reached within --max-spp\n", target);
        }
    }
    gib_image_free(&img);
    gib_image_free(&se);
    gib_scene_free(&scene);
    return status;
}
