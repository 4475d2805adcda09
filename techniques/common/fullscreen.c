#include "fullscreen.h"

#include <glad/gl.h>
#include <string.h>

#include "techniques/common/shader.h"

int gib_fullscreen_create(gib_fullscreen *fs, const char *fragment, const char *defines,
                          gib_error *err)
{
    memset(fs, 0, sizeof *fs);
    const char *files[] = {"common/fullscreen.vert", fragment};
    if (!(fs->program = gib_program(files, 2, defines, err)))
        return -1;
    glCreateVertexArrays(1, &fs->vao);
    return 0;
}

void gib_fullscreen_begin(const gib_fullscreen *fs, unsigned fbo, int width, int height,
                          int additive)
{
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(0, 0, width, height);
    glDisable(GL_DEPTH_TEST);
    if (additive) {
        glEnable(GL_BLEND);
        glBlendFunc(GL_ONE, GL_ONE);
    } else {
        glDisable(GL_BLEND);
    }
    glUseProgram(fs->program);
    glBindVertexArray(fs->vao);
}

void gib_fullscreen_draw(const gib_fullscreen *fs)
{
    (void)fs;
    glDrawArrays(GL_TRIANGLES, 0, 3);
}

void gib_fullscreen_end(void)
{
    glBindVertexArray(0);
    glDisable(GL_BLEND);
}

void gib_fullscreen_destroy(gib_fullscreen *fs)
{
    if (fs->program)
        glDeleteProgram(fs->program);
    if (fs->vao)
        glDeleteVertexArrays(1, &fs->vao);
    memset(fs, 0, sizeof *fs);
}
