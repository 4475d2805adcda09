#include "shader.h"

#include <glad/gl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Appends src to a growing buffer, expanding #include "x" lines recursively. */
static int expand(const char *path, const char *src, char **buf, size_t *len, size_t *cap, int depth,
                  gib_error *err)
{
    if (depth > 8)
        return gib_fail_code(err, GIB_ERR_SHADER, "shader '%s': #include nested too deeply", path);
    const char *p = src;
    while (*p) {
        const char *eol = strchr(p, '\n');
        size_t n = eol ? (size_t)(eol - p + 1) : strlen(p);
        const char *q = p;
        while (q < p + n && (*q == ' ' || *q == '\t'))
            q++;
        if (!strncmp(q, "#include", 8)) {
            const char *a = strchr(q, '"'), *b = a ? strchr(a + 1, '"') : NULL;
            if (!a || !b || b > p + n)
                return gib_fail_code(err, GIB_ERR_SHADER, "shader '%s': malformed #include", path);
            char inc[256];
            snprintf(inc, sizeof inc, "%.*s", (int)(b - a - 1), a + 1);
            const char *isrc = gib_shader_source(inc);
            if (!isrc)
                return gib_fail_code(err, GIB_ERR_SHADER,
                                     "shader '%s': included file '%s' is not embedded", path, inc);
            /* Each file is included once per program: a marker line records it. */
            char marker[300];
            snprintf(marker, sizeof marker, "// included: %s\n", inc);
            if (!strstr(*buf, marker)) {
                if (expand(inc, marker, buf, len, cap, depth + 1, err) < 0 ||
                    expand(inc, isrc, buf, len, cap, depth + 1, err) < 0)
                    return -1;
            }
        } else {
            if (*len + n + 2 > *cap) {
                *cap = (*len + n + 2) * 2;
                char *nb = realloc(*buf, *cap);
                if (!nb)
                    return gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY,
                                         "out of memory expanding shader '%s'", path);
                *buf = nb;
            }
            memcpy(*buf + *len, p, n);
            *len += n;
            (*buf)[*len] = 0;
        }
        p += n;
    }
    if (*len + 2 > *cap) {
        char *nb = realloc(*buf, *len + 2);
        if (!nb)
            return gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY, "out of memory");
        *buf = nb;
        *cap = *len + 2;
    }
    (*buf)[(*len)++] = '\n';
    (*buf)[*len] = 0;
    return 0;
}

static GLenum stage_of(const char *path)
{
    const char *dot = strrchr(path, '.');
    if (!dot)
        return 0;
    if (!strcmp(dot, ".vert")) return GL_VERTEX_SHADER;
    if (!strcmp(dot, ".frag")) return GL_FRAGMENT_SHADER;
    if (!strcmp(dot, ".geom")) return GL_GEOMETRY_SHADER;
    if (!strcmp(dot, ".comp")) return GL_COMPUTE_SHADER;
    return 0;
}

unsigned gib_program(const char *const *files, int count, const char *defines, gib_error *err)
{
    GLuint prog = glCreateProgram();
    GLuint shaders[4] = {0};
    int ok = 1;
    for (int i = 0; i < count && i < 4 && ok; i++) {
        const char *src = gib_shader_source(files[i]);
        GLenum stage = stage_of(files[i]);
        if (!src || !stage) {
            gib_fail_code(err, GIB_ERR_SHADER,
                          "shader '%s' is not embedded in this build (or has an unknown extension)",
                          files[i]);
            ok = 0;
            break;
        }
        size_t cap = strlen(src) + 1024, len = 0;
        char *buf = malloc(cap);
        if (!buf) {
            gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY, "out of memory");
            ok = 0;
            break;
        }
        len = (size_t)snprintf(buf, cap, "#version 450 core\n%s#line 1\n", defines ? defines : "");
        if (expand(files[i], src, &buf, &len, &cap, 0, err) < 0) {
            free(buf);
            ok = 0;
            break;
        }
        /* Fault injection (tests/faults): a shader whose path contains the environment's
         * GIBENCH_INJECT_SHADER_ERROR gets a line the GLSL compiler rejects. */
        const char *inject = getenv("GIBENCH_INJECT_SHADER_ERROR");
        if (inject && *inject && strstr(files[i], inject) && len + 64 < cap)
            len += (size_t)snprintf(buf + len, cap - len, "\nnot glsl: an injected fault;\n");
        shaders[i] = glCreateShader(stage);
        const char *s = buf;
        glShaderSource(shaders[i], 1, &s, NULL);
        glCompileShader(shaders[i]);
        free(buf);
        GLint status = 0;
        glGetShaderiv(shaders[i], GL_COMPILE_STATUS, &status);
        if (!status) {
            char log[1536] = "";
            glGetShaderInfoLog(shaders[i], sizeof log, NULL, log);
            gib_fail_code(err, GIB_ERR_SHADER, "shader '%s' failed to compile: %s", files[i], log);
            ok = 0;
            break;
        }
        glAttachShader(prog, shaders[i]);
    }
    if (ok) {
        glLinkProgram(prog);
        GLint status = 0;
        glGetProgramiv(prog, GL_LINK_STATUS, &status);
        if (!status) {
            char log[1536] = "";
            glGetProgramInfoLog(prog, sizeof log, NULL, log);
            gib_fail_code(err, GIB_ERR_SHADER,
                          "program (%s ...) failed to link: %s", files[0], log);
            ok = 0;
        }
    }
    for (int i = 0; i < 4; i++)
        if (shaders[i])
            glDeleteShader(shaders[i]);
    if (!ok) {
        glDeleteProgram(prog);
        return 0;
    }
    return prog;
}
