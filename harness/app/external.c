/* gibench — external techniques (external.h): their matrix section, and one run: the job written,
 * the command run under its timeout, its images and timings read back into a run result. */
#define _GNU_SOURCE
#include "external.h"

#include <errno.h>
#include <fcntl.h>
#include <ftw.h>
#include <limits.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "app.h"
#include "matrix.h"
#include "harness/base/status.h"

/* ---- the matrix section ---- */

static int parse_components(const char *value, unsigned *bits, gib_error *err)
{
    char buf[256];
    snprintf(buf, sizeof buf, "%s", value);
    *bits = 0;
    for (char *tok = strtok(buf, ", \t"); tok; tok = strtok(NULL, ", \t")) {
        unsigned bit = 0;
        for (unsigned b = 1; b <= GIB_OUT_CAUSTIC; b <<= 1)
            if (!strcmp(tok, gib_output_name(b)))
                bit = b;
        if (!bit)
            return gib_fail(err, "components: unknown component '%s' (ao, direct, indirect, "
                            "glossy, caustic)", tok);
        *bits |= bit;
    }
    return *bits ? 0 : gib_fail(err, "components: empty list");
}

int gib_external_set(gib_external *x, const char *key, const char *value, gib_error *err)
{
    if (!strcmp(key, "command")) {
        if (!*value || strlen(value) >= sizeof x->command)
            return gib_fail(err, "command: empty or over %zu characters", sizeof x->command - 1);
        snprintf(x->command, sizeof x->command, "%s", value);
    } else if (!strcmp(key, "version")) {
        if (!*value || strlen(value) >= sizeof x->version || strpbrk(value, ";=|,\"\n"))
            return gib_fail(err, "version: '%s' must be 1 to %zu characters without ; = | , \"",
                            value, sizeof x->version - 1);
        snprintf(x->version, sizeof x->version, "%s", value);
    } else if (!strcmp(key, "components")) {
        return parse_components(value, &x->technique.components, err);
    } else if (!strcmp(key, "timeout_s")) {
        return gib_parse_float("timeout_s", value, 0.001, 86400.0, &x->timeout_s, err);
    } else {
        return gib_fail(err, "unknown key '%s' in [external.%s] (command, version, components, "
                        "timeout_s)", key, x->name);
    }
    return 0;
}

int gib_external_finish(gib_external *x, const char *matrix_path, gib_error *err)
{
    if (!x->command[0] || !x->technique.components)
        return gib_fail(err, "[external.%s] needs command and components", x->name);
    if (!x->version[0])
        snprintf(x->version, sizeof x->version, "unversioned");
    if (x->timeout_s <= 0)
        x->timeout_s = 600;
    snprintf(x->tech_name, sizeof x->tech_name, GIB_EXTERNAL_PREFIX "%s", x->name);
    gib_path_folder(matrix_path, x->workdir, sizeof x->workdir);
    char abs[PATH_MAX];
    if (realpath(x->workdir, abs) && strlen(abs) < sizeof x->workdir)
        memcpy(x->workdir, abs, strlen(abs) + 1);
    gib_technique *t = &x->technique;
    t->name = x->tech_name;
    t->source = x->command;
    if (t->components & GIB_OUT_AO) {
        x->params[0] = (gib_param_spec){"dmax", GIB_PARAM_LENGTH, INFINITY, 0, INFINITY,
                                        "the AO range the reference and the renderer use"};
        x->params[1] = (gib_param_spec){"obscurance", GIB_PARAM_INT, 0, 0, 1,
                                        "1: obscurance min(d/dmax, 1) instead of visibility"};
        x->reference[0] = (gib_ref_binding){GIB_OUT_AO, GIB_REF_AO_DMAX, "dmax"};
        x->reference[1] = (gib_ref_binding){GIB_OUT_AO, GIB_REF_AO_OBSCURANCE, "obscurance"};
    }
    t->params = x->params;
    t->reference = x->reference;
    return 0;
}

void gib_external_params_key(const gib_external *x, const gib_params *p, char *out, int len)
{
    gib_params_key(&x->technique, p, out, len);
    size_t n = strlen(out);
    snprintf(out + n, (size_t)len - n, "%sversion=%s", n ? ";" : "", x->version);
}

/* ---- running the command ---- */

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec / 1e6;
}

/* The last `max` bytes of a file on one line (control characters become spaces), or "". */
static void file_tail(const char *path, char *out, size_t max)
{
    out[0] = 0;
    FILE *f = fopen(path, "rb");
    if (!f)
        return;
    fseek(f, 0, SEEK_END);
    long size = ftell(f);
    long from = size > (long)max - 1 ? size - (long)max + 1 : 0;
    fseek(f, from, SEEK_SET);
    size_t n = fread(out, 1, max - 1, f);
    fclose(f);
    out[n] = 0;
    while (n > 0 && (out[n - 1] == '\n' || out[n - 1] == ' ' || out[n - 1] == '\r'))
        out[--n] = 0;
    for (size_t i = 0; i < n; i++)
        if ((unsigned char)out[i] < 0x20)
            out[i] = ' ';
}

/* In the child: the job folder's log files as stdout and stderr, the environment, then sh -c. */
static void exec_child(const gib_external *x, const char *dir, const char *job)
{
    char path[2200], cmd[1200];
    setpgid(0, 0);
    snprintf(path, sizeof path, "%s/stdout.txt", dir);
    int out = open(path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    snprintf(path, sizeof path, "%s/stderr.txt", dir);
    int errfd = open(path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    int in = open("/dev/null", O_RDONLY);
    if (out < 0 || errfd < 0 || in < 0 || dup2(in, 0) < 0 || dup2(out, 1) < 0 ||
        dup2(errfd, 2) < 0 || chdir(x->workdir) != 0)
        _exit(126);
    setenv("GIBENCH_JOB", job, 1);
    setenv("GIBENCH_PROJECT_ROOT", GIB_PROJECT_ROOT, 1);
    snprintf(cmd, sizeof cmd, "%s \"$1\"", x->command);
    execl("/bin/sh", "sh", "-c", cmd, "sh", job, (char *)NULL);
    _exit(127);
}

/* Runs the command on the job; sets r's status when it fails or times out. Returns 0 on exit 0. */
static int run_command(const gib_external *x, const char *dir, gib_run_result *r, double *ms)
{
    char job[2200], tail[600], errpath[2200];
    snprintf(job, sizeof job, "%s/job.json", dir);
    snprintf(errpath, sizeof errpath, "%s/stderr.txt", dir);
    const double start = now_ms();
    pid_t pid = fork();
    if (pid < 0) {
        snprintf(r->status, sizeof r->status, "%s", gib_status_name(GIB_STATUS_EXTERNAL_FAILED));
        return gib_fail(&r->err, "external '%s': cannot start: %s", x->name, strerror(errno));
    }
    if (pid == 0)
        exec_child(x, dir, job);
    setpgid(pid, pid);
    int st = 0, timed_out = 0;
    while (waitpid(pid, &st, WNOHANG) == 0) {
        if (now_ms() - start > x->timeout_s * 1e3) {
            kill(-pid, SIGKILL);
            kill(pid, SIGKILL);
            waitpid(pid, &st, 0);
            timed_out = 1;
            break;
        }
        nanosleep(&(struct timespec){0, 5000000}, NULL);
    }
    *ms = now_ms() - start;
    file_tail(errpath, tail, sizeof tail);
    if (timed_out) {
        snprintf(r->status, sizeof r->status, "%s", gib_status_name(GIB_STATUS_TIMEOUT));
        return gib_fail(&r->err, "external '%s' (%s): no result after its timeout_s %g s, killed; "
                        "stderr: %s", x->name, x->command, x->timeout_s, tail);
    }
    if (WIFEXITED(st) && WEXITSTATUS(st) == 0)
        return 0;
    snprintf(r->status, sizeof r->status, "%s", gib_status_name(GIB_STATUS_EXTERNAL_FAILED));
    if (WIFSIGNALED(st))
        return gib_fail(&r->err, "external '%s' (%s): killed by signal %d; stderr: %s", x->name,
                        x->command, WTERMSIG(st), tail);
    return gib_fail(&r->err, "external '%s' (%s): exited with status %d%s; stderr: %s", x->name,
                    x->command, WEXITSTATUS(st),
                    WEXITSTATUS(st) == 127 ? " (command not found?)" : "", tail);
}

/* ---- reading back ---- */

static void set_readback_failed(gib_run_result *r)
{
    snprintf(r->status, sizeof r->status, "%s", gib_status_name(GIB_STATUS_READBACK_FAILED));
}

/* One image per component, each of the job's size (RGB or RGBA or Y, float or half). */
static int read_images(const gib_external_request *rq, const char *dir, gib_run_result *r)
{
    const gib_external *x = rq->x;
    char path[2200], tail[400], errpath[2200];
    snprintf(errpath, sizeof errpath, "%s/stderr.txt", dir);
    for (unsigned bit = 1; bit <= GIB_OUT_CAUSTIC; bit <<= 1) {
        if (!(x->technique.components & bit))
            continue;
        snprintf(path, sizeof path, "%s/%s.exr", dir, gib_output_name(bit));
        const int i = r->output_count;
        r->output_components[i] = bit;
        gib_error e;
        if (access(path, F_OK) != 0) {
            set_readback_failed(r);
            file_tail(errpath, tail, sizeof tail);
            return gib_fail(&r->err, "external '%s' (%s) exited 0 but wrote no %s.exr; "
                            "stderr: %s", x->name, x->command, gib_output_name(bit), tail);
        }
        if (gib_exr_read(path, &r->images[i], NULL, NULL, &e) < 0) {
            set_readback_failed(r);
            return gib_fail(&r->err, "external '%s': %s", x->name, e.msg);
        }
        r->output_count++;
        if (r->images[i].width != rq->width || r->images[i].height != rq->height) {
            set_readback_failed(r);
            return gib_fail(&r->err, "external '%s': %s.exr is %dx%d, the job asked for %dx%d",
                            x->name, gib_output_name(bit), r->images[i].width,
                            r->images[i].height, rq->width, rq->height);
        }
    }
    return 0;
}

/* ---- the temporary folder ---- */

static int remove_entry(const char *path, const struct stat *sb, int flag, struct FTW *ftw)
{
    (void)sb, (void)flag, (void)ftw;
    return remove(path);
}

static void remove_job(const char *dir)
{
    const char *keep = getenv("GIBENCH_KEEP_JOBS");
    if (keep && *keep && strcmp(keep, "0"))
        fprintf(stderr, "gibench run: external job kept in %s (GIBENCH_KEEP_JOBS)\n", dir);
    else
        nftw(dir, remove_entry, 16, FTW_DEPTH | FTW_PHYS);
}

/* The job written at the row's instant (a moving scene posed), the command run, the outputs
 * read. */
static void run_job(const gib_external_request *rq, const char *dir, gib_run_result *r)
{
    gib_scene posed;
    gib_external_request at = *rq;
    if (gib_scene_posed(rq->scene, rq->time, &posed, &r->err) < 0) {
        snprintf(r->status, sizeof r->status, "%s", gib_status_name(GIB_STATUS_SCENE_UPDATE_FAILED));
        return;
    }
    at.scene = &posed;
    int rc = gib_external_write_job(&at, dir, &r->err);
    gib_scene_posed_free(&posed);
    if (rc < 0) {
        snprintf(r->status, sizeof r->status, "%s", gib_status_name(GIB_STATUS_EXTERNAL_FAILED));
        gib_error_prefix(&r->err, "external '%s': writing the job", rq->x->name);
        return;
    }
    double ms = 0;
    if (run_command(rq->x, dir, r, &ms) < 0 || read_images(rq, dir, r) < 0)
        return;
    r->first_frame_ms = ms; /* the command's wall time: start, load, render, write */
    char path[2200];
    snprintf(path, sizeof path, "%s/timings.json", dir);
    if (access(path, F_OK) == 0 && gib_external_read_timings(path, r, &r->err) < 0) {
        set_readback_failed(r);
        gib_error_prefix(&r->err, "external '%s'", rq->x->name);
        return;
    }
    snprintf(r->status, sizeof r->status, "%s", gib_status_name(GIB_STATUS_OK));
    r->ok = 1;
}

void gib_external_run(const gib_external_request *rq, gib_run_result *r)
{
    memset(r, 0, sizeof *r);
    r->driver_bytes = -1;
    r->warmup_frames = rq->warmup;
    r->frames = rq->frames;
    r->gpu_total.median_ms = r->gpu_total.min_ms = r->gpu_total.max_ms = NAN;
    r->gpu_total.iqr_ms = r->gpu_total.first_ms = NAN;
    r->cpu_total = r->gpu_total;
    snprintf(r->renderer, sizeof r->renderer, "%s %s", rq->x->name, rq->x->version);
    snprintf(r->status, sizeof r->status, "%s", gib_status_name(GIB_STATUS_EXTERNAL_FAILED));
    if (gib_params_check(&rq->x->technique, rq->params, &r->err) < 0)
        return;
    const char *tmp = getenv("TMPDIR");
    char dir[1024];
    snprintf(dir, sizeof dir, "%s/gibench-ext-XXXXXX", tmp && *tmp ? tmp : "/tmp");
    if (!mkdtemp(dir)) {
        gib_fail(&r->err, "external '%s': cannot make a job folder %s: %s", rq->x->name, dir,
                 strerror(errno));
        return;
    }
    run_job(rq, dir, r);
    remove_job(dir);
}
