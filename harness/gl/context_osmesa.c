/* OSMesa backend, kept in its own file: GL/osmesa.h pulls in GL/gl.h, which must not meet glad's
 * header. libOSMesa does not export the DSA entry points, so every GL function is loaded through
 * OSMesaGetProcAddress (ARCHITECTURE.md, "Toolchain facts").
 *
 * libOSMesa is opened at run time, not linked: it pulls in libLLVM and more (hundreds of MB), and a
 * machine with a GPU driver needs none of it. GL/osmesa.h gives the types and constants only. */
#include <GL/osmesa.h>
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>

#include "context_backends.h"

#define GIB_OSMESA_SONAME "libOSMesa.so.8"

static struct {
    OSMesaContext (*create)(const int *attribs, OSMesaContext share);
    GLboolean (*make_current)(OSMesaContext, void *, GLenum, GLsizei, GLsizei);
    void (*destroy)(OSMesaContext);
    OSMESAproc (*get_proc)(const char *);
} g_osm;
static OSMesaContext g_ctx;
static unsigned char *g_buffer;

/* Opens libOSMesa once and resolves the four entry points gibench calls. The library stays loaded
 * for the life of the process (its GL functions are used until exit; Mesa does not unload
 * cleanly). */
static int osmesa_open(char *why, int why_len)
{
    if (g_osm.get_proc)
        return 0;
    void *lib = dlopen(GIB_OSMESA_SONAME, RTLD_NOW | RTLD_LOCAL);
    if (!lib) {
        const char *e = dlerror();
        snprintf(why, why_len, "dlopen(%s) failed: %s", GIB_OSMESA_SONAME, e ? e : "not found");
        return -1;
    }
    /* dlsym returns void *; POSIX guarantees it converts to a function pointer. */
    *(void **)&g_osm.create = dlsym(lib, "OSMesaCreateContextAttribs");
    *(void **)&g_osm.make_current = dlsym(lib, "OSMesaMakeCurrent");
    *(void **)&g_osm.destroy = dlsym(lib, "OSMesaDestroyContext");
    *(void **)&g_osm.get_proc = dlsym(lib, "OSMesaGetProcAddress");
    if (!g_osm.create || !g_osm.make_current || !g_osm.destroy || !g_osm.get_proc) {
        snprintf(why, why_len, "%s lacks OSMesaCreateContextAttribs or another entry point",
                 GIB_OSMESA_SONAME);
        g_osm.get_proc = NULL;
        return -1;
    }
    return 0;
}

int gib_osmesa_create(char *why, int why_len)
{
    if (osmesa_open(why, why_len) < 0)
        return -1;
    const int attribs[] = {OSMESA_FORMAT,   OSMESA_RGBA, OSMESA_DEPTH_BITS, 24,
                           OSMESA_PROFILE,  OSMESA_CORE_PROFILE,
                           OSMESA_CONTEXT_MAJOR_VERSION, 4,
                           OSMESA_CONTEXT_MINOR_VERSION, 5, 0};
    g_ctx = g_osm.create(attribs, NULL);
    if (!g_ctx) {
        snprintf(why, why_len, "OSMesaCreateContextAttribs(core 4.5) returned NULL");
        return -1;
    }
    /* OSMesa needs a colour buffer to make a context current even though we render into FBOs. */
    g_buffer = calloc(16 * 16, 4);
    if (!g_buffer || !g_osm.make_current(g_ctx, g_buffer, GL_UNSIGNED_BYTE, 16, 16)) {
        snprintf(why, why_len, "OSMesaMakeCurrent failed");
        g_osm.destroy(g_ctx);
        g_ctx = NULL;
        free(g_buffer);
        g_buffer = NULL;
        return -1;
    }
    return 0;
}

static gib_proc osmesa_proc(const char *name) { return (gib_proc)g_osm.get_proc(name); }

gib_proc_loader gib_osmesa_loader(void) { return osmesa_proc; }

void gib_osmesa_destroy(void)
{
    if (g_ctx)
        g_osm.destroy(g_ctx);
    g_ctx = NULL;
    free(g_buffer);
    g_buffer = NULL;
}
