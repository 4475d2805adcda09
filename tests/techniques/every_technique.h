/* gibench tests — what the tests that walk every technique share (test_registry,
 * test_closed_form, test_contract_gl): the techniques gibench runs, then those only tests run
 * (the template), and whether a scene is one a technique runs on, as a matrix decides it. A
 * technique added to either list of techniques/registry.c is walked without a change here. */
#ifndef GIB_TEST_EVERY_TECHNIQUE_H
#define GIB_TEST_EVERY_TECHNIQUE_H

#include <stddef.h>

#include "techniques/technique.h"

#define EVERY_TECHNIQUE_MAX 64

/* Fills out[] with gib_techniques() then gib_techniques_test_only(); returns the count (at most
 * max; more is a failure the caller reports). */
int every_technique(const gib_technique **out, int max);
/* 1 when `s` has every feature of t->scene_needs and one of t->scene_needs_any; else 0 with the
 * reason ("scene lacks sky", "scene has none of mirror,specular") in why. */
int technique_runs_on(const gib_technique *t, const gib_scene *s, char *why, size_t len);

#endif
