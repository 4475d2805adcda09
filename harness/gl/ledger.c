#include "ledger.h"

#include <glad/gl.h>
#include <stdio.h>
#include <string.h>

#include "context.h"

void gib_ledger_init(gib_ledger *l) { memset(l, 0, sizeof *l); }

unsigned gib_format_bytes(unsigned f)
{
    switch (f) {
    case GL_R8: case GL_R8UI: return 1;
    case GL_RG8: case GL_R16F: case GL_R16: case GL_DEPTH_COMPONENT16: return 2;
    case GL_RGBA8: case GL_SRGB8_ALPHA8: case GL_R32F: case GL_R32UI: case GL_RG16F:
    case GL_DEPTH_COMPONENT24: case GL_DEPTH_COMPONENT32F: case GL_DEPTH24_STENCIL8:
    case GL_RGB10_A2: case GL_R11F_G11F_B10F: return 4;
    case GL_RG32F: case GL_RG32UI: case GL_RGBA16F: case GL_RGBA16: return 8;
    case GL_RGBA32F: case GL_RGBA32UI: return 16;
    default: return 0;
    }
}

int gib_mip_levels(int w, int h, int d)
{
    int m = w > h ? w : h;
    if (d > m)
        m = d;
    int levels = 1;
    while (m > 1) {
        m >>= 1;
        levels++;
    }
    return levels;
}

static int add_entry(gib_ledger *l, const char *label, unsigned name, int is_texture, uint64_t bytes,
                     gib_error *err)
{
    if (l->count >= GIB_LEDGER_MAX)
        return gib_fail_code(err, GIB_ERR_OVERFLOW,
                             "memory ledger full (%d allocations) at '%s'", GIB_LEDGER_MAX, label);
    gib_ledger_entry *e = &l->entries[l->count++];
    snprintf(e->label, sizeof e->label, "%s", label);
    e->name = name;
    e->is_texture = is_texture;
    e->bytes = bytes;
    l->current_bytes += bytes;
    if (l->current_bytes > l->peak_bytes)
        l->peak_bytes = l->current_bytes;
    return 0;
}

/* The budget check, before anything is allocated. */
static int over_budget(const gib_ledger *l, const char *label, uint64_t bytes, gib_error *err)
{
    if (!l->budget_bytes || l->current_bytes + bytes <= l->budget_bytes)
        return 0;
    return gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY,
                         "out of memory: '%s' (%llu bytes) would take the technique to %llu bytes, "
                         "over the budget of %llu bytes", label, (unsigned long long)bytes,
                         (unsigned long long)(l->current_bytes + bytes),
                         (unsigned long long)l->budget_bytes);
}

unsigned gib_gpu_buffer(gib_ledger *l, const char *label, uint64_t bytes, const void *data,
                        unsigned flags, gib_error *err)
{
    if (over_budget(l, label, bytes, err) < 0)
        return 0;
    GLuint b = 0;
    glCreateBuffers(1, &b);
    glNamedBufferStorage(b, (GLsizeiptr)(bytes ? bytes : 4), data, flags);
    if (gib_gl_check(label, err) < 0 || add_entry(l, label, b, 0, bytes, err) < 0) {
        glDeleteBuffers(1, &b);
        gib_error_prefix(err, "allocating buffer '%s' of %llu bytes", label,
                         (unsigned long long)bytes);
        return 0;
    }
    return b;
}

uint64_t gib_texture_bytes(unsigned target, int w, int h, int layers, unsigned fmt, int levels)
{
    if (levels <= 0)
        levels = gib_mip_levels(w, h, target == GL_TEXTURE_3D ? layers : 1);
    uint64_t bytes = 0, bpt = gib_format_bytes(fmt);
    int faces = target == GL_TEXTURE_CUBE_MAP ? 6 : 1;
    for (int i = 0; i < levels; i++) {
        uint64_t lw = (uint64_t)(w >> i ? w >> i : 1), lh = (uint64_t)(h >> i ? h >> i : 1);
        uint64_t ld = target == GL_TEXTURE_3D ? (uint64_t)(layers >> i ? layers >> i : 1)
                      : target == GL_TEXTURE_2D_ARRAY || target == GL_TEXTURE_CUBE_MAP_ARRAY
                          ? (uint64_t)layers : 1;
        bytes += lw * lh * ld * bpt * (uint64_t)faces;
    }
    return bytes;
}

unsigned gib_gpu_texture(gib_ledger *l, const char *label, unsigned target, int w, int h,
                         int layers, unsigned fmt, int levels, gib_error *err)
{
    int depth3d = target == GL_TEXTURE_3D ? layers : 1;
    if (levels <= 0)
        levels = gib_mip_levels(w, h, depth3d);
    if (over_budget(l, label, gib_texture_bytes(target, w, h, layers, fmt, levels), err) < 0)
        return 0;
    GLuint t = 0;
    glCreateTextures(target, 1, &t);
    if (target == GL_TEXTURE_2D || target == GL_TEXTURE_CUBE_MAP)
        glTextureStorage2D(t, levels, fmt, w, h);
    else
        glTextureStorage3D(t, levels, fmt, w, h, layers);
    uint64_t bytes = gib_texture_bytes(target, w, h, layers, fmt, levels);
    if (gib_gl_check(label, err) < 0 || add_entry(l, label, t, 1, bytes, err) < 0) {
        glDeleteTextures(1, &t);
        gib_error_prefix(err, "allocating texture '%s' %dx%dx%d", label, w, h, layers);
        return 0;
    }
    return t;
}

unsigned gib_gpu_renderbuffer(gib_ledger *l, const char *label, unsigned fmt, int w, int h,
                              gib_error *err)
{
    if (over_budget(l, label, (uint64_t)w * h * gib_format_bytes(fmt), err) < 0)
        return 0;
    GLuint r = 0;
    glCreateRenderbuffers(1, &r);
    glNamedRenderbufferStorage(r, fmt, w, h);
    if (gib_gl_check(label, err) < 0 ||
        add_entry(l, label, r, 2, (uint64_t)w * h * gib_format_bytes(fmt), err) < 0) {
        glDeleteRenderbuffers(1, &r);
        return 0;
    }
    return r;
}

static void delete_object(const gib_ledger_entry *e)
{
    GLuint n = e->name;
    if (e->is_texture == 1)
        glDeleteTextures(1, &n);
    else if (e->is_texture == 2)
        glDeleteRenderbuffers(1, &n);
    else
        glDeleteBuffers(1, &n);
}

void gib_gpu_free(gib_ledger *l, unsigned name, int is_texture)
{
    for (int i = 0; i < l->count; i++) {
        gib_ledger_entry *e = &l->entries[i];
        if (e->name == name && e->is_texture == is_texture) {
            delete_object(e);
            l->current_bytes -= e->bytes;
            *e = l->entries[--l->count];
            return;
        }
    }
}

void gib_ledger_release_all(gib_ledger *l)
{
    for (int i = 0; i < l->count; i++)
        delete_object(&l->entries[i]);
    l->count = 0;
    l->current_bytes = 0;
}

/* Length of the key a label is summed under: the whole label, or (by_structure) the part before
 * its first '.'. */
static size_t key_len(const char *label, int by_structure)
{
    const char *dot = by_structure ? strchr(label, '.') : NULL;
    return dot ? (size_t)(dot - label) : strlen(label);
}

static void summary(const gib_ledger_entry *entries, int count, int by_structure, char *out,
                    int out_len)
{
    int used = 0;
    out[0] = 0;
    char seen[GIB_LEDGER_MAX] = {0};
    for (int i = 0; i < count; i++) {
        if (seen[i])
            continue;
        const char *key = entries[i].label;
        size_t n_key = key_len(key, by_structure);
        uint64_t sum = 0;
        for (int j = i; j < count; j++)
            if (key_len(entries[j].label, by_structure) == n_key &&
                !strncmp(entries[j].label, key, n_key)) {
                sum += entries[j].bytes;
                seen[j] = 1;
            }
        int n = snprintf(out + used, out_len - used, "%s%.*s=%llu", used ? ";" : "", (int)n_key,
                         key, (unsigned long long)sum);
        if (n < 0 || n >= out_len - used)
            break;
        used += n;
    }
}

void gib_ledger_summary(const gib_ledger *l, char *out, int out_len)
{
    summary(l->entries, l->count, 0, out, out_len);
}

void gib_ledger_structures(const gib_ledger *l, char *out, int out_len)
{
    summary(l->entries, l->count, 1, out, out_len);
}

void gib_ledger_planned_structures(const gib_ledger *l, char *out, int out_len)
{
    summary(l->planned, l->planned_count, 1, out, out_len);
}

void gib_ledger_plan(gib_ledger *l, const char *label, uint64_t bytes)
{
    for (int i = 0; i < l->planned_count; i++)
        if (!strcmp(l->planned[i].label, label)) {
            l->planned[i].bytes = bytes;
            return;
        }
    if (l->planned_count == GIB_LEDGER_PLAN_MAX) {
        gib_ledger_entry *last = &l->planned[GIB_LEDGER_PLAN_MAX - 1];
        snprintf(last->label, sizeof last->label, "other");
        last->bytes += bytes;
        return;
    }
    gib_ledger_entry *e = &l->planned[l->planned_count++];
    memset(e, 0, sizeof *e);
    snprintf(e->label, sizeof e->label, "%s", label);
    e->bytes = bytes;
}
