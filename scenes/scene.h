/* gibench — the one scene model seen by the GL techniques and by the path tracer (ARCHITECTURE.md,
 * "One scene model for both sides"). Everything is flattened to world space at load time.
 *
 * Conventions shared by both sides (and mirrored in techniques/common/scene.glsl):
 *  - camera: pinhole, vertical field of view, rays through pixel centres, image row 0 on top;
 *    gib_camera_ray() is the definition.
 *  - lights: point (intensity I in W/sr, radiance at distance r: I / r^2), spot (intensity on the
 *    axis, times cos^e(theta) inside the outer angle, 0 outside), directional (irradiance E on a
 *    surface facing it). gib_light_eval() is the definition.
 *  - materials: Lambertian albedo rho_d (times a texture, linearised from sRGB), plus an optional
 *    specular lobe (mirror, or normalised Phong with exponent n) with rho_d + rho_s <= 1.
 *    BRDF f = rho_d / pi (+ specular). two_sided: the shading normal faces the viewer.
 *  - units: linear RGB radiance; `exposure` scales images for previews and the SSIM channel. */
#ifndef GIB_SCENE_H
#define GIB_SCENE_H

#include <stdint.h>

#include "harness/base/error.h"

enum gib_spec_type { GIB_SPEC_NONE = 0, GIB_SPEC_MIRROR = 1, GIB_SPEC_PHONG = 2 };
enum gib_light_type { GIB_LIGHT_POINT = 0, GIB_LIGHT_SPOT = 1, GIB_LIGHT_DIRECTIONAL = 2 };

/* Scene feature flags: what a scene contains, so that the harness runs only technique/scene pairs
 * that make sense and techniques allocate nothing for absent effects. */
enum gib_feature {
    GIB_FEAT_TEXTURES = 1u << 0,    /* some material has an albedo texture */
    GIB_FEAT_SPECULAR = 1u << 1,    /* some material has a Phong lobe */
    GIB_FEAT_MIRROR = 1u << 2,      /* some material is a mirror */
    GIB_FEAT_POINT_LIGHT = 1u << 3, /* has a point light */
    GIB_FEAT_SPOT_LIGHT = 1u << 4,
    GIB_FEAT_DIR_LIGHT = 1u << 5,
    GIB_FEAT_ALPHA_MASK = 1u << 6,  /* some material has an alpha (cut-out) mask */
    GIB_FEAT_CLOSED = 1u << 7,      /* geometry encloses the camera and lights (no escaping rays) */
    GIB_FEAT_SKY = 1u << 8,         /* a uniform sky: rays that escape see radiance `sky` */
};

typedef struct gib_texture {
    char path[512];     /* as resolved on disk */
    int width, height;
    float *rgba;        /* width*height*4, LINEAR (sRGB decoded for colour), row 0 = top of image,
                         * i.e. texel (s, t) with t = 1 - v */
} gib_texture;

typedef struct gib_material {
    char name[128];
    float albedo[3];      /* rho_d, linear; multiplied by the texture when albedo_tex >= 0 */
    int albedo_tex;       /* index into scene->textures, -1 for none */
    int alpha_tex;        /* cut-out mask (texture's first channel < 0.5 is a hole), -1 for none */
    int spec_type;        /* enum gib_spec_type */
    float specular[3];    /* rho_s */
    float phong_n;        /* normalised Phong exponent, for GIB_SPEC_PHONG */
    int two_sided;        /* 1: lit from both sides (shading normal flipped toward the viewer) */
} gib_material;

typedef struct gib_light {
    char name[64];
    int type;             /* enum gib_light_type */
    float position[3];    /* point, spot */
    float direction[3];   /* spot axis / direction the directional light travels; unit length */
    float intensity[3];   /* W/sr on the axis (point, spot), irradiance W/m^2 (directional) */
    float spot_exponent;  /* e in cos^e(theta) */
    float spot_outer_deg; /* half-angle of the cone outside which the spot gives nothing */
} gib_light;

typedef struct gib_camera {
    char name[64];
    float eye[3], target[3], up[3];
    float vfov_deg;       /* vertical field of view, full angle */
} gib_camera;

/* Triangles grouped in draw ranges of one material each (GL binds a material's texture once per
 * range). Positions and normals in world space; uv per vertex (0 where the mesh has none). */
typedef struct gib_draw_range {
    uint32_t first_index; /* into idx (a multiple of 3) */
    uint32_t index_count;
    uint32_t material;
} gib_draw_range;

/* A mesh that moves (FORMAT.md, "Motion"): its vertices [first_vertex, first_vertex +
 * vertex_count) are posed at time t by gib_motion_pose. Rigid: keyframes of rotation (Euler
 * degrees, R = Rz Ry Rx) about `pivot` and translation, interpolated linearly (USD's
 * xformOp time samples); p(t) = R(t) (p_rest - pivot) + pivot + T(t), p_rest the placed mesh.
 * Water: a height field y = sum_i a_i sin(k_i . (x, z) - w_i t) in the mesh's own frame, then
 * the mesh's placement (m, nm, translate). */
enum gib_motion_kind { GIB_MOTION_RIGID = 0, GIB_MOTION_WATER = 1 };
#define GIB_MOTION_MAX_KEYS 16
#define GIB_MOTION_MAX_WAVES 8
typedef struct gib_wave {
    float amplitude, k[2], omega; /* a, wave vector (rad/unit) in x and z, angular speed (rad/s) */
} gib_wave;
typedef struct gib_motion {
    char mesh[64];
    int kind;                      /* enum gib_motion_kind */
    uint32_t first_vertex, vertex_count;
    float *rest_positions;         /* rigid: placed, world space; water: the grid in the mesh's
                                    * own frame at height 0 */
    float *rest_normals;           /* rigid only */
    int key_count, loop;           /* loop: time wraps over [key 0, last key]; else clamps */
    float key_time[GIB_MOTION_MAX_KEYS];
    float key_rotate[GIB_MOTION_MAX_KEYS][3], key_translate[GIB_MOTION_MAX_KEYS][3];
    float pivot[3];
    int wave_count;
    gib_wave waves[GIB_MOTION_MAX_WAVES];
    float m[3][3], nm[3][3], translate[3]; /* water: the mesh's placement (R S, R S^-1, t) */
} gib_motion;

typedef struct gib_scene {
    char name[64];
    char file[512];        /* the .scene file, or "" for a scene built purely in C */
    char description[512];
    float exposure;        /* for previews and the SSIM channel; default 1 */
    float sky[3];          /* radiance of a uniform sky (environment light) seen by every ray that
                              leaves the scene; 0 = none. Its direct light on a Lambertian point with
                              unoccluded fraction V (cosine-weighted) is rho * sky * V: part of the
                              `direct` component (L D E with L the sky). */

    uint32_t vertex_count;
    float *positions;      /* 3 per vertex */
    float *normals;        /* 3 per vertex, unit length */
    float *uvs;            /* 2 per vertex */
    uint32_t triangle_count;
    uint32_t *indices;     /* 3 per triangle */
    uint32_t *tri_material;/* 1 per triangle (also implied by ranges; the path tracer uses this) */
    gib_draw_range *ranges;
    uint32_t range_count;

    gib_material *materials;
    uint32_t material_count;
    gib_texture *textures;
    uint32_t texture_count;
    gib_light *lights;
    uint32_t light_count;
    gib_camera *cameras;
    uint32_t camera_count; /* >= 1; cameras[0] is the default view */

    gib_motion *motions;   /* meshes that move; none: the scene is static */
    uint32_t motion_count;
    float time;            /* the instant positions/normals hold (0 as loaded) */

    unsigned features;     /* enum gib_feature bits */
    float bounds_min[3], bounds_max[3]; /* with motion: cover every instant (conservative), so
                                           structures sized from them at create stay valid */
    uint64_t content_hash; /* hash of the scene file, every mesh and texture file's bytes and of
                              everything built procedurally: changes whenever the image could */
    char ignored[256];     /* what the load dropped as harmless, comma-separated ("normal maps"):
                              a glTF's features gibench does not model (FORMAT.md, "glTF scenes");
                              "" for none. `gibench list` prints it. */
} gib_scene;

/* Where shared scene data lives: $GIBENCH_SCENES, else <project root>/../shared/scenes when it
 * exists, else NULL. */
const char *gib_scene_data_root(void);

/* The folder holding the project's *.scene files: $GIBENCH_ROOT/scenes when set (a bundle's
 * binary run beside a copy of the repository, harness/device/), else <project root>/scenes. */
const char *gib_scene_dir(void);

/* Loads a scene by name (scenes/<name>.scene) or by path to a .scene file. Errors name the file
 * and line ("scenes/cornell.scene:12: light 'key': 'intensity' expects 3 numbers, got 'abc'").
 * When the scene needs shared data that is absent, returns GIB_SCENE_UNAVAILABLE with a message
 * that says where to get the data. */
#define GIB_SCENE_UNAVAILABLE (-2)
int gib_scene_load(const char *name_or_path, gib_scene *scene, gib_error *err);
void gib_scene_free(gib_scene *scene);

/* Positions and normals of motion m's vertices at time t (seconds), 3 floats per vertex of its
 * range each, written to pos and nrm (indexed from the range's first vertex). */
void gib_motion_pose(const gib_motion *m, double t, float *pos, float *nrm);
/* Poses every moving mesh of the scene at time t in place (positions, normals, scene->time);
 * a static scene is left as it is. */
void gib_scene_set_time(gib_scene *scene, double t);
/* A scene at time t for a renderer that reads the arrays: *posed shares everything with scene
 * but positions and normals, which it owns (static scenes: shares those too). Free with
 * gib_scene_posed_free, never gib_scene_free. */
int gib_scene_posed(const gib_scene *scene, double t, gib_scene *posed, gib_error *err);
void gib_scene_posed_free(gib_scene *posed);

/* One line per scene file found in gib_scene_dir(): name, availability and features. */
typedef struct gib_scene_info {
    char name[64];
    char description[512];
    int available;           /* 0 when its shared data is missing */
    char why_unavailable[512];
} gib_scene_info;
int gib_scene_list(gib_scene_info **out, int *count, gib_error *err);

/* Comma-separated feature names ("textures,spot_light"), for `gibench list` and CSV. */
void gib_features_str(unsigned features, char *out, int out_len);

/* --- the frame both renderers work in (scene_frame.c) ---
 * Float coordinates 1e5 m from the origin are 7.8 mm apart: a renderer that adds ray offsets,
 * subtracts light positions or stores depths there loses the scene (hard_far). So a scene whose
 * largest vertex coordinate exceeds GIB_FRAME_FAR times its diagonal is moved next to the origin
 * first, by `origin` (its bounding box's centre on a power-of-two grid, so that moving a vertex is
 * exact), positions, lights and cameras alike; the path tracer and the GL side render that copy,
 * whose images are the scene's (every image is translation-invariant). A scene nearer the origin
 * keeps its own coordinates bit for bit (origin 0): there, floats already resolve the scene to
 * 2^-24 x GIB_FRAME_FAR of its diagonal. The frame depends on the scene alone, not on a camera,
 * so one BVH or GPU upload serves every camera. */
#define GIB_FRAME_FAR 8.0
typedef struct gib_scene_frame {
    gib_scene scene;       /* the copy: positions, lights, cameras, bounds moved; the rest shared */
    float origin[3];       /* world = frame + origin; 0 when not moved */
    int moved;
    float *positions;      /* owned when moved */
    gib_light *lights;
    gib_camera *cameras;
} gib_scene_frame;
void gib_scene_frame_origin(const gib_scene *scene, float origin[3]);
/* Fills f: f->scene is a shallow copy of scene, with its own moved positions, lights and cameras
 * when f->moved (nothing is allocated otherwise). */
int gib_scene_frame_make(const gib_scene *scene, gib_scene_frame *f, gib_error *err);
void gib_scene_frame_free(gib_scene_frame *f);

/* --- camera and light definitions shared with the path tracer --- */

/* Orthonormal camera basis: right, up, and forward (unit vectors). */
void gib_camera_basis(const gib_camera *cam, float right[3], float up[3], float forward[3]);
/* World-space ray through image position (px, py) in pixels (pixel centres are at +0.5),
 * row 0 on top. dir is unit length; origin = eye. */
void gib_camera_ray(const gib_camera *cam, int width, int height, float px, float py,
                    float origin[3], float dir[3]);

/* Light arriving at point p from light l: fills wi (unit, from p toward the light; for a
 * directional light, -direction), the distance to the light (INFINITY for directional), and the
 * incident radiance-like quantity E such that the reflected radiance of a Lambertian surface is
 * (rho/pi) * E * max(0, dot(n, wi)) when unshadowed: E = I * falloff / r^2 (point, spot) or the
 * irradiance (directional). Returns 0 when the light gives nothing at p (outside the spot cone). */
int gib_light_eval(const gib_light *l, const float p[3], float wi[3], float *dist, float E[3]);

/* cos^e(theta) inside the outer angle, 0 outside (theta from the spot axis). */
float gib_spot_falloff(const gib_light *l, const float dir_from_light[3]);
/* The same two with the spot's cos(outer angle) given, as gib_spot_cos_outer(l) computes it once
 * per light (the path tracer evaluates lights at every vertex). */
float gib_spot_cos_outer(const gib_light *l);
/* gib_spot_falloff_cos(l, cos_outer, dir_from_light) and
 * gib_light_eval_cos(l, cos_outer, p, wi, dist, E): static inline, in light_eval.h. */
#include "light_eval.h"

#endif
