/* What the vct tests that trace cones through vct_probe.comp share: the GL fixture and the probe
 * program, and one dispatch over n cones (in: (p, tan_half), (n, max_dist), (D, 0) per cone; out:
 * vct_cone's (radiance, occlusion)). */
#ifndef GIB_TEST_VCT_PROBE_H
#define GIB_TEST_VCT_PROBE_H

#include <glad/gl.h>
#include <stdio.h>
#include <stdlib.h>

#include "harness/gl/bindings.h"
#include "techniques/common/shader.h"
#include "techniques/vct/vct.h"
#include "techniques/vct/vct_slots.h"
#include "tests/common/gl_fixture.h"

/* Opens the fixture (the Cornell box's context) and builds the probe. On failure prints FAIL and
 * returns -1. */
static inline int vct_probe_open(gib_gl_fixture *fx, unsigned *prog)
{
    if (gib_fixture_open(fx, "cornell") < 0)
        return -1;
    gib_error err;
    const char *files[] = {"vct/vct_probe.comp"};
    *prog = gib_program(files, 1, NULL, &err);
    if (!*prog) {
        printf("FAIL: %s\n", err.msg);
        gib_fixture_close(fx);
        return -1;
    }
    return 0;
}

/* Writes rad and nrm (res^3 RGBA floats each, radiance + occlusion and normal) into v's base
 * voxels, frees them, and builds the anisotropic mips. */
static inline void vct_probe_upload(vct_volume *v, int res, float *rad, float *nrm)
{
    glTextureSubImage3D(v->radiance, 0, 0, 0, 0, res, res, res, GL_RGBA, GL_FLOAT, rad);
    glTextureSubImage3D(v->normal, 0, 0, 0, 0, res, res, res, GL_RGBA, GL_FLOAT, nrm);
    free(rad);
    free(nrm);
    vct_volume_mips(v);
}

/* The n cones of `in` traced through v with `cones`' settings into out. 0, or -1 on a GL error. */
static inline int vct_probe_run(unsigned prog, const vct_volume *v, const vct_cone_settings *cones,
                                const float (*in)[4], int n, float (*out)[4])
{
    GLuint buf[2];
    glCreateBuffers(2, buf);
    glNamedBufferStorage(buf[0], (GLsizeiptr)(sizeof in[0] * 3 * n), in, 0);
    glNamedBufferStorage(buf[1], (GLsizeiptr)(sizeof out[0] * n), NULL, 0);
    glUseProgram(prog);
    vct_volume_bind_cones(v, cones);
    glUniform1i(VCT_PROBE_LOC_COUNT, n);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GIB_SSBO_OWN_FIRST + 1, buf[0]);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GIB_SSBO_OWN_FIRST + 2, buf[1]);
    glDispatchCompute((GLuint)(n + 63) / 64, 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetNamedBufferSubData(buf[1], 0, (GLsizeiptr)(sizeof out[0] * n), out);
    glDeleteBuffers(2, buf);
    gib_error err;
    return gib_gl_check("vct probe", &err);
}

#endif
