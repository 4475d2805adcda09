/* gibench tests — CHECK(cond, fmt, ...): prints "FAIL file:line: message" and counts the failure in
 * the including file's `failures` (an int it defines) when cond is false. */
#ifndef GIB_TEST_CHECK_H
#define GIB_TEST_CHECK_H

#include <stdio.h>

#define CHECK(cond, ...)                                                                           \
    do {                                                                                           \
        if (!(cond)) {                                                                             \
            failures++;                                                                            \
            printf("FAIL %s:%d: ", __FILE__, __LINE__);                                            \
            printf(__VA_ARGS__);                                                                   \
            printf("\n");                                                                          \
        }                                                                                          \
    } while (0)

#endif
