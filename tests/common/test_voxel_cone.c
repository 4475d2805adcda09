/* techniques/common/voxel_cone.glsl, compiled with a probe compute shader and run on the occlusion
 * voxels of a small procedural scene (check_cones says what is checked and the tolerances). */
#include <glad/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "harness/base/cone_set.h"
#include "harness/gl/bindings.h"
#include "techniques/common/shader.h"
#include "techniques/common/voxels.h"
#include "tests/common/gl_fixture.h"
#include "tests/common/check.h"

static int failures;

/* ---- voxel_cone.glsl, compiled into a probe compute shader ---- */

/* Each query is 3 vec4: (p, mode), (n, dist or diameter or cone index), (dir, aperture); the
 * result replaces the first vec4. Modes: 0 voxel_occlusion(p, diameter), 1 shadow_cone,
 * 2 diffuse cone i: (dir, weight). */
static const char *probe_main =
    "layout(local_size_x = 1) in;\n"
    "layout(std430, binding = GIB_SSBO_OWN_FIRST) buffer Q { vec4 q[]; };\n"
    "void main() {\n"
    "  uint i = 3u * gl_WorkGroupID.x;\n"
    "  vec4 a = q[i], b = q[i + 1u], c = q[i + 2u];\n"
    "  if (a.w == 0.0) q[i] = vec4(voxel_occlusion(a.xyz, b.w));\n"
    "  else if (a.w == 1.0) q[i] = vec4(shadow_cone(a.xyz, b.xyz, c.xyz, b.w, c.w));\n"
    "  else { int k = int(b.w); q[i] = vec4(diffuse_cone_dir(k, b.xyz), diffuse_cone_weight(k));\n"
    "         if (k == 0) q[i + 1u].w = float(diffuse_cone_count()); }\n"
    "}\n";

/* The embedded files in order, their #include lines commented out (each is included once). */
static unsigned probe_program(void)
{
    const char *files[3] = {"gl/bindings.h", "common/basis.glsl", "common/voxel_cone.glsl"};
    size_t cap = 1 << 16, len = 0;
    char *src = calloc(cap, 1);
    len += (size_t)snprintf(src, cap, "#version 450 core\n");
    for (int f = 0; f < 3; f++) {
        const char *t = gib_shader_source(files[f]);
        if (!t) {
            CHECK(0, "%s is not embedded", files[f]);
            free(src);
            return 0;
        }
        for (const char *l = t; *l;) {
            const char *e = strchr(l, '\n');
            size_t n = e ? (size_t)(e - l + 1) : strlen(l);
            if (!strncmp(l, "#include", 8))
                len += (size_t)snprintf(src + len, cap - len, "//");
            len += (size_t)snprintf(src + len, cap - len, "%.*s", (int)n, l);
            l += n;
        }
        len += (size_t)snprintf(src + len, cap - len, "\n");
    }
    snprintf(src + len, cap - len, "%s", probe_main);
    GLuint sh = glCreateShader(GL_COMPUTE_SHADER), prog = glCreateProgram();
    const char *cs = src;
    glShaderSource(sh, 1, &cs, NULL);
    glCompileShader(sh);
    free(src);
    GLint ok = 0;
    glGetShaderiv(sh, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[2048];
        glGetShaderInfoLog(sh, sizeof log, NULL, log);
        CHECK(0, "voxel_cone.glsl does not compile: %s", log);
        glDeleteShader(sh);
        glDeleteProgram(prog);
        return 0;
    }
    glAttachShader(prog, sh);
    glLinkProgram(prog);
    glDeleteShader(sh);
    glGetProgramiv(prog, GL_LINK_STATUS, &ok);
    if (!ok) {
        CHECK(0, "the voxel_cone.glsl probe does not link");
        glDeleteProgram(prog);
        return 0;
    }
    return prog;
}

static void run_probe(unsigned prog, const gib_voxels *v, float (*q)[4], int count)
{
    GLuint buf = 0;
    glCreateBuffers(1, &buf);
    glNamedBufferStorage(buf, (GLsizeiptr)count * 48, q, GL_DYNAMIC_STORAGE_BIT);
    glUseProgram(prog);
    gib_voxels_bind(v);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GIB_SSBO_OWN_FIRST, buf);
    glDispatchCompute((GLuint)count, 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetNamedBufferSubData(buf, 0, (GLsizeiptr)count * 48, q);
    glUseProgram(0);
    glDeleteBuffers(1, &buf);
}

/* A 2 m floor (y = 0) under a 0.6 x 0.2 x 0.6 m box at y = 0.4..0.6 (the roof):
 *  - voxel_occlusion at the centre of a set roof voxel is 1 (level 0, any diameter up to a voxel),
 *    0 in empty space and outside the grid (the border); tolerance 1/255 (R8);
 *  - a shadow cone straight up from under the roof is blocked (visibility < 0.5: a box's shell is
 *    two layers one voxel thin, and a layer one voxel thin read at mip level m lets 1 - 2^-m
 *    through, the leak of voxel cone tracing), from the floor beside it open (> 0.95), and from
 *    the roof's top face up open (> 0.95) wherever the face lies in its voxel: the start offset
 *    keeps a surface's own voxel out;
 *  - the 6 diffuse cones: one along n, five at 60 degrees from n, 72 degrees apart in azimuth,
 *    weights summing to 1 and proportional to cos(tilt) (the cosine-weighted share of equal caps),
 *    for several normals, and the same as the reference's copy (harness/base/cone_set.h, what
 *    `gibench reference --cone` renders) to 1e-5. */
static void check_cones(const char *dir)
{
    const char *text = "[scene]\ndescription = voxels: roof over a floor\n"
                       "[mesh.floor]\nprocedural = quad\nsize = 2 2\n"
                       "[mesh.roof]\nprocedural = box\nsize = 0.6 0.2 0.6\ntranslate = 0 0.4 0\n"
                       "[camera.c]\neye = 0 1 3\ntarget = 0 0 0\nup = 0 1 0\nfov = 60\n"
                       "[light.l]\ntype = point\nposition = 0 2 2\nintensity = 1 1 1\n";
    gib_gl_fixture fx;
    if (gib_fixture_open_text(&fx, dir, "roof", text) < 0) {
        failures++;
        return;
    }
    gib_ledger ledger;
    gib_ledger_init(&ledger);
    gib_voxels v;
    gib_error err;
    unsigned prog = probe_program();
    if (!prog || gib_voxels_create(&v, &fx.gpu, 64, "voxels", &ledger, &err) < 0) {
        if (prog)
            CHECK(0, "cones: %s", err.msg);
        gib_fixture_close(&fx);
        return;
    }
    gib_voxels_build(&v, &fx.gpu, NULL, "voxelization");
    const float vs = v.size / (float)v.res;
    /* The roof voxel under (0, 0.5, 0): its centre. */
    float c[3];
    for (int k = 0; k < 3; k++) {
        float x = k == 1 ? 0.6f : 0.0f;
        c[k] = v.origin[k] + (floorf((x - v.origin[k]) / vs) + 0.5f) * vs;
    }
    const float deg = (float)M_PI / 180;
    float q[][3][4] = {
        {{c[0], c[1], c[2], 0}, {0, 0, 0, vs}, {0}},             /* set voxel, 1 voxel */
        {{c[0], c[1], c[2], 0}, {0, 0, 0, 0.3f * vs}, {0}},      /* set voxel, below 1 voxel */
        {{0.0f, 0.25f, 0.0f, 0}, {0, 0, 0, vs}, {0}},            /* empty */
        {{0.0f, 5.0f, 0.0f, 0}, {0, 0, 0, vs}, {0}},             /* outside the grid */
        {{0, 0, 0, 1}, {0, 1, 0, 1.0f}, {0, 1, 0, 10 * deg}},    /* under the roof, up */
        {{0.8f, 0, 0.8f, 1}, {0, 1, 0, 1.0f}, {0, 1, 0, 10 * deg}}, /* beside it, up */
    };
    const int nfix = (int)(sizeof q / sizeof q[0]), ntop = 8;
    const float normals[4][3] = {{0, 1, 0}, {0, -1, 0}, {1, 0, 0}, {0.48f, 0.6f, 0.64f}};
    float (*all)[4] = calloc((size_t)(nfix + 24 + ntop) * 3, sizeof *all);
    memcpy(all, q, sizeof q);
    /* Shadow cones up from the roof's top face, the face placed anywhere in its voxel: points
     * across the voxel the face (y = 0.6) lies in. */
    const float top = floorf((0.6f - v.origin[1]) / vs);
    for (int k = 0; k < ntop; k++) {
        float (*e)[4] = all + 3 * (nfix + 24 + k);
        const float p[4] = {0, v.origin[1] + (top + (k + 0.5f) / ntop) * vs, 0, 1};
        const float n[4] = {0, 1, 0, 1.0f}, d[4] = {0, 1, 0, 10 * deg};
        memcpy(e[0], p, 16);
        memcpy(e[1], n, 16);
        memcpy(e[2], d, 16);
    }
    for (int m = 0; m < 4; m++)
        for (int i = 0; i < 6; i++) {
            float (*e)[4] = all + 3 * (nfix + 6 * m + i);
            e[0][3] = 2;
            memcpy(e[1], normals[m], 12);
            e[1][3] = (float)i;
        }
    run_probe(prog, &v, all, nfix + 24 + ntop);
    CHECK(!(gib_gl_check("running the voxel_cone.glsl probe", &err) < 0), "cones: %s", err.msg);
    const float want[4] = {1, 1, 0, 0};
    for (int i = 0; i < 4; i++) {
        char what[96];
        snprintf(what, sizeof what, "cones: voxel_occlusion query %d = %.4f, |error| from %.0f", i,
                 all[3 * i][0], want[i]);
        CHECK_AT_MOST(what, fabsf(all[3 * i][0] - want[i]), 1.0f / 255, "R8 voxels: 1/255");
    }
    float blocked = all[3 * 4][0], open = all[3 * 5][0];
    printf("  cones: occlusion %.3f %.3f %.3f %.3f; shadow cone under the roof %.3f, beside %.3f\n",
           all[0][0], all[3][0], all[6][0], all[9][0], blocked, open);
    CHECK(!(!(blocked < 0.5f) || !(open > 0.95f)),
          "cones: shadow cone visibility %.3f under the roof (< 0.5), %.3f beside "
          "(> 0.95)", blocked, open);
    float worst_top = 1;
    for (int k = 0; k < ntop; k++)
        worst_top = fminf(worst_top, all[3 * (nfix + 24 + k)][0]);
    printf("  cones: from the roof's top face, up: visibility >= %.3f\n", worst_top);
    CHECK(worst_top > 0.95f, "cones: a shadow cone up from the roof's top face sees its own voxel "
          "(visibility %.3f, expected > 0.95)", worst_top);
    for (int m = 0; m < 4; m++) {
        const float *n = normals[m];
        double wsum = 0, tsum[3] = {0, 0, 0};
        int bad = (int)all[3 * (nfix + 6 * m) + 1][3] != 6;
        for (int i = 0; i < 6; i++) {
            const float *r = all[3 * (nfix + 6 * m + i)];
            double cosn = r[0] * n[0] + r[1] * n[1] + r[2] * n[2];
            double len = sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
            double want_cos = i == 0 ? 1.0 : 0.5, want_w = want_cos / 3.5; /* cos / sum of cos */
            bad += fabs(len - 1) > 1e-5 || fabs(cosn - want_cos) > 1e-5 ||
                   fabs(r[3] - want_w) > 1e-6;
            /* The reference's copy of the set (harness/base/cone_set.h) is the same cone. */
            float c_dir[3];
            gib_diffuse_cone_dir(i, n, c_dir);
            for (int k = 0; k < 3; k++)
                bad += fabsf(c_dir[k] - r[k]) > 1e-5f;
            bad += fabsf(gib_diffuse_cone_weight(i) - r[3]) > 1e-6f;
            wsum += r[3];
            for (int k = 0; k < 3 && i; k++)
                tsum[k] += r[k] - cosn * n[k];
            /* Neighbours in azimuth 72 degrees apart: tangent parts at cos 72 x sin^2 60. */
            if (i) {
                const float *s = all[3 * (nfix + 6 * m + (i % 5) + 1)];
                double d = 0;
                for (int k = 0; k < 3; k++)
                    d += (r[k] - 0.5 * n[k]) * (s[k] - 0.5 * n[k]);
                bad += fabs(d - cos(72 * M_PI / 180) * 0.75) > 1e-5;
            }
        }
        bad += fabs(wsum - 1) > 1e-6 ||
               sqrt(tsum[0] * tsum[0] + tsum[1] * tsum[1] + tsum[2] * tsum[2]) > 1e-5;
        CHECK(!bad, "cones: the diffuse cone set for normal (%g %g %g) (%d errors)", n[0],
              n[1], n[2], bad);
    }
    free(all);
    glDeleteProgram(prog);
    gib_voxels_destroy(&v, &ledger);
    gib_fixture_close(&fx);
}

int main(void)
{
    char dir[] = "/tmp/gib_voxel_cone_XXXXXX";
    if (!mkdtemp(dir)) {
        CHECK(0, "cannot make a temporary folder");
        return 1;
    }
    check_cones(dir);
    char path[600];
    snprintf(path, sizeof path, "%s/roof.scene", dir);
    remove(path);
    rmdir(dir);
    if (failures)
        printf("%d failure(s)\n", failures);
    else
        printf("PASS\n");
    return failures ? 1 : 0;
}
