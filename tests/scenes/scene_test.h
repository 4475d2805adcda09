/* gibench scene tests — the checks, the temporary directory and the file writer every scene test
 * uses. A failed check prints FAIL with its file and line and counts; scene_test_end() prints the
 * summary and gives the exit status. */
#ifndef GIB_SCENE_TEST_H
#define GIB_SCENE_TEST_H

#include <math.h>
#include <stddef.h>
#include <stdio.h>

extern int failures;
extern char tmpdir[256]; /* a fresh directory under /tmp, removed by scene_test_end() */

#include "tests/common/check.h"

/* |a - b| <= tol; `why` says where the tolerance comes from. */
#define NEAR(a, b, tol, why)                                                                       \
    CHECK(fabs((double)(a) - (double)(b)) <= (tol), "%s = %.9g, want %.9g +- %g (%s)", #a,         \
          (double)(a), (double)(b), (double)(tol), why)

/* Creates tmpdir as /tmp/<name>_XXXXXX; -1 (after printing FAIL) if it cannot. */
int scene_test_begin(const char *name);
/* Writes text to tmpdir/name and returns the path in out (exits on failure: nothing can follow). */
void write_file(const char *name, const char *text, char *out, size_t n);
/* Loads `text` as a scene file and expects return code `want_rc`, and a message that names the
 * file, `:line:` and contains `phrase` (and `phrase2` when non-NULL). */
void scene_expect_load(const char *what, const char *text, int want_rc, int line,
                       const char *phrase, const char *phrase2);
/* Removes tmpdir and its files, prints "passed"/"FAILED" with the failure count; the exit status. */
int scene_test_end(void);

#endif
