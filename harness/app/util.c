/* gibench — small helpers shared by the subcommands: option parsing, directories, revision. */
#include <errno.h>
#include <math.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

#include "app.h"
#include "harness/imaging/flip.h"

int gib_parse_size(const char *opt, const char *s, int *w, int *h, gib_error *err)
{
    char *end;
    errno = 0;
    long a = strtol(s, &end, 10);
    if (end == s || (*end != 'x' && *end != 'X'))
        return gib_fail(err, "%s expects WIDTHxHEIGHT (e.g. 256x256), got '%s'", opt, s);
    const char *p = end + 1;
    long b = strtol(p, &end, 10);
    if (end == p || *end || errno || a < 1 || b < 1 || a > 16384 || b > 16384)
        return gib_fail(err, "%s expects WIDTHxHEIGHT with sides 1..16384, got '%s'", opt, s);
    *w = (int)a;
    *h = (int)b;
    return 0;
}

int gib_parse_int(const char *opt, const char *s, long min, long max, long *out, gib_error *err)
{
    char *end;
    errno = 0;
    long v = strtol(s, &end, 10);
    if (end == s || *end || errno)
        return gib_fail(err, "%s expects an integer, got '%s'", opt, s);
    if (v < min || v > max)
        return gib_fail(err, "%s = %ld is outside [%ld, %ld]", opt, v, min, max);
    *out = v;
    return 0;
}

int gib_parse_float(const char *opt, const char *s, double min, double max, double *out,
                    gib_error *err)
{
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    if (end == s || *end || errno)
        return gib_fail(err, "%s expects a number, got '%s'", opt, s);
    if (!(v >= min && v <= max))
        return gib_fail(err, "%s = %g is outside [%g, %g]", opt, v, min, max);
    *out = v;
    return 0;
}

int gib_cli_load_scene(const char *cmd, const char *name, long camera, gib_scene *scene)
{
    gib_error err;
    int rc = gib_scene_load(name, scene, &err);
    if (rc < 0) {
        fprintf(stderr, "gibench %s: %s\n", cmd, err.msg);
        return rc == GIB_SCENE_UNAVAILABLE ? 3 : 1;
    }
    if (camera < 0 || camera >= (long)scene->camera_count) {
        fprintf(stderr, "gibench %s: --camera %ld: scene '%s' has %u camera(s)\n", cmd, camera,
                scene->name, scene->camera_count);
        gib_scene_free(scene);
        return 2;
    }
    return 0;
}

int gib_mkdirs(const char *path, gib_error *err)
{
    char buf[4096];
    snprintf(buf, sizeof buf, "%s", path);
    for (char *p = buf + 1; *p; p++) {
        if (*p != '/')
            continue;
        *p = 0;
        if (mkdir(buf, 0777) < 0 && errno != EEXIST)
            return gib_fail(err, "cannot create directory '%s': %s", buf, strerror(errno));
        *p = '/';
    }
    if (mkdir(buf, 0777) < 0 && errno != EEXIST)
        return gib_fail(err, "cannot create directory '%s': %s", buf, strerror(errno));
    return 0;
}

void gib_path_folder(const char *path, char *out, size_t size)
{
    const char *slash = strrchr(path, '/');
    if (!slash)
        snprintf(out, size, ".");
    else if (slash == path)
        snprintf(out, size, "/");
    else
        snprintf(out, size, "%.*s", (int)(slash - path), path);
}

int gib_check_output(const char *opt, const char *path, const char *ext, gib_error *err)
{
    size_t n = strlen(path), e = ext ? strlen(ext) : 0;
    if (n == 0)
        return gib_fail(err, "%s: empty path", opt);
    if (ext && (n <= e || strcasecmp(path + n - e, ext) != 0))
        return gib_fail(err, "%s %s: the file name must end in %s", opt, path, ext);
    struct stat sb;
    if (stat(path, &sb) == 0) {
        if (S_ISDIR(sb.st_mode))
            return gib_fail(err, "%s %s is a directory", opt, path);
        if (access(path, W_OK) != 0)
            return gib_fail(err, "%s %s: cannot write it: %s", opt, path, strerror(errno));
    }
    char dir[4096];
    if (n >= sizeof dir)
        return gib_fail(err, "%s: path too long (%zu characters)", opt, n);
    gib_path_folder(path, dir, sizeof dir);
    if (stat(dir, &sb) != 0 || !S_ISDIR(sb.st_mode))
        return gib_fail(err, "%s %s: folder %s does not exist", opt, path, dir);
    if (access(dir, W_OK | X_OK) != 0)
        return gib_fail(err, "%s %s: cannot write in folder %s: %s", opt, path, dir,
                        strerror(errno));
    return 0;
}

const char *gib_git_revision(void)
{
    static char rev[64];
    if (rev[0])
        return rev;
#ifdef GIB_REVISION
    snprintf(rev, sizeof rev, "%s", GIB_REVISION);
    return rev;
#endif
    snprintf(rev, sizeof rev, "unknown");
    FILE *p = popen("git -C '" GIB_PROJECT_ROOT "' rev-parse --short=12 HEAD 2>/dev/null", "r");
    if (p) {
        char line[64];
        if (fgets(line, sizeof line, p)) {
            line[strcspn(line, "\r\n")] = 0;
            if (line[0])
                snprintf(rev, sizeof rev, "%s", line);
        }
        pclose(p);
        /* A dirty tree is marked, so a result is never attributed to a commit it did not come from.
         * results/ is left out: it holds what gibench writes (make reproduce moves the committed
         * tables aside before it runs), never what the numbers are computed by. */
        p = popen("git -C '" GIB_PROJECT_ROOT "' status --porcelain --untracked-files=no -- . "
                  "':(exclude)results' 2>/dev/null", "r");
        if (p) {
            char l2[8];
            if (fgets(l2, sizeof l2, p) && strcmp(rev, "unknown"))
                strncat(rev, "-dirty", sizeof rev - strlen(rev) - 1);
            pclose(p);
        }
    }
    return rev;
}

int gib_score_flip(const gib_image *ref, const gib_image *img, float exposure, float *ldr_map,
                   gib_metrics *m, gib_error *err)
{
    m->flip = m->hdrflip = NAN;
    int w = ref->width, h = ref->height;
    size_t n = (size_t)w * h;
    if (img->width != w || img->height != h || ref->channels < 3 || img->channels < 3)
        return 0; /* gib_metrics_compute reports the mismatch */
    float *a = malloc(4 * 3 * n * sizeof(float));
    if (!a)
        return gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY,
                             "FLIP: out of memory for a %dx%d image", w, h);
    float *b = a + 3 * n, *la = b + 3 * n, *lb = la + 3 * n;
    for (size_t i = 0; i < n; i++)
        for (int c = 0; c < 3; c++) {
            a[3 * i + c] = ref->px[i * ref->channels + c];
            b[3 * i + c] = img->px[i * img->channels + c];
            la[3 * i + c] = fminf(fmaxf(exposure * a[3 * i + c], 0.0f), 1.0f);
            lb[3 * i + c] = fminf(fmaxf(exposure * b[3 * i + c], 0.0f), 1.0f);
        }
    /* A NaN mean (non-finite samples, black reference) is the answer: the row's nonfinite count
     * and status already say what is wrong with the image, so the message is not needed. */
    gib_error ferr = {0};
    const float ppd = gib_flip_default_ppd();
    m->flip = gib_flip_ldr(la, lb, w, h, ppd, ldr_map, &ferr);
    if (!isnan(m->flip))
        m->hdrflip = gib_flip_hdr(a, b, w, h, ppd, NULL, NULL, NULL, &ferr);
    free(a);
    if (isnan(m->flip + m->hdrflip) && ferr.code == GIB_ERR_OUT_OF_MEMORY)
        return gib_fail_code(err, ferr.code, "%s", ferr.msg);
    return 0;
}

int gib_score_and_save(const gib_image *ref, const gib_image *img, float exposure, const char *dir,
                       const char *name, gib_metrics *m, gib_error *err)
{
    if (gib_metrics_compute(ref, img, exposure, m, err) < 0)
        return -1;
    float *map = dir ? malloc((size_t)ref->width * ref->height * sizeof(float)) : NULL;
    if (dir && !map)
        return gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY,
                             "FLIP: out of memory for a %dx%d map", ref->width, ref->height);
    if (gib_score_flip(ref, img, exposure, map, m, err) < 0) {
        free(map);
        return -1;
    }
    if (!dir)
        return 0;
    char path[4096];
    if (!isnan(m->flip)) {
        snprintf(path, sizeof path, "%s/%s_flip.png", dir, name);
        if (gib_flip_write_png(path, map, ref->width, ref->height, err) < 0) {
            free(map);
            return GIB_IMAGE_WRITE_FAILED;
        }
    }
    free(map);
    snprintf(path, sizeof path, "%s/%s.exr", dir, name);
    if (gib_exr_write(path, img, NULL, 0, err) < 0)
        return GIB_IMAGE_WRITE_FAILED;
    snprintf(path, sizeof path, "%s/%s.png", dir, name);
    if (gib_png_write_preview(path, img, exposure, err) < 0)
        return GIB_IMAGE_WRITE_FAILED;
    snprintf(path, sizeof path, "%s/%s_error.png", dir, name);
    if (gib_png_write_error_map(path, ref, img, 0.0f, err) < 0)
        return GIB_IMAGE_WRITE_FAILED;
    return 0;
}

int gib_score_image(const gib_image *ref, double ref_noise_rmse, const gib_image *img,
                    float exposure, const char *dir, const char *name, gib_score *s,
                    gib_error *err)
{
    int rc = gib_score_and_save(ref, img, exposure, dir, name, &s->m, err);
    if (rc == 0 || rc == GIB_IMAGE_WRITE_FAILED)
        gib_rmse_interval(s->m.rmse, ref_noise_rmse, (long)ref->width * ref->height, &s->rmse);
    return rc;
}

const char *gib_ref_setting_name(int setting)
{
    return setting == GIB_REF_AO_DMAX ? "dmax" : setting == GIB_REF_AO_OBSCURANCE ? "obscurance" : "";
}

double gib_ref_setting_default(int setting)
{
    return setting == GIB_REF_AO_DMAX ? INFINITY : 0.0;
}

void gib_ref_request_match(gib_ref_request *rq, const gib_technique *t, const gib_params *p,
                           unsigned output)
{
    rq->dmax = (float)gib_ref_setting_default(GIB_REF_AO_DMAX);
    rq->obscurance = (int)gib_ref_setting_default(GIB_REF_AO_OBSCURANCE);
    for (const gib_ref_binding *b = t->reference; b && b->setting != GIB_REF_END; b++) {
        if (!(b->components & output))
            continue;
        double v = gib_param_float(t, p, b->param);
        switch (b->setting) {
        case GIB_REF_AO_DMAX: rq->dmax = (float)v; break;
        case GIB_REF_AO_OBSCURANCE: rq->obscurance = (int)v; break;
        }
    }
}
