/* gibench — error reporting shared by every module.
 *
 * Functions return 0 on success and a negative value on failure, and fill a gib_error with a
 * message a user can act on (it names the file, line or parameter). Nothing but main() exits. */
#ifndef GIB_ERROR_H
#define GIB_ERROR_H

#include <stddef.h>

typedef struct gib_error {
    char msg[2048];
} gib_error;

/* Formats the message into err (if non-NULL) and returns -1, so callers can write
 * `return gib_fail(err, "scene '%s': ...", name);`. */
int gib_fail(gib_error *err, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* Prefixes an existing message: "context: old message". Returns -1. */
int gib_error_prefix(gib_error *err, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* Allocation helpers that report failure through err instead of crashing. */
void *gib_calloc(size_t n, size_t size, gib_error *err);
void *gib_realloc_array(void *p, size_t n, size_t size, gib_error *err);
char *gib_strdup(const char *s);

#endif
