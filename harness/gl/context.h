/* gibench — headless OpenGL 4.5 core contexts.
 *
 * Order tried by GIB_BACKEND_AUTO: EGL on the surfaceless platform (Mesa: llvmpipe or a GPU), then
 * EGL on the device platform (EGL_EXT_platform_device: how an NVIDIA GPU is reached without a
 * display; hardware devices before Mesa's software one), then OSMesa (libOSMesa.so.8, opened at
 * run time). GIB_BACKEND_EGL tries both EGL platforms; GIB_BACKEND_EGL_DEVICE the device platform
 * alone. There is no default framebuffer: everything renders into FBOs. Every GL
 * entry point is loaded through the backend's own GetProcAddress (glad2), never by linking libGL. */
#ifndef GIB_CONTEXT_H
#define GIB_CONTEXT_H

#include "harness/base/error.h"

enum gib_backend {
    GIB_BACKEND_AUTO = 0,
    GIB_BACKEND_EGL = 1,
    GIB_BACKEND_OSMESA = 2,
    GIB_BACKEND_EGL_DEVICE = 3
};

typedef struct gib_gl_info {
    char backend[32];   /* "egl-surfaceless", "egl-device", "osmesa" */
    char renderer[256]; /* GL_RENDERER */
    char version[256];  /* GL_VERSION */
    char vendor[256];
    /* On the device platform: which device of how many, its DRM node and its device extensions
     * ("device 0 of 2, /dev/dri/renderD128: EGL_NV_device_cuda ..."); empty otherwise. */
    char device[512];
} gib_gl_info;

/* Parses "egl", "egl-device", "osmesa" or "auto"; -1 for anything else. */
int gib_backend_parse(const char *s);

/* Creates a context and makes it current; on failure the message lists every attempt and why it
 * failed. Only one context per process. */
int gib_gl_init(int backend, gib_gl_info *info, gib_error *err);
void gib_gl_shutdown(void);

/* Drains glGetError; returns -1 and names `where` and the error if there was one. */
int gib_gl_check(const char *where, gib_error *err);

#endif
