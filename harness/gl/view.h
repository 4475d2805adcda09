/* gibench — view and projection matrices that reproduce gib_camera_ray() exactly under GL
 * rasterisation: the pixel centre (i + 0.5, GL row j) maps to the ray through image pixel
 * (i + 0.5, height - 1 - j + 0.5). Column-major 4x4, GL clip conventions. */
#ifndef GIB_VIEW_H
#define GIB_VIEW_H

#include "scenes/scene.h"

/* What a technique is told about the frame it renders. */
typedef struct gib_view {
    const gib_camera *camera;
    int width, height;
    float time;           /* seconds, for animated scenes */
    /* Column-major, GL conventions, RELATIVE to `origin` (the camera's eye): shaders transform
     * p - origin, a subtraction that is exact near the camera, so a scene far from the world origin
     * keeps its precision (hard case `hard_far`: 1e5 m away, where view_proj * p loses the depth). */
    float view[16], proj[16], view_proj[16];
    float origin[3];
} gib_view;

void gib_mat4_mul(const float a[16], const float b[16], float out[16]);
/* Camera-style view matrix from an orthonormal basis (right, up, forward) and an origin. */
void gib_mat4_view(const float right[3], const float up[3], const float forward[3],
                   const float eye[3], float out[16]);
/* Orthonormal t, b completing the unit direction d (t x b = d), the same as ortho_basis() in
 * techniques/common/basis.glsl: shadow maps and LDMs build their orthographic views with it. */
void gib_ortho_basis(const float d[3], float t[3], float b[3]);
void gib_mat4_perspective(float vfov_rad, float aspect, float znear, float zfar, float out[16]);
void gib_mat4_ortho(float l, float r, float b, float t, float n, float f, float out[16]);
/* The same with reversed depth for glClipControl's [0, 1] range: 1 at the near plane, 0 at the far
 * one. With a float depth buffer the depth's precision is then about the same share of the
 * distance everywhere (a 24-bit buffer with near = far / 1e5 resolved 4-7 cm at 15 m). */
void gib_mat4_perspective_reversed(float vfov_rad, float aspect, float znear, float zfar,
                                   float out[16]);
void gib_mat4_ortho_reversed(float l, float r, float b, float t, float n, float f, float out[16]);

/* The sphere that orthographic views of the scene are fitted to (light views, LDMs): centre of
 * the bounding box, radius half its diagonal with a 1% margin, so that geometry on the sphere still
 * rasterises inside the map. */
void gib_view_bounding_sphere(const gib_scene *scene, float centre[3], float *radius);

/* Fills view->view, proj, view_proj (relative to view->origin = the eye) for a scene camera; near
 * and far planes from the scene bounds. */
void gib_view_make(const gib_scene *scene, const gib_camera *cam, int width, int height, float time,
                   gib_view *view);

#endif
