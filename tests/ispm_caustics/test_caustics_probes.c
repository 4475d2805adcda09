/* ispm_caustics' shaders on synthetic input (thesis 004, Sec. 3.3), run on the GPU as the
 * technique runs them:
 *  1. Phong lobe sampling (caustics.glsl, Sec. 3.3.1.2 with its pdf corrected, caustics.glsl says how): over 2^16
 *     samples per lobe the mean cosine to the lobe axis equals (n+1)/(n+2), the mean of the pdf
 *     (n+1)/(2 pi) cos^n, within 4 standard errors (the samples' own); exactly the directions
 *     under the surface are rejected, so none accepted lies below it.
 *  2. The specular mask's mips (mask_mip.comp, Fig. 3.5): on a synthetic 64^2 mask the texels of
 *     level l that are exactly 1 (the photons of Sec. 3.3.1.1) are the blocks of 4^l texels all
 *     specular, counted on the CPU: equal, for l = 0..3. Texels whose material is specular but
 *     rho_s = 0, or where the light sees nothing, are not specular.
 *  3. One photon's splat (splat.*, Sec. 3.3.2.3) on a plane seen orthographically at 512^2: the
 *     irradiance summed over the pixels times their area is the photon's flux within 0.5% (the
 *     midpoint rule on a Gaussian cut at r = h, h = 48 pixels: its error is ~1e-4; the 0.5% leaves
 *     room for float sums). */
#include <glad/gl.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness/gl/bindings.h"
#include "harness/gl/context.h"
#include "techniques/common/shader.h"
#include "tests/common/check.h"

static int failures;
static char check_msg[512]; /* what a CHECK_TRUE line says */

static uint64_t rs = 0x9e3779b97f4a7c15ull;
static float rnd(void)
{
    rs = rs * 6364136223846793005ull + 1442695040888963407ull;
    return (float)(rs >> 40) * (1.0f / 16777216.0f);
}

static int phong(void)
{
    gib_error err;
    const char *files[] = {"ispm_caustics/phong_probe.comp"};
    unsigned prog = gib_program(files, 1, NULL, &err);
    if (!prog) {
        CHECK(0, "phong probe: %s", err.msg);
        return 0;
    }
    const int N = 1 << 16;
    float *xi = malloc(16 * N), *out = malloc(16 * N);
    unsigned b[2];
    glCreateBuffers(2, b);
    int ok = 1;
    const float ns[3] = {1, 10, 100}, tilt[2] = {30, 80};
    for (int a = 0; a < 3; a++)
        for (int k = 0; k < 2; k++) {
            for (int i = 0; i < 4 * N; i++)
                xi[i] = rnd();
            glNamedBufferData(b[0], 16 * N, xi, GL_STATIC_DRAW);
            glNamedBufferData(b[1], 16 * N, NULL, GL_STATIC_READ);
            float th = tilt[k] * (float)M_PI / 180;
            float r[3] = {sinf(th), 0, cosf(th)}, nrm[3] = {0, 0, 1};
            glUseProgram(prog);
            glUniform3fv(2, 1, r);
            glUniform3fv(3, 1, nrm);
            glUniform1f(4, ns[a]);
            glUniform1i(5, N);
            glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 8, b[0]);
            glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 9, b[1]);
            glDispatchCompute(N / 64, 1, 1);
            glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
            glGetNamedBufferSubData(b[1], 0, 16 * N, out);
            double s = 0, s2 = 0;
            int below = 0, wrong = 0, rejected = 0;
            for (int i = 0; i < N; i++) {
                const float *d = out + 4 * i;
                double c = d[0] * r[0] + d[1] * r[1] + d[2] * r[2];
                s += c;
                s2 += c * c;
                int acc = d[3] > 0.5f;
                rejected += !acc;
                below += acc && d[2] <= 0;
                wrong += !acc && d[2] > 0;
            }
            double mean = s / N, se = sqrt((s2 / N - mean * mean) / N);
            double want = (ns[a] + 1) / (ns[a] + 2);
            snprintf(check_msg, sizeof check_msg,
                     "Phong n = %g, axis %g deg from the normal: mean cos (%.2f standard errors)",
                     ns[a], tilt[k], (mean - want) / se);
            CHECK_NEAR(check_msg, want, mean, 4 * se,
                       "4 standard errors of the 2^16 samples' own mean");
            snprintf(check_msg, sizeof check_msg,
                     "Phong n = %g, axis %g deg: %d rejected, %d accepted below, %d rejected above",
                     ns[a], tilt[k], rejected, below, wrong);
            CHECK_TRUE(check_msg, below == 0 && wrong == 0,
                       "exactly the directions under the surface are rejected");
        }
    glDeleteBuffers(2, b);
    glDeleteProgram(prog);
    free(xi);
    free(out);
    return ok;
}

static unsigned array_tex(int res, const float *data)
{
    unsigned t;
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &t);
    glTextureStorage3D(t, 1, GL_RGBA32F, res, res, 1);
    glTextureSubImage3D(t, 0, 0, 0, 0, res, res, 1, GL_RGBA, GL_FLOAT, data);
    return t;
}

static int mask(void)
{
    gib_error err;
    const char *files[] = {"ispm_caustics/mask_mip.comp"};
    unsigned prog = gib_program(files, 1, NULL, &err);
    if (!prog) {
        CHECK(0, "mask probe: %s", err.msg);
        return 0;
    }
    enum { R = 64, L = 3 };
    static float pos[R * R * 4], nrm[R * R * 4], spc[R * R * 4];
    static int spec[R * R];
    for (int y = 0; y < R; y++)
        for (int x = 0; x < R; x++) {
            int i = y * R + x;
            /* a disc, a ring of partial blocks, holes and non-specular look-alikes */
            float dx = x - 30.5f, dy = y - 33.5f;
            int in = dx * dx + dy * dy < 26 * 26 && !(x % 13 == 5 && y % 11 == 7);
            int kind = rnd() < 0.5f ? 1 : 2; /* mirror or Phong */
            int seen = !(x > 50 && y < 10);
            int zero_rho = x < 4 && y > 40;
            pos[4 * i + 3] = seen ? 1.0f : 0.0f;
            nrm[4 * i + 2] = 1;
            nrm[4 * i + 3] = in || zero_rho ? (float)kind : 0.0f;
            for (int c = 0; c < 3; c++)
                spc[4 * i + c] = in && !zero_rho ? 0.5f : 0.0f;
            spec[i] = in && seen && !zero_rho;
        }
    unsigned tp = array_tex(R, pos), tn = array_tex(R, nrm), ts = array_tex(R, spc), tm;
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &tm);
    glTextureStorage3D(tm, L + 1, GL_R32F, R, R, 1);
    glBindTextureUnit(GIB_UNIT_LV_POSITION, tp);
    glBindTextureUnit(GIB_UNIT_LV_NORMAL, tn);
    glBindTextureUnit(GIB_UNIT_LV_SPECULAR, ts);
    glUseProgram(prog);
    int ok = 1;
    for (int l = 0; l <= L; l++) {
        int res = R >> l;
        glBindImageTexture(0, tm, l, GL_TRUE, 0, GL_WRITE_ONLY, GL_R32F);
        glBindImageTexture(1, tm, l > 0 ? l - 1 : 0, GL_TRUE, 0, GL_READ_ONLY, GL_R32F);
        glUniform1i(2, l);
        glUniform1i(3, res);
        glDispatchCompute((unsigned)(res + 7) / 8, (unsigned)(res + 7) / 8, 1);
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
        static float m[R * R];
        glGetTextureImage(tm, l, GL_RED, GL_FLOAT, (GLsizei)sizeof m, m);
        int gpu = 0, cpu = 0, b = 1 << l;
        for (int i = 0; i < res * res; i++)
            gpu += m[i] == 1.0f;
        for (int y = 0; y < res; y++)
            for (int x = 0; x < res; x++) {
                int all = 1;
                for (int j = 0; j < b; j++)
                    for (int k = 0; k < b; k++)
                        all &= spec[(y * b + j) * R + x * b + k];
                cpu += all;
            }
        int pass = gpu == cpu && cpu > 0;
        snprintf(check_msg, sizeof check_msg,
                 "mask level %d: %d texels exactly 1, %d fully specular blocks of %d^2",
                 l, gpu, cpu, b);
        CHECK_TRUE(check_msg, pass, "");
    }
    unsigned tex[4] = {tp, tn, ts, tm};
    glDeleteTextures(4, tex);
    glDeleteProgram(prog);
    return ok;
}

static int splat(void)
{
    gib_error err;
    const char *files[] = {"ispm_caustics/splat.vert", "ispm_caustics/splat.geom",
                           "ispm_caustics/splat.frag"};
    unsigned prog = gib_program(files, 3, NULL, &err);
    if (!prog) {
        CHECK(0, "splat probe: %s", err.msg);
        return 0;
    }
    enum { R = 512 };
    const float px = 2.0f / R; /* the plane z = 0.2, x and y in [-1, 1], one pixel px wide */
    float *pos = malloc(sizeof(float) * 4 * R * R), *nrm = malloc(sizeof(float) * 4 * R * R);
    for (int y = 0; y < R; y++)
        for (int x = 0; x < R; x++) {
            float *p = pos + 4 * (y * R + x), *n = nrm + 4 * (y * R + x);
            p[0] = -1 + (x + 0.5f) * px, p[1] = -1 + (y + 0.5f) * px, p[2] = 0.2f, p[3] = 1;
            n[0] = 0, n[1] = 0, n[2] = 1, n[3] = 0;
        }
    unsigned t[3], fbo, buf, vao;
    glCreateTextures(GL_TEXTURE_2D, 3, t);
    for (int i = 0; i < 3; i++)
        glTextureStorage2D(t[i], 1, GL_RGBA32F, R, R);
    glTextureSubImage2D(t[0], 0, 0, 0, R, R, GL_RGBA, GL_FLOAT, pos);
    glTextureSubImage2D(t[1], 0, 0, 0, R, R, GL_RGBA, GL_FLOAT, nrm);
    glCreateFramebuffers(1, &fbo);
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, t[2], 0);
    const float h = 48 * px, flux[3] = {1.0f, 2.0f, 0.25f};
    const float photon[20] = {0, 0, 1, 1,    0, 0, -1, 0,    flux[0], flux[1], flux[2], 0,
                              0.1f, -0.05f, 0.2f, h,         0, 0, 1, 1};
    glCreateBuffers(1, &buf);
    glNamedBufferData(buf, sizeof photon, photon, GL_STATIC_DRAW);
    glCreateVertexArrays(1, &vao);
    const float id[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0.5f, 0, 0, 0, 0, 1}, zero3[3] = {0, 0, 0};
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(0, 0, R, R);
    const float black[4] = {0, 0, 0, 0};
    glClearBufferfv(GL_COLOR, 0, black);
    glDisable(GL_DEPTH_TEST);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    glUseProgram(prog);
    glUniformMatrix4fv(1, 1, GL_FALSE, id);
    glUniform3fv(6, 1, zero3);
    glUniform1f(2, 0.25f);
    glBindTextureUnit(GIB_UNIT_GBUF_POSITION, t[0]);
    glBindTextureUnit(GIB_UNIT_GBUF_NORMAL, t[1]);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 10, buf);
    glBindVertexArray(vao);
    glDrawArrays(GL_POINTS, 0, 1);
    glDisable(GL_BLEND);
    glBindVertexArray(0);
    glGetTextureImage(t[2], 0, GL_RGBA, GL_FLOAT, (GLsizei)(sizeof(float) * 4 * R * R), pos);
    double sum[3] = {0, 0, 0};
    for (int i = 0; i < R * R; i++)
        for (int c = 0; c < 3; c++)
            sum[c] += (double)pos[4 * i + c] * px * px;
    int before = failures;
    for (int c = 0; c < 3; c++) {
        snprintf(check_msg, sizeof check_msg,
                 "one photon's splat, channel %d: %.5f W integrated over its flux %.5f W", c,
                 sum[c], flux[c]);
        CHECK_NEAR(check_msg, 1, sum[c] / flux[c], 5e-3,
                   "the midpoint rule on the cut Gaussian errs ~1e-4; room for float sums");
    }
    int ok = failures == before;
    glDeleteTextures(3, t);
    glDeleteFramebuffers(1, &fbo);
    glDeleteBuffers(1, &buf);
    glDeleteVertexArrays(1, &vao);
    glDeleteProgram(prog);
    free(pos);
    free(nrm);
    return ok;
}

int main(void)
{
    gib_error err;
    gib_gl_info info;
    if (gib_gl_init(GIB_BACKEND_AUTO, &info, &err) < 0) {
        CHECK(0, "set-up: %s", err.msg);
        return 1;
    }
    printf("renderer %s\n", info.renderer);
    failures += !phong();
    failures += !mask();
    failures += !splat();
    printf("%s\n", failures ? "FAIL" : "PASS");
    return failures != 0;
}
