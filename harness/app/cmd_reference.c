/* gibench reference — renders one light-transport component with the Embree path tracer and
 * writes it as EXR with its metadata (and a PNG preview beside it). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "app.h"

static const char help[] =
    "usage: gibench reference --scene S --component C --spp N --size WxH --out F.exr\n"
    "                         [--dmax D] [--camera I] [--seed N] [--threads N] [--stderr F.exr]\n"
    "\n"
    "Components: ao (with --dmax, default unbounded), direct.\n"
    "The EXR header records component, spp, seconds, scene hash, renderer version and the\n"
    "image's noise RMSE (standard error from the per-pixel sample variance).\n";

int gib_cmd_reference(int argc, char **argv)
{
    const char *scene_name = NULL, *comp = NULL, *out = NULL, *size = "256x256", *se_out = NULL;
    long spp = 16, camera = 0, seed = 1, threads = 0;
    double dmax = INFINITY;
    gib_error err = {{0}};
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            fputs(help, stdout);
            return 0;
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
        else if (!strcmp(a, "--stderr")) se_out = v;
        else if (!strcmp(a, "--size")) size = v;
        else if (!strcmp(a, "--spp")) rc = gib_parse_int(a, v, 1, 1 << 24, &spp, &err);
        else if (!strcmp(a, "--camera")) rc = gib_parse_int(a, v, 0, 64, &camera, &err);
        else if (!strcmp(a, "--seed")) rc = gib_parse_int(a, v, 0, 1L << 30, &seed, &err);
        else if (!strcmp(a, "--threads")) rc = gib_parse_int(a, v, 0, 1024, &threads, &err);
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
    if (!scene_name || !comp || !out) {
        fprintf(stderr, "gibench reference: --scene, --component and --out are required\n%s", help);
        return 2;
    }
    int component = gib_component_parse(comp);
    if (component < 0) {
        fprintf(stderr, "gibench reference: unknown component '%s' (ao, direct)\n", comp);
        return 2;
    }
    int w, h;
    if (gib_parse_size("--size", size, &w, &h, &err) < 0) {
        fprintf(stderr, "gibench reference: %s\n", err.msg);
        return 2;
    }
    gib_scene scene;
    int rc = gib_scene_load(scene_name, &scene, &err);
    if (rc < 0) {
        fprintf(stderr, "gibench reference: %s\n", err.msg);
        return rc == GIB_SCENE_UNAVAILABLE ? 3 : 1;
    }
    if (camera >= (long)scene.camera_count) {
        fprintf(stderr, "gibench reference: --camera %ld: scene '%s' has %u camera(s)\n", camera,
                scene.name, scene.camera_count);
        gib_scene_free(&scene);
        return 2;
    }
    gib_ref_params p = {.component = component, .width = w, .height = h, .spp = (int)spp,
                        .dmax = (float)dmax, .seed = (uint64_t)seed, .threads = (int)threads,
                        .camera = (int)camera};
    gib_image img = {0}, se = {0};
    gib_ref_stats st;
    int status = 0;
    if (gib_reference_render(&scene, &p, &img, se_out ? &se : NULL, &st, &err) < 0) {
        fprintf(stderr, "gibench reference: %s\n", err.msg);
        gib_scene_free(&scene);
        return 1;
    }
    gib_kv attrs[32];
    int n = gib_reference_attrs(&scene, &p, &st, attrs, 32);
    char png[4096];
    snprintf(png, sizeof png, "%s", out);
    char *dot = strrchr(png, '.');
    if (dot && !strcmp(dot, ".exr"))
        *dot = 0;
    strncat(png, ".png", sizeof png - strlen(png) - 1);
    if (gib_exr_write(out, &img, attrs, n, &err) < 0 ||
        gib_png_write_preview(png, &img, scene.exposure, &err) < 0 ||
        (se_out && gib_exr_write(se_out, &se, attrs, n, &err) < 0)) {
        fprintf(stderr, "gibench reference: %s\n", err.msg);
        status = 1;
    } else {
        printf("%s %s %dx%d: %ld spp in %.2f s (%.2f Mrays/s), mean %.6g, noise RMSE %.4g -> %s\n",
               scene.name, comp, w, h, spp, st.seconds, st.rays / st.seconds / 1e6, st.mean,
               st.noise_rmse, out);
    }
    gib_image_free(&img);
    gib_image_free(&se);
    gib_scene_free(&scene);
    return status;
}
