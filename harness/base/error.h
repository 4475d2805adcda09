/* gibench — error reporting shared by every module.
 *
 * Functions return 0 on success and a negative value on failure, and fill a gib_error with a
 * message a user can act on (it names the file, line or parameter). Nothing but main() exits. */
#ifndef GIB_ERROR_H
#define GIB_ERROR_H

#include <stddef.h>

/* What kind of failure a message describes, set where the failure happens: the runner turns it into
 * a result row's status (harness/app/runner.c) and never reads the status from the text. */
typedef enum gib_error_code {
    GIB_ERR_NONE = 0,
    GIB_ERR_FAILED,        /* any failure without a code of its own */
    GIB_ERR_OUT_OF_MEMORY, /* host or GPU allocation, or a memory plan over the budget */
    GIB_ERR_SHADER,        /* a shader failed to compile or a program to link */
    GIB_ERR_OVERFLOW,      /* a fixed-size buffer or counter would overflow */
    GIB_ERR_NON_FINITE,    /* a computed value is NaN or infinite */
    GIB_ERR_REFERENCE,     /* the reference image could not be rendered or read */
} gib_error_code;

typedef struct gib_error {
    char msg[2048];
    gib_error_code code;
} gib_error;

/* Formats the message into err (if non-NULL), sets its code to GIB_ERR_FAILED and returns -1, so
 * callers can write `return gib_fail(err, "scene '%s': ...", name);`. */
int gib_fail(gib_error *err, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* The same with the failure's code. */
int gib_fail_code(gib_error *err, gib_error_code code, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
/* The result row's status a code stands for (GIB_STATUS_OUT_OF_MEMORY, ...: harness/base/status.h);
 * -1 for GIB_ERR_NONE and GIB_ERR_FAILED, which have none. */
int gib_error_code_status(gib_error_code code);

/* Prefixes an existing message: "context: old message"; the code is kept. Returns -1. */
int gib_error_prefix(gib_error *err, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* Allocation helpers that report failure through err instead of crashing. */
void *gib_calloc(size_t n, size_t size, gib_error *err);
void *gib_realloc_array(void *p, size_t n, size_t size, gib_error *err);
char *gib_strdup(const char *s);

#endif
