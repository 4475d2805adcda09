/* gibench — one description of a pass's fixed-function state, set whole by gib_pass_apply so that
 * a pass never inherits what the pass before it left (blending, a stencil test, a colour mask).
 * Zero means the usual default in every field, as in sokol's sg_pipeline_desc: a pass writes only
 * what differs,
 *     gib_pass_apply(&(gib_pass_state){.fbo = fbo, .width = w, .height = h,
 *                                      .blend = GIB_BLEND_ADD});
 * and what it leaves unwritten is off: no blending, no depth test, no culling, no stencil test,
 * colour written. The viewport has no default: width and height are the pass's. Programs, vertex
 * arrays, textures and buffers are not state here: a pass binds its own. A pass starts with
 * gib_pass_apply and ends with gib_pass_end. */
#ifndef GIB_PASS_STATE_H
#define GIB_PASS_STATE_H

typedef enum gib_blend {
    GIB_BLEND_OFF = 0,
    GIB_BLEND_ADD,          /* dst + src (GL_ONE, GL_ONE, GL_FUNC_ADD): passes that sum */
} gib_blend;

typedef enum gib_depth {
    GIB_DEPTH_OFF = 0,      /* no test; nothing written */
    GIB_DEPTH_LESS,         /* nearer fragments pass and are written */
    GIB_DEPTH_REVERSED,     /* depth 1 near, 0 far (glClipControl's [0, 1] range for the pass):
                               fragments of greater depth pass and are written; clear to 0 */
} gib_depth;

typedef enum gib_cull {
    GIB_CULL_NONE = 0,      /* front and back faces drawn */
    GIB_CULL_BACK,          /* counter-clockwise faces are the front */
} gib_cull;

typedef enum gib_stencil {
    GIB_STENCIL_OFF = 0,
    GIB_STENCIL_MARK,       /* every fragment drawn writes stencil_ref */
    GIB_STENCIL_EQUAL,      /* only fragments where the stencil is stencil_ref pass; none written */
} gib_stencil;

typedef struct gib_pass_state {
    unsigned fbo;           /* 0: the default framebuffer */
    int x, y;               /* the viewport's lower left corner, pixels */
    int width, height;      /* the viewport's size: no default */
    gib_blend blend;
    gib_depth depth;
    gib_cull cull;
    gib_stencil stencil;
    int stencil_ref;
    int no_color;           /* 1: colour writes off (a pass that marks the stencil only) */
} gib_pass_state;

/* Binds the framebuffer and sets the viewport and every fixed-function state the struct names,
 * defaults included; the scissor test is off. */
void gib_pass_apply(const gib_pass_state *s);
/* Sets the fixed-function state back to the zero description's (the framebuffer and viewport
 * stay): what comes after the pass, the harness's clears of its targets included, finds colour,
 * depth and stencil writes on and no blending or tests. */
void gib_pass_end(void);

#endif
