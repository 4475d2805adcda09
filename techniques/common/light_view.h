/* gibench — the view of every light, written once (ARCHITECTURE.md, "Light views"): rendered each
 * frame into a reflective shadow map (Dachsbacher and Stamminger 2005) whose attributes the
 * techniques ask for. Shadow maps read its depth; photon emission, VPLs and the LRSM read its
 * position, normal, flux and specular part.
 *
 * A point light is seen through the 6 faces of a cube; a spot light whose cone is at most 45
 * degrees from its axis through one perspective view over the cone (its texels are then never
 * coarser than a cube face's), a wider spot through the cube; a directional light through an
 * orthographic view fitted to the scene's bounding sphere. Every face is a layer of one 2D array
 * per attribute; the table (light_view.glsl) says which layers a light has and how each projects. */
#ifndef GIB_LIGHT_VIEW_H
#define GIB_LIGHT_VIEW_H

#include "techniques/common/light_view_shared.h"
#include "techniques/technique.h"

enum gib_lv_attribute {
    GIB_LV_DEPTH = 1u << 0,    /* R32F: distance to the light; ortho: depth along the light's
                                  direction from the plane behind the scene; +inf where empty */
    GIB_LV_POSITION = 1u << 1, /* RGBA32F: world position, w = 1 where a surface was seen */
    GIB_LV_NORMAL = 1u << 2,   /* RGBA32F: shading normal facing the light, w = the specular mask
                                  (the material's specular type: 0 none, 1 mirror, 2 Phong) */
    GIB_LV_FLUX = 1u << 3,     /* RGBA32F: rgb = rho_d x the flux reaching the texel (W): the
                                  flux the surface seen there reflects diffusely */
    GIB_LV_SPECULAR = 1u << 4, /* RGBA32F: rgb = rho_s, w = Phong exponent */
};
#define GIB_LV_ATTRIBUTE_COUNT 5
/* Not an attribute: views of point and spot lights only (techniques that emit photons from local
 * lights allocate and render nothing for directional ones). */
#define GIB_LV_LOCAL_LIGHTS_ONLY (1u << 8)
/* Not an attribute: the LRSM paper's RSM format (Sec. 6: reflected radiance, depth, normal and
 * <n.l> "packed in two 16-bit per component textures"; Table 2: 16 bytes a texel with mips, 22.37
 * MB at 1024^2) instead of the attributes: textures[0] RGBA16F rgb = the reflected radiance
 * rho E <n.l> / pi, a = the depth (+inf where empty); textures[1] RGBA16F xyz = the normal facing
 * the light, w = <n.l>. Both are allocated with full mip chains, as the paper's figure counts them
 * (the chains are not built: the LRSM is the RSM's filtered form); the z-buffer the rasteriser
 * needs is labelled "<label>_raster.zbuffer", a structure apart, which Table 2 does not list. */
#define GIB_LV_PACKED16 (1u << 9)

/* The kinds of view; their values are light_view_shared.h's, which the shaders read. */
enum gib_lv_kind {
    GIB_LV_CUBE = GIB_LV_KIND_CUBE,
    GIB_LV_PERSPECTIVE = GIB_LV_KIND_PERSPECTIVE,
    GIB_LV_ORTHO = GIB_LV_KIND_ORTHO,
};

typedef struct gib_lv_face {
    int light, kind;
    float origin[3];     /* the light's position; ortho: the centre of the plane behind the scene */
    float forward[3];    /* view axis */
    float right[3], up[3]; /* the view's other axes: a texel's step in x and in y */
    float view_proj[16]; /* maps p - origin to clip space */
} gib_lv_face;

typedef struct gib_light_views {
    int res;
    unsigned attributes;           /* GIB_LV_* bits rendered */
    int packed;                    /* GIB_LV_PACKED16: textures[0..1] hold the packed format */
    int face_count;
    gib_lv_face *faces;
    int *first_face;               /* per light */
    int *faces_of;                 /* per light: 6 (cube), 1, or 0 (not viewed) */
    float *texel;                  /* per light: a texel's side on the plane at unit distance
                                      (perspective, cube) or in world units (ortho) */
    unsigned textures[GIB_LV_ATTRIBUTE_COUNT]; /* 2D arrays, one layer per face; 0 if not asked */
    unsigned depth, fbo, program, table;
    float *table_data;
    int table_floats;
} gib_light_views;

/* The kind of view light l gets (whether or not a light view set includes it). */
int gib_light_view_kind(const gib_light *l);
/* Allocates res x res views of every light with the given attributes (GIB_LV_DEPTH always) through
 * the ledger, labelled "<label>.<attribute>". */
int gib_light_views_create(gib_light_views *lv, const gib_gpu_scene *scene, int res,
                           unsigned attributes, const char *label, gib_ledger *ledger,
                           gib_error *err);
/* Renders every light's views, timed as pass `pass`. The views are set up each frame from the
 * scene's lights and bounds, as a scene that moves would need. */
void gib_light_views_render(gib_light_views *lv, const gib_gpu_scene *scene, gib_timers *timers,
                            const char *pass);
/* Binds the attributes to GIB_UNIT_LV_* and the table to GIB_SSBO_LIGHT_VIEWS. */
void gib_light_views_bind(const gib_light_views *lv);
void gib_light_views_destroy(gib_light_views *lv, gib_ledger *ledger);

#endif
