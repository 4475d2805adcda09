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
    const gib_pass_state state = {.fbo = fbo, .width = width, .height = height,
                                  .blend = additive ? GIB_BLEND_ADD : GIB_BLEND_OFF};
    gib_fullscreen_begin_pass(fs, &state);
}

void gib_fullscreen_begin_pass(const gib_fullscreen *fs, const gib_pass_state *state)
{
    gib_pass_apply(state);
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
    gib_pass_end();
}

void gib_fullscreen_destroy(gib_fullscreen *fs)
{
    if (fs->program)
        glDeleteProgram(fs->program);
    if (fs->vao)
        glDeleteVertexArrays(1, &fs->vao);
    memset(fs, 0, sizeof *fs);
}
