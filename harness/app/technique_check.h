/* gibench — the checks every technique is held to, built-in or plugin, in one place: the
 * descriptor against the contract of techniques/technique.h (no GL), and the contract at run time
 * (create / render / destroy at two sizes on a small scene). tests/techniques/test_registry.c and
 * test_contract_gl.c walk every technique through them; `gibench check-technique NAME` runs them
 * for one (harness/app/cmd_check.c). Each failed check prints one line "FAIL <technique>...: what"
 * to `out` and counts; with `verbose` each group that held prints "PASS <technique> <group>". */
#ifndef GIB_TECHNIQUE_CHECK_H
#define GIB_TECHNIQUE_CHECK_H

#include <stdio.h>

#include "harness/gl/gpu_scene.h"
#include "techniques/technique.h"

/* The descriptor: name, source, components, functions; parameters (types, ranges, defaults, help,
 * no name twice), passes ([a-z0-9_]+, at least one, none twice), reference bindings (real
 * parameters, ao binds a length dmax), presets (applied, named back, explicit values kept) and
 * constraints (choices, multiples, rules over declared parameters that defaults and presets hold).
 * Returns the number of failed checks. */
int gib_check_descriptor(const gib_technique *t, FILE *out, int verbose);

/* "" or name=value pairs joined by ';' (name [a-z0-9_]+, value a number): a technique's counters. */
int gib_counters_parse(const char *s);

/* 1 when scene s has every feature of t->scene_needs and one of t->scene_needs_any; else 0 with the
 * reason ("scene lacks sky", "scene has none of mirror,specular") in why. */
int gib_technique_runs_on(const gib_technique *t, const gib_scene *s, char *why, size_t len);

/* The small scenes the run-time check uses, loaded on first use and shared between techniques:
 * furnace (a point light, a closed room), plane_box_sky (a spot light, a sky), ring (a mirror). */
#define GIB_CHECK_SCENE_COUNT 3
typedef struct gib_check_scenes {
    gib_scene scene[GIB_CHECK_SCENE_COUNT];
    gib_gpu_scene gpu[GIB_CHECK_SCENE_COUNT];
    int state[GIB_CHECK_SCENE_COUNT]; /* 0 not tried, 1 loaded, -1 failed */
} gib_check_scenes;
/* Frees what was loaded (needs the GL context still current). */
void gib_check_scenes_free(gib_check_scenes *s);

/* The contract at run time (a GL context current; the scenes zeroed before first use): on the first
 * scene t accepts, at 32x24 and 48x40, two frames each with default parameters and a ledger of its
 * own: create returns a state, render returns 0, no GL error; at least one timed pass, each one of
 * the descriptor's `passes`, none left open; every output value finite; a status of status.h's;
 * counters that parse; after destroy the ledger empty and no GL error. Returns the number of failed
 * checks, or -1 when no scene of the set suits t (printed as SKIP with each scene's reason). */
int gib_check_runtime(const gib_technique *t, gib_check_scenes *scenes, FILE *out, int verbose);

#endif
