/* gibench tests — the one check helper of the C tests. Each macro counts a failure in the including
 * file's `failures` (an int it defines) and prints one line, "PASS" or "FAIL", with file:line, what
 * was checked, the values compared and, for a tolerance or a bound, the reason it is what it is:
 *   CHECK(cond, fmt, ...)                         a condition (FAIL lines only)
 *   CHECK_TRUE(what, cond, detail)                a condition, printed either way
 *   CHECK_NEAR(what, want, got, tol, why)         |got - want| <= tol (equal values pass, inf too)
 *   CHECK_AT_MOST(what, got, bound, why)          got <= bound
 *   CHECK_AT_LEAST(what, got, bound, why)         got >= bound */
#ifndef GIB_TEST_CHECK_H
#define GIB_TEST_CHECK_H

#include <math.h>
#include <stdio.h>
#include <string.h>

#define CHECK(cond, ...)                                                                           \
    do {                                                                                           \
        if (!(cond)) {                                                                             \
            failures++;                                                                            \
            printf("FAIL %s:%d: ", __FILE__, __LINE__);                                            \
            printf(__VA_ARGS__);                                                                   \
            printf("\n");                                                                          \
        }                                                                                          \
    } while (0)

static inline int gib_check_report(const char *file, int line, int ok, const char *what,
                                   const char *detail)
{
    const char *in_tests = strstr(file, "tests/"); /* the path from the repository's root */
    printf("%s %s:%d: %-46s %s\n", ok ? "PASS" : "FAIL", in_tests ? in_tests : file, line, what,
           detail);
    return !ok;
}

static inline int gib_check_near(const char *file, int line, const char *what, double want,
                                 double got, double tol, const char *why)
{
    char detail[512];
    int ok = want == got || fabs(got - want) <= tol;
    snprintf(detail, sizeof detail, "expected %.12g measured %.12g tol %.3g (%s)", want, got, tol,
             why);
    return gib_check_report(file, line, ok, what, detail);
}

static inline int gib_check_bound(const char *file, int line, const char *what, double got,
                                  double bound, int at_most, const char *why)
{
    char detail[512];
    int ok = at_most ? got <= bound : got >= bound;
    snprintf(detail, sizeof detail, "measured %.12g, bound %s %.12g (%s)", got,
             at_most ? "<=" : ">=", bound, why);
    return gib_check_report(file, line, ok, what, detail);
}

#define CHECK_TRUE(what, cond, detail)                                                             \
    (failures += gib_check_report(__FILE__, __LINE__, (cond) != 0, (what), (detail)))
#define CHECK_NEAR(what, want, got, tol, why)                                                      \
    (failures += gib_check_near(__FILE__, __LINE__, (what), (want), (got), (tol), (why)))
#define CHECK_AT_MOST(what, got, bound, why)                                                       \
    (failures += gib_check_bound(__FILE__, __LINE__, (what), (got), (bound), 1, (why)))
#define CHECK_AT_LEAST(what, got, bound, why)                                                      \
    (failures += gib_check_bound(__FILE__, __LINE__, (what), (got), (bound), 0, (why)))

#endif
