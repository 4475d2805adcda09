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
#include "harness/imaging/score.h"

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

int gib_score_and_save(const gib_image *ref, const gib_image *img, float exposure, const char *dir,
                       const char *name, gib_metrics *m, gib_error *err)
{
    return gib_score_pair(ref, img, exposure, dir, name, m, err);
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
