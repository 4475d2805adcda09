/* Internal to harness/gl/context*.c: the backends behind gib_gl_init. */
#ifndef GIB_CONTEXT_BACKENDS_H
#define GIB_CONTEXT_BACKENDS_H

typedef void (*gib_proc)(void);
typedef gib_proc (*gib_proc_loader)(const char *name);

int gib_osmesa_create(char *why, int why_len);
gib_proc_loader gib_osmesa_loader(void);
void gib_osmesa_destroy(void);

#endif
