/* OSMesa backend, kept in its own file: GL/osmesa.h pulls in GL/gl.h, which must not meet glad's
 * header. libOSMesa does not export the DSA entry points, so every GL function is loaded through
 * OSMesaGetProcAddress (ARCHITECTURE.md, "Toolchain facts"). */
#include <GL/osmesa.h>
#include <stdio.h>
#include <stdlib.h>

#include "context_backends.h"

static OSMesaContext g_ctx;
static unsigned char *g_buffer;

int gib_osmesa_create(char *why, int why_len)
{
    const int attribs[] = {OSMESA_FORMAT,   OSMESA_RGBA, OSMESA_DEPTH_BITS, 24,
                           OSMESA_PROFILE,  OSMESA_CORE_PROFILE,
                           OSMESA_CONTEXT_MAJOR_VERSION, 4,
                           OSMESA_CONTEXT_MINOR_VERSION, 5, 0};
    g_ctx = OSMesaCreateContextAttribs(attribs, NULL);
    if (!g_ctx) {
        snprintf(why, why_len, "OSMesaCreateContextAttribs(core 4.5) returned NULL");
        return -1;
    }
    /* OSMesa needs a colour buffer to make a context current even though we render into FBOs. */
    g_buffer = calloc(16 * 16, 4);
    if (!g_buffer || !OSMesaMakeCurrent(g_ctx, g_buffer, GL_UNSIGNED_BYTE, 16, 16)) {
        snprintf(why, why_len, "OSMesaMakeCurrent failed");
        OSMesaDestroyContext(g_ctx);
        g_ctx = NULL;
        return -1;
    }
    return 0;
}

gib_proc_loader gib_osmesa_loader(void) { return (gib_proc_loader)OSMesaGetProcAddress; }

void gib_osmesa_destroy(void)
{
    if (g_ctx)
        OSMesaDestroyContext(g_ctx);
    g_ctx = NULL;
    free(g_buffer);
    g_buffer = NULL;
}
