/* The technique contract (techniques/technique.h) at run time, over every technique: the registry
 * walked and the test-only template (tests/techniques/every_technique.h), so a technique is
 * checked the day it is registered. test_registry checks the descriptors without GL; this drives
 * create / render / status / counters / destroy as the runner does, but with a ledger of its own,
 * which the runner would empty behind a technique's back.
 *
 * Each technique runs on the first of SCENES it accepts (its scene_needs; none: skipped, the
 * reason printed), at two sizes (a technique sized at create must not keep the first size's
 * objects), two frames each (the second finds the first's state), default parameters. Per size:
 *  - create returns a state, render returns 0 both frames, and no GL error is left;
 *  - at least one timed pass, none left open after render;
 *  - every output value finite (no NaN, no Inf);
 *  - every timed pass one of the descriptor's `passes` (the names the report's tables read);
 *  - status one of harness/base/status.h's (the words the CSV's status column can hold);
 *  - counters "" or name=value pairs joined by ';' (name [a-z0-9_]+, value a number);
 *  - after destroy the ledger empty: no object, no byte (what destroy forgot would be freed by
 *    the runner and never show up), and no GL error.
 * Runtime on llvmpipe (2 shared cores): 31-35 s in the release build, 33-43 s under ASan, two
 * thirds of it ldm_ao's and ldm_indirect's LDMs. */
#include <glad/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness/gl/context.h"
#include "harness/gl/gpu_scene.h"
#include "harness/gl/timers.h"
#include "harness/gl/view.h"
#include "tests/techniques/every_technique.h"

static int failures;
#include "tests/common/check.h"

/* Small scenes that between them have every feature a technique asks for: a point light and a
 * closed room (furnace), a spot light and a sky (plane_box_sky), a mirror (ring). */
static const char *const SCENES[] = {"furnace", "plane_box_sky", "ring"};
#define SCENE_COUNT 3
static const int SIZES[2][2] = {{32, 24}, {48, 40}};
#define FRAMES 2
#define MAX_TARGETS 5

/* The words a technique's status may return (the CSV's status column): ARCHITECTURE.md, "Data
 * flow of a matrix row". A technique with a new word adds it here and there. */

typedef struct loaded {
    gib_scene scene;
    gib_gpu_scene gpu;
    int state; /* 0 not tried, 1 loaded, -1 failed */
} loaded;


/* "" or name=value;name=value with name [a-z0-9_]+ and value a number. */
static int counters_parse(const char *s)
{
    while (*s) {
        const char *name = s;
        while ((*s >= 'a' && *s <= 'z') || (*s >= '0' && *s <= '9') || *s == '_')
            s++;
        if (s == name || *s++ != '=')
            return 0;
        char *end;
        strtod(s, &end);
        if (end == s || (*end && *end != ';'))
            return 0;
        s = *end ? end + 1 : end;
        if (*end && !*s)
            return 0; /* a trailing ';' */
    }
    return 1;
}

/* The output targets the runner would hand the technique (harness/app/runner.c), in a ledger of
 * their own. Returns the count, or -1. */
static int make_targets(unsigned components, int w, int h, gib_ledger *out,
                        gib_image_target *targets, gib_error *err)
{
    unsigned depth = gib_gpu_renderbuffer(out, "output.depth", GL_DEPTH_COMPONENT24, w, h, err);
    if (!depth)
        return -1;
    int n = 0;
    for (unsigned bit = 1; bit && n < MAX_TARGETS; bit <<= 1) {
        if (!(components & bit))
            continue;
        unsigned tex = gib_gpu_texture(out, "output.color", GL_TEXTURE_2D, w, h, 1, GL_RGBA32F, 1,
                                       err);
        if (!tex)
            return -1;
        unsigned fbo = 0;
        glCreateFramebuffers(1, &fbo);
        glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, tex, 0);
        glNamedFramebufferRenderbuffer(fbo, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth);
        const float zero[4] = {0, 0, 0, 0};
        glClearNamedFramebufferfv(fbo, GL_COLOR, 0, zero);
        targets[n++] = (gib_image_target){.component = bit, .fbo = fbo, .texture = tex};
    }
    return n;
}

/* Non-finite RGB values over the targets. */
static long nonfinite_outputs(const gib_image_target *targets, int n, int w, int h)
{
    float *rgba = malloc((size_t)w * h * 16);
    long bad = 0;
    for (int i = 0; rgba && i < n; i++) {
        glGetTextureImage(targets[i].texture, 0, GL_RGBA, GL_FLOAT, w * h * 16, rgba);
        for (long p = 0; p < (long)w * h; p++)
            for (int c = 0; c < 3; c++)
                bad += !isfinite(rgba[4 * p + c]);
    }
    free(rgba);
    return rgba ? bad : -1;
}

/* Whether `name` is one of the passes t's descriptor declares. */
static int declared_pass(const gib_technique *t, const char *name)
{
    for (int i = 0; t->passes && t->passes[i]; i++)
        if (!strcmp(t->passes[i], name))
            return 1;
    return 0;
}

/* What the frames left: the passes, the status, the counters, the images. */
static void check_frames(const gib_technique *t, void *self, const gib_timers *timers,
                         const gib_image_target *targets, int n, int w, int h)
{
    CHECK(timers->pass_count > 0, "%s %dx%d: no timed pass", t->name, w, h);
    for (int i = 0; i < timers->pass_count; i++)
        CHECK(declared_pass(t, timers->names[i]), "%s %dx%d: pass '%s' is not in its descriptor's "
              "passes", t->name, w, h, timers->names[i]);
    CHECK(timers->active < 0, "%s %dx%d: a pass left open after render", t->name, w, h);
    gib_status status = t->status ? t->status(self) : GIB_STATUS_OK;
    CHECK(gib_status_name(status) != NULL, "%s %dx%d: status %d is not one of status.h's",
          t->name, w, h, (int)status);
    char counters[256] = "";
    if (t->counters)
        t->counters(self, counters, sizeof counters);
    CHECK(counters_parse(counters), "%s %dx%d: counters '%s' are not name=value;...", t->name, w,
          h, counters);
    long bad = nonfinite_outputs(targets, n, w, h);
    CHECK(bad == 0, "%s %dx%d: %ld non-finite output values", t->name, w, h, bad);
    printf("  %dx%d: %d passes, status %s, counters '%s', %ld non-finite\n", w, h,
           timers->pass_count, gib_status_name(status), counters, bad);
}

/* create, FRAMES x render, the checks, destroy, at one size. */
static void run_size(const gib_technique *t, const loaded *s, int w, int h)
{
    gib_error err = {0};
    gib_ledger ledger, out;
    gib_ledger_init(&ledger);
    gib_ledger_init(&out);
    gib_image_target targets[MAX_TARGETS];
    int n = make_targets(t->components, w, h, &out, targets, &err);
    gib_params p;
    gib_params_default(t, &p);
    glGetError();
    void *self = n > 0 ? t->create(&s->gpu, &p, w, h, &ledger, &err) : NULL;
    CHECK(self, "%s %dx%d: create failed: %s", t->name, w, h, err.msg);
    if (self) {
        gib_timers timers;
        gib_timers_init(&timers);
        gib_view view;
        gib_view_make(s->gpu.scene, &s->gpu.scene->cameras[0], w, h, 0, &view);
        int rc = 0;
        for (int f = 0; f < FRAMES && rc == 0; f++) {
            gib_timers_frame_begin(&timers, 1);
            rc = t->render(self, &view, &timers, targets, n, &err);
            gib_timers_frame_end(&timers);
        }
        CHECK(rc == 0, "%s %dx%d: render failed: %s", t->name, w, h, err.msg);
        CHECK(gib_gl_check(t->name, &err) == 0, "%s %dx%d: GL error after render: %s", t->name, w,
              h, err.msg);
        check_frames(t, self, &timers, targets, n, w, h);
        gib_timers_destroy(&timers);
        t->destroy(self);
        CHECK(ledger.count == 0 && ledger.current_bytes == 0,
              "%s %dx%d: destroy left %d objects, %llu bytes in the ledger (first '%s')", t->name,
              w, h, ledger.count, (unsigned long long)ledger.current_bytes,
              ledger.count ? ledger.entries[0].label : "");
        CHECK(gib_gl_check(t->name, &err) == 0, "%s %dx%d: GL error after destroy: %s", t->name,
              w, h, err.msg);
    }
    gib_ledger_release_all(&ledger);
    for (int i = 0; i < n; i++)
        glDeleteFramebuffers(1, &targets[i].fbo);
    gib_ledger_release_all(&out);
}

/* The first scene of SCENES the technique accepts, loaded on first use; NULL: none (printed). */
static const loaded *scene_for(const gib_technique *t, loaded *scenes)
{
    char why[SCENE_COUNT][256];
    for (int i = 0; i < SCENE_COUNT; i++) {
        if (scenes[i].state == 0) {
            gib_error err;
            int rc = gib_scene_load(SCENES[i], &scenes[i].scene, &err);
            if (rc == 0 && gib_gpu_scene_upload(&scenes[i].scene, &scenes[i].gpu, &err) < 0) {
                gib_scene_free(&scenes[i].scene);
                rc = -1;
            }
            scenes[i].state = rc == 0 ? 1 : -1;
            CHECK(rc == 0, "scene %s: %s", SCENES[i], err.msg);
        }
        if (scenes[i].state > 0 && technique_runs_on(t, &scenes[i].scene, why[i], sizeof why[i]))
            return &scenes[i];
        if (scenes[i].state < 0)
            snprintf(why[i], sizeof why[i], "not loaded");
    }
    printf("SKIP %s: no test scene it runs on (", t->name);
    for (int i = 0; i < SCENE_COUNT; i++)
        printf("%s%s: %s", i ? "; " : "", SCENES[i], why[i]);
    printf(")\n");
    return NULL;
}

/* The parser on what it must take and refuse, so a pass means the counters were read. */
static void check_parser(void)
{
    static const char *const good[] = {"", "photons=6954", "a=1;b_2=0.5", "n=-3;m=1e6"};
    static const char *const bad[] = {"photons", "=3", "a=1;", "a=x", "a=1 b=2", "A=1", "a=1;;b=2"};
    for (size_t i = 0; i < sizeof good / sizeof good[0]; i++)
        CHECK(counters_parse(good[i]), "counters parser refuses '%s'", good[i]);
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++)
        CHECK(!counters_parse(bad[i]), "counters parser takes '%s'", bad[i]);
}

int main(void)
{
    check_parser();
    gib_error err;
    gib_gl_info info;
    if (gib_gl_init(GIB_BACKEND_AUTO, &info, &err) < 0) {
        CHECK(0, "set-up: %s", err.msg);
        return 1;
    }
    loaded scenes[SCENE_COUNT] = {0};
    const gib_technique *all[EVERY_TECHNIQUE_MAX];
    int n = every_technique(all, EVERY_TECHNIQUE_MAX);
    CHECK(n <= EVERY_TECHNIQUE_MAX, "%d techniques, the test holds %d", n, EVERY_TECHNIQUE_MAX);
    for (int i = 0; i < n && i < EVERY_TECHNIQUE_MAX; i++) {
        const loaded *s = scene_for(all[i], scenes);
        if (!s)
            continue;
        const double start = gib_now_ms();
        printf("%s on %s:\n", all[i]->name, s->scene.name);
        for (int k = 0; k < 2; k++)
            run_size(all[i], s, SIZES[k][0], SIZES[k][1]);
        printf("  (%.1f s)\n", (gib_now_ms() - start) / 1000);
    }
    for (int i = 0; i < SCENE_COUNT; i++)
        if (scenes[i].state > 0) {
            gib_gpu_scene_free(&scenes[i].gpu);
            gib_scene_free(&scenes[i].scene);
        }
    gib_gl_shutdown();
    printf("%s: the technique contract at run time (%s)\n", failures ? "FAIL" : "PASS",
           info.renderer);
    return failures ? 1 : 0;
}
