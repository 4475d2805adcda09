/* dl_iterate_phdr (link.h) is a GNU extension. */
#define _GNU_SOURCE
#include "context.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <dlfcn.h>
#include <glad/gl.h>
#include <link.h>
#include <stdio.h>
#include <string.h>

#include "context_backends.h"

static struct {
    EGLDisplay display;
    EGLContext context;
    int osmesa;
} g_gl;

int gib_backend_parse(const char *s)
{
    if (!strcmp(s, "auto"))
        return GIB_BACKEND_AUTO;
    if (!strcmp(s, "egl"))
        return GIB_BACKEND_EGL;
    if (!strcmp(s, "egl-device"))
        return GIB_BACKEND_EGL_DEVICE;
    if (!strcmp(s, "osmesa"))
        return GIB_BACKEND_OSMESA;
    return -1;
}

static const char *egl_error_name(EGLint e)
{
    switch (e) {
    case EGL_SUCCESS: return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
    default: return "EGL error";
    }
}

/* Makes a 4.5 core context on an initialised display, with no config and no surface
 * (EGL_KHR_no_config_context, EGL_KHR_surfaceless_context). 4.6 fails with EGL_BAD_MATCH on Mesa
 * 22, and 4.5 is all gibench needs. */
static int egl_context_on(EGLDisplay dpy, char *why, int why_len)
{
    EGLint major, minor;
    if (!eglInitialize(dpy, &major, &minor)) {
        snprintf(why, why_len, "eglInitialize: %s", egl_error_name(eglGetError()));
        return -1;
    }
    const char *ext = eglQueryString(dpy, EGL_EXTENSIONS);
    if (!ext || !strstr(ext, "EGL_KHR_surfaceless_context")) {
        snprintf(why, why_len, "display lacks EGL_KHR_surfaceless_context");
        eglTerminate(dpy);
        return -1;
    }
    if (!eglBindAPI(EGL_OPENGL_API)) {
        snprintf(why, why_len, "eglBindAPI(OpenGL): %s", egl_error_name(eglGetError()));
        eglTerminate(dpy);
        return -1;
    }
    EGLConfig config = EGL_NO_CONFIG_KHR;
    if (!strstr(ext, "EGL_KHR_no_config_context")) {
        /* Drivers without no-config contexts (some NVIDIA versions) need any GL-capable config. */
        const EGLint cattr[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, EGL_PBUFFER_BIT,
                                EGL_NONE};
        EGLint n = 0;
        if (!eglChooseConfig(dpy, cattr, &config, 1, &n) || n < 1) {
            snprintf(why, why_len, "no EGL config for desktop OpenGL");
            eglTerminate(dpy);
            return -1;
        }
    }
    const EGLint attr[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                           EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                           EGL_NONE};
    EGLContext ctx = eglCreateContext(dpy, config, EGL_NO_CONTEXT, attr);
    if (ctx == EGL_NO_CONTEXT) {
        snprintf(why, why_len, "eglCreateContext(4.5 core): %s", egl_error_name(eglGetError()));
        eglTerminate(dpy);
        return -1;
    }
    if (!eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx)) {
        snprintf(why, why_len, "eglMakeCurrent(surfaceless): %s", egl_error_name(eglGetError()));
        eglDestroyContext(dpy, ctx);
        eglTerminate(dpy);
        return -1;
    }
    g_gl.display = dpy;
    g_gl.context = ctx;
    return 0;
}

static int try_egl_surfaceless(char *why, int why_len)
{
    PFNEGLGETPLATFORMDISPLAYEXTPROC get_display =
        (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
    if (!get_display) {
        snprintf(why, why_len, "eglGetPlatformDisplayEXT not available");
        return -1;
    }
    EGLDisplay dpy = get_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL);
    if (dpy == EGL_NO_DISPLAY) {
        snprintf(why, why_len, "no surfaceless display: %s", egl_error_name(eglGetError()));
        return -1;
    }
    return egl_context_on(dpy, why, why_len);
}

/* The device's extension string, or "" (EGL_EXT_device_query). */
static const char *device_extensions(EGLDeviceEXT dev)
{
    PFNEGLQUERYDEVICESTRINGEXTPROC query_string =
        (PFNEGLQUERYDEVICESTRINGEXTPROC)eglGetProcAddress("eglQueryDeviceStringEXT");
    const char *ext = query_string ? query_string(dev, EGL_EXTENSIONS) : NULL;
    return ext ? ext : "";
}

/* Mesa's software device (llvmpipe) says so in its extensions; an NVIDIA or Mesa GPU device does
 * not. */
static int device_is_software(EGLDeviceEXT dev)
{
    return strstr(device_extensions(dev), "EGL_MESA_device_software") != NULL;
}

/* Tries every device the driver lists, hardware devices first (Mesa lists its software device
 * beside a GPU's, and the first to give a context wins). On success info->device names the device
 * and its extensions. */
static int try_egl_device(gib_gl_info *info, char *why, int why_len)
{
    PFNEGLQUERYDEVICESEXTPROC query_devices =
        (PFNEGLQUERYDEVICESEXTPROC)eglGetProcAddress("eglQueryDevicesEXT");
    PFNEGLGETPLATFORMDISPLAYEXTPROC get_display =
        (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
    PFNEGLQUERYDEVICESTRINGEXTPROC query_string =
        (PFNEGLQUERYDEVICESTRINGEXTPROC)eglGetProcAddress("eglQueryDeviceStringEXT");
    if (!query_devices || !get_display) {
        snprintf(why, why_len, "EGL_EXT_device_enumeration not available");
        return -1;
    }
    EGLDeviceEXT devices[16];
    EGLint n = 0;
    if (!query_devices(16, devices, &n) || n == 0) {
        snprintf(why, why_len, "eglQueryDevicesEXT found no device");
        return -1;
    }
    int order[16], k = 0;
    for (int pass = 0; pass < 2; pass++)
        for (EGLint i = 0; i < n; i++)
            if (device_is_software(devices[i]) == pass)
                order[k++] = (int)i;
    int used = 0;
    for (int j = 0; j < k; j++) {
        const int i = order[j];
        EGLDisplay dpy = get_display(EGL_PLATFORM_DEVICE_EXT, devices[i], NULL);
        if (dpy == EGL_NO_DISPLAY)
            continue;
        used += snprintf(why + used, why_len > used ? why_len - used : 0, "device %d%s: ", i,
                         device_is_software(devices[i]) ? " (software)" : "");
        if (used >= why_len)
            used = why_len - 1;
        if (egl_context_on(dpy, why + used, why_len - used) == 0) {
            const char *node = NULL;
            if (query_string && strstr(device_extensions(devices[i]), "EGL_EXT_device_drm"))
                node = query_string(devices[i], EGL_DRM_DEVICE_FILE_EXT);
            snprintf(info->device, sizeof info->device, "device %d of %d, %s: %s", i, (int)n,
                     node ? node : "no DRM node", device_extensions(devices[i]));
            return 0;
        }
        used += (int)strlen(why + used);
        used += snprintf(why + used, why_len > used ? why_len - used : 0, "; ");
        if (used >= why_len)
            used = why_len - 1;
    }
    return -1;
}

static gib_proc egl_loader(const char *name) { return (gib_proc)eglGetProcAddress(name); }

int gib_gl_init(int backend, gib_gl_info *info, gib_error *err)
{
    char tried[1536] = "";
    char why[512];
    memset(info, 0, sizeof *info);
    gib_proc_loader loader = NULL;
    if (backend == GIB_BACKEND_AUTO || backend == GIB_BACKEND_EGL ||
        backend == GIB_BACKEND_EGL_DEVICE) {
        why[0] = 0;
        if (backend != GIB_BACKEND_EGL_DEVICE && try_egl_surfaceless(why, sizeof why) == 0) {
            loader = egl_loader;
            snprintf(info->backend, sizeof info->backend, "egl-surfaceless");
        } else {
            size_t u = strlen(tried);
            if (backend != GIB_BACKEND_EGL_DEVICE)
                snprintf(tried + u, sizeof tried - u, "EGL surfaceless platform: %s; ", why);
            why[0] = 0;
            if (try_egl_device(info, why, sizeof why) == 0) {
                loader = egl_loader;
                snprintf(info->backend, sizeof info->backend, "egl-device");
            } else {
                u = strlen(tried);
                snprintf(tried + u, sizeof tried - u, "EGL device platform: %s; ", why);
            }
        }
    }
    if (!loader && (backend == GIB_BACKEND_AUTO || backend == GIB_BACKEND_OSMESA)) {
        why[0] = 0;
        if (gib_osmesa_create(why, sizeof why) == 0) {
            loader = gib_osmesa_loader();
            g_gl.osmesa = 1;
            snprintf(info->backend, sizeof info->backend, "osmesa");
        } else {
            size_t u = strlen(tried);
            snprintf(tried + u, sizeof tried - u, "OSMesa: %s; ", why);
        }
    }
    if (!loader)
        return gib_fail(err, "no OpenGL 4.5 core context could be created (tried %s). Install Mesa "
                        "(libegl-mesa0, libosmesa6, libgl1-mesa-dri: `make deps`) or a GPU driver",
                        tried);
    if (!gladLoadGL((GLADloadfunc)loader)) {
        gib_gl_shutdown();
        return gib_fail(err, "%s: loading the GL 4.5 entry points failed", info->backend);
    }
    snprintf(info->renderer, sizeof info->renderer, "%s", (const char *)glGetString(GL_RENDERER));
    snprintf(info->version, sizeof info->version, "%s", (const char *)glGetString(GL_VERSION));
    snprintf(info->vendor, sizeof info->vendor, "%s", (const char *)glGetString(GL_VENDOR));
    GLint major = 0, minor = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    if (major * 10 + minor < 45) {
        gib_gl_shutdown();
        return gib_fail(err, "%s gave OpenGL %d.%d (%s); gibench needs 4.5 core", info->backend,
                        major, minor, info->renderer);
    }
    return 0;
}

/* Marks every loaded DRI driver (and Mesa's gallium library) RTLD_NODELETE, so that
 * eglTerminate cannot unload it. Only for the sanitizer build's sake: LeakSanitizer reports at
 * exit, and a leak inside a library unloaded by then has no module name to suppress it by
 * (tests/lsan_mesa.supp names Mesa's libraries, never ours). */
static int pin_one(struct dl_phdr_info *info, size_t size, void *data)
{
    (void)size;
    (void)data;
    const char *n = info->dlpi_name;
    if (n && (strstr(n, "/dri/") || strstr(n, "libgallium") || strstr(n, "libLLVM")))
        dlopen(n, RTLD_NOW | RTLD_NOLOAD | RTLD_NODELETE);
    return 0;
}

static void pin_drivers(void)
{
    dl_iterate_phdr(pin_one, NULL);
}

void gib_gl_shutdown(void)
{
    pin_drivers();
    if (g_gl.osmesa) {
        gib_osmesa_destroy();
        g_gl.osmesa = 0;
    }
    if (g_gl.display) {
        eglMakeCurrent(g_gl.display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        if (g_gl.context)
            eglDestroyContext(g_gl.display, g_gl.context);
        eglTerminate(g_gl.display);
        g_gl.display = NULL;
        g_gl.context = NULL;
    }
}

int gib_gl_check(const char *where, gib_error *err)
{
    GLenum e, first = GL_NO_ERROR;
    while ((e = glGetError()) != GL_NO_ERROR)
        if (first == GL_NO_ERROR)
            first = e;
    if (first == GL_NO_ERROR)
        return 0;
    const char *name = first == GL_INVALID_ENUM        ? "GL_INVALID_ENUM"
                       : first == GL_INVALID_VALUE     ? "GL_INVALID_VALUE"
                       : first == GL_INVALID_OPERATION ? "GL_INVALID_OPERATION"
                       : first == GL_OUT_OF_MEMORY     ? "GL_OUT_OF_MEMORY"
                       : first == GL_INVALID_FRAMEBUFFER_OPERATION ? "GL_INVALID_FRAMEBUFFER_OPERATION"
                                                                    : "GL error";
    return gib_fail_code(err, first == GL_OUT_OF_MEMORY ? GIB_ERR_OUT_OF_MEMORY : GIB_ERR_FAILED,
                         "%s: %s (0x%04x)", where, name, (unsigned)first);
}
