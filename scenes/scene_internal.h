/* gibench — internals of the scene loader, shared by the files in scenes/ and by their tests.
 * Not part of the public interface (scene.h): nothing outside scenes/ and tests/scenes/ should
 * include this.
 *
 * Loading runs in stages, each in its own file:
 *   scene_file.c   the .scene text (INI via libinih) -> gib_scene_spec, file:line for every key
 *   scene_check.c  whole-file checks of the spec; is the shared data there?
 *   procedural.c   generators built in C: their keys and checks, cornell_box, plane_box, room
 *   proc_shapes.c  quad, box, slivers, sphere_interior; proc_hairball.c: hairball;
 *                  proc_water.c: water; proc_ring.c: ring
 *   mesh_import.c  mesh files through assimp (OBJ+MTL, PLY, gzipped PLY) -> gib_geom
 *   gltf_scene.c   a glTF's cameras, lights and materials for [scene] gltf (FORMAT.md, "glTF
 *                  scenes"), read with gltf_bounds.c's JSON reader
 *   scene_build.c  spec + geometry -> the flattened gib_scene (materials, ranges, hash, features)
 *   textures.c     texture files -> linear float RGBA, cached per file
 *   paths.c        data root, case-insensitive path resolution
 *   scene_load.c   the public entry points: load, list, free
 *   camera_light.c the camera and light definitions both renderers share */
#ifndef GIB_SCENE_INTERNAL_H
#define GIB_SCENE_INTERNAL_H

#include <stddef.h>
#include <stdint.h>

#include "scene.h"

/* Changes whenever the loader or a generator would build different data from the same files, so
 * the content hash (and with it the reference cache) changes too. */
#define GIB_SCENE_LOADER_VERSION "gib_scene 1"

#define GIB_PATH_MAX 512

/* ---------------------------------------------------------------- geometry under construction */

/* A material as a mesh file or generator describes it, with its texture files not yet loaded. */
typedef struct gib_mat_desc {
    gib_material m;                /* albedo_tex / alpha_tex are -1 here */
    char albedo_path[GIB_PATH_MAX]; /* texture file as named by the MTL, joined to the mesh's
                                     * folder but not yet resolved on disk; "" for none */
    char alpha_path[GIB_PATH_MAX];
    int mesh_index;                /* the [mesh.*] it came from, for error messages; -1 if none */
    int source_index;              /* mesh files: the file's own material index (assimp's) */
    /* glTF: assimp's reading of the file's material, which gltf_scene.c matches to the file's
     * own (assimp 5.2 orders a glTF's materials by first use, not by index): base colour r g b a,
     * metallic, roughness, and GIB_SRC_* bits */
    float src_pbr[6];
    unsigned src_flags;
} gib_mat_desc;
enum { GIB_SRC_NAMED = 1u << 0, GIB_SRC_BASE_TEX = 1u << 1, GIB_SRC_TWO_SIDED = 1u << 2,
       GIB_SRC_LAST = 1u << 3 /* assimp's last material: glTF's default, for primitives without */ };

/* A growable triangle soup with its own material table; triangles index mats. */
typedef struct gib_geom {
    uint32_t vcount, vcap;
    float *pos, *nrm, *uv;         /* 3, 3, 2 floats per vertex */
    uint32_t tcount, tcap;
    uint32_t *idx;                 /* 3 per triangle */
    uint32_t *mat;                 /* 1 per triangle, into mats */
    uint32_t mcount, mcap;
    gib_mat_desc *mats;
} gib_geom;

/* Makes room for `verts` more vertices and `tris` more triangles. */
int gib_geom_reserve(gib_geom *g, uint32_t verts, uint32_t tris, gib_error *err);
/* Appends a vertex (room must have been reserved); uv may be NULL. Returns its index. */
uint32_t gib_geom_vertex(gib_geom *g, const float p[3], const float n[3], const float uv[2]);
/* Appends a triangle (room must have been reserved). */
void gib_geom_triangle(gib_geom *g, uint32_t a, uint32_t b, uint32_t c, uint32_t material);
/* Appends a material; returns its index, or -1 on allocation failure. */
int gib_geom_material(gib_geom *g, const gib_mat_desc *m, gib_error *err);
void gib_geom_free(gib_geom *g);
/* A Lambertian, two-sided material description with the given albedo. */
gib_mat_desc gib_mat_desc_diffuse(const char *name, float r, float g, float b);

/* ---------------------------------------------------------------- procedural generators */

/* Keys a [mesh.NAME] section gives to a procedural generator (FORMAT.md says which generator takes
 * which). The parser checks each key's own rules (how many numbers, whole or not, range); the
 * generator's rules (which keys it takes, limits on combinations) are gib_procedural_check's. */
enum gib_proc_key {
    GIB_PK_SIZE,         /* room, box: w h d; quad, slivers: w d */
    GIB_PK_RADIUS,       /* hairball: radius of the ball; sphere_interior: of the sphere */
    GIB_PK_THICKNESS,    /* hairball: radius of one tube */
    GIB_PK_TUBES,        /* hairball: number of tubes */
    GIB_PK_SEGMENTS,     /* hairball: segments per tube; slivers: fan triangles */
    GIB_PK_SIDES,        /* hairball: sides of a tube's cross-section */
    GIB_PK_SEED,         /* hairball: random seed */
    GIB_PK_SUBDIVISIONS, /* sphere_interior: icosahedron subdivision levels */
    GIB_PK_HEIGHT,       /* ring: height of the wall */
    GIB_PK_COUNT
};

typedef struct gib_proc_params {
    unsigned set;                  /* bit k: key k was given */
    int line[GIB_PK_COUNT];        /* the line that gave it */
    int count[GIB_PK_COUNT];       /* how many numbers it gave */
    double v[GIB_PK_COUNT][3];
} gib_proc_params;

typedef struct gib_proc_key_info {
    const char *name;
    int min_n, max_n;              /* how many numbers */
    int whole;                     /* 1: whole numbers in [lo, hi]; 0: numbers in (lo, hi] */
    double lo, hi;
} gib_proc_key_info;

/* Parses generator key `name` = `value` (given on `line`) into p, checking the key's own rules.
 * 0, or -1 with a message ("'sides' must be a whole number from 3 to 64, got '2'"). */
int gib_proc_key_parse(gib_proc_params *p, const char *name, const char *value, int line,
                       char *msg, size_t msg_len);
/* The key called `name` (enum gib_proc_key), or -1. */
int gib_proc_key_find(const char *name);
const gib_proc_key_info *gib_proc_key_get(int key);
/* Component i of key k when given, else dflt. */
double gib_proc_get(const gib_proc_params *p, int key, int i, double dflt);

/* The hairball's defaults (FORMAT.md); thickness is a fraction of the radius. */
#define GIB_HAIRBALL_RADIUS 1.0
#define GIB_HAIRBALL_THICKNESS 0.01
#define GIB_HAIRBALL_TUBES 1200
#define GIB_HAIRBALL_SEGMENTS 20
#define GIB_HAIRBALL_SIDES 6
#define GIB_HAIRBALL_SEED 1

/* 1 if `name` is a known generator. */
int gib_procedural_known(const char *name);
/* The comma-separated list of generator names, for error messages. */
const char *gib_procedural_names(void);
/* The generator's own rules on its keys. Returns 0, or -1 with a message in msg and in *key the
 * key whose line the message is about (-1: the `procedural` line). */
int gib_procedural_check(const char *name, const gib_proc_params *p, int *key, char *msg,
                         size_t msg_len);
/* Builds the generator's triangles and materials into out (appending), and hashes its name and
 * parameters into *hash. Parameters must have passed gib_procedural_check. */
int gib_procedural_build(const char *name, const gib_proc_params *p, gib_geom *out,
                         uint64_t *hash, gib_error *err);

/* The generators, one file each beside procedural.c (they append to g; p as checked). */
int gib_gen_quad(gib_geom *g, const gib_proc_params *p, gib_error *err);
int gib_gen_box(gib_geom *g, const gib_proc_params *p, gib_error *err);
int gib_gen_slivers(gib_geom *g, const gib_proc_params *p, gib_error *err);
int gib_gen_sphere_interior(gib_geom *g, const gib_proc_params *p, gib_error *err);
int gib_gen_hairball(gib_geom *g, const gib_proc_params *p, gib_error *err);
int gib_gen_water(gib_geom *g, const gib_proc_params *p, gib_error *err);
int gib_gen_ring(gib_geom *g, const gib_proc_params *p, gib_error *err);
/* The ring's defaults (FORMAT.md): inner radius; thickness and height are fractions of it. */
#define GIB_RING_RADIUS 0.5
#define GIB_RING_THICKNESS 0.06
#define GIB_RING_HEIGHT 0.6
#define GIB_RING_SEGMENTS 32
/* The water grid's defaults (FORMAT.md). */
#define GIB_WATER_SIZE 4.0
#define GIB_WATER_SEGMENTS 64

/* Rotation about x, then y, then z by deg (degrees): r = Rz Ry Rx (scene_build.c). */
void gib_euler_rotation(const float deg[3], float r[3][3]);
/* Frees the motions' arrays (gib_scene_free). */
void gib_scene_free_motion(gib_scene *sc);

/* Building blocks for flat faces (geom.c): each triangle gets its own vertices carrying its
 * geometric normal. add_quad: corners in order around the face, any winding; the normal is made
 * to point toward `toward` (facing = +1) or away from it (-1); uvs are the unit square.
 * add_box: axis-aligned [lo, hi], faces outward (inward = 0) or inward; face order -x, +x, -y,
 * +y, -z, +z; skip_mask bit f leaves face f out; mats[f] is face f's material. Room for the
 * vertices and triangles must have been reserved (6 and 2 per face). */
void gib_geom_add_quad(gib_geom *g, float q[4][3], const float toward[3], int facing,
                       uint32_t material);
void gib_geom_add_box(gib_geom *g, const float lo[3], const float hi[3], int inward,
                      unsigned skip_mask, const uint32_t mats[6]);

/* ---------------------------------------------------------------- mesh files */

/* Imports a mesh file (OBJ+MTL, PLY, OFF, STL, glTF 2.0, GLB, gzipped PLY/OFF/STL/GLB; others are
 * refused, gib_mesh_format) into out (appending), after gib_mesh_bounds has passed,
 * in the file's own coordinates. Hashes the bytes of every file read (the mesh, its MTL) into
 * *hash. smooth_angle_deg limits normal smoothing for meshes that carry no normals. Texture paths
 * are stored joined to the mesh's folder, unresolved. Errors name the file. */
int gib_mesh_import(const char *path, float smooth_angle_deg, gib_geom *out, uint64_t *hash,
                    gib_error *err);
/* The same with flags: GIB_IMPORT_NO_TEXTURES leaves the materials' texture paths empty (a glTF
 * whose materials gltf_scene.c maps, embedded textures included). Each material's source_index
 * is the file's own (assimp's) material index. */
enum { GIB_IMPORT_NO_TEXTURES = 1u << 0 };
int gib_mesh_import_ex(const char *path, float smooth_angle_deg, unsigned import_flags,
                       gib_geom *out, uint64_t *hash, gib_error *err);

/* mesh_bounds.c: the mesh formats gibench reads (scenes/FORMAT.md, "Meshes"). gib_mesh_format
 * puts path's format ("obj", "ply", "off", "stl", "gltf", "glb") in fmt and sets *gz for a
 * gzipped one (.ply.gz, .off.gz, .stl.gz, .glb.gz): 0, or -1 with an error naming the file and
 * the formats read. gib_mesh_formats_text: that list, in words. */
int gib_mesh_format(const char *path, char fmt[8], int *gz, gib_error *err);
const char *gib_mesh_formats_text(void);
/* 0 when what data (a whole mesh file of format fmt, len bytes) declares fits its bytes (and the
 * format's own check passes: gib_obj_check, gib_ply_check); else -1 with an error naming the file,
 * what it declared and its size. Every mesh file goes through it before assimp reads it. */
int gib_mesh_bounds(const char *data, size_t len, const char *path, const char *fmt,
                    gib_error *err);
/* gltf_bounds.c: gib_mesh_bounds for glTF 2.0 (glb = 0: JSON; 1: GLB). Buffers named by a uri
 * are found beside path. */
int gib_gltf_bounds(const char *data, size_t len, const char *path, int glb, gib_error *err);

/* The JSON reader of gltf_bounds.c, read-only, for gltf_scene.c. Tokens are ints (the root object
 * is 0; -1 = absent). gib_json_parse: 0, -1 (not one JSON object), -2 (out of memory); text must
 * outlive the document. gib_json_type: 'o', 'a', 's' (string), 'p' (number, true, false, null), -1.
 * gib_json_child: an array's element or an object's KEY after prev (-1: the first), -1 at the end;
 * an object member's value is key + 1. gib_json_num: a finite number, 0 or -1. gib_json_str: a
 * string's raw text (escapes kept), truncated to cap. gib_glb_split: a GLB's JSON and BIN chunks
 * (bin NULL when none), checked as gib_gltf_bounds checks them. */
typedef struct gib_json gib_json;
int gib_json_parse(const char *text, size_t len, gib_json **out);
void gib_json_free(gib_json *j);
int gib_json_get(const gib_json *j, int obj, const char *key);
int gib_json_type(const gib_json *j, int tok);
int gib_json_child(const gib_json *j, int container, int prev);
int gib_json_num(const gib_json *j, int tok, double *out);
int gib_json_str(const gib_json *j, int tok, char *out, size_t cap);
int gib_json_span(const gib_json *j, int tok, const char **s, size_t *n);
int gib_json_streq(const gib_json *j, int tok, const char *s);
int gib_glb_split(const char *data, size_t len, const char *path, const char **json, size_t *jlen,
                  const char **bin, size_t *blen, gib_error *err);

/* gltf_scene.c: what a .scene takes from a glTF 2.0 file on request (FORMAT.md, "glTF scenes"):
 * its cameras, KHR_lights_punctual lights and materials mapped to the scene model, read from its
 * JSON (node transforms included). What gibench cannot model is refused (an error naming the file
 * and the feature); what is harmless to drop is listed in `ignored` ("normal maps, ..."). */
enum { GIB_GLTF_CAMERAS = 1u << 0, GIB_GLTF_LIGHTS = 1u << 1, GIB_GLTF_MATERIALS = 1u << 2 };
typedef struct gib_gltf_info {
    gib_camera *cameras;           /* every node instance with a camera, in node order */
    int camera_count;
    char (*camera_alias)[64];      /* the camera's own name, where the node's differs */
    gib_light *lights;             /* every node instance with a KHR_lights_punctual light */
    int light_count;
    gib_mat_desc *mats;            /* glTF material i, mapped; textures as paths or image refs */
    int mat_count;
    float (*raw)[6];               /* material i's factors as the file gives them (src_pbr) */
    unsigned *raw_flags;           /* and its GIB_SRC_* bits */
    char (*raw_name)[128];         /* its name, "" for none */
    char ignored[256];             /* comma-separated: what was dropped ("normal maps") */
} gib_gltf_info;
int gib_gltf_read(const char *path, unsigned want, gib_gltf_info *out, gib_error *err);
void gib_gltf_info_free(gib_gltf_info *info);
/* The glTF material that assimp's material d (as gib_mesh_import_ex read it) is: its index, -1
 * for none (assimp's default for primitives without a material), or -2 with an error when two
 * of the file's materials that map differently cannot be told apart (unnamed, same factors). */
int gib_gltf_match(const gib_gltf_info *info, const gib_mat_desc *d, const char *path,
                   gib_error *err);
/* The glTF mapping's numbers (FORMAT.md), exposed for the tests. */
#define GIB_GLTF_LM_PER_W 683.0
#define GIB_GLTF_PHONG_MAX 10000.0f
float gib_gltf_phong_n(float roughness);
float gib_gltf_spot_exponent(double inner_rad, double outer_rad);
/* An image embedded in a glTF (a GLB's bufferView, a data: URI) is named "<file>#image<N>"; the
 * alpha-mask of glTF image N (any source) "<file>#mask<N>:<scale>" (mask = alpha x scale).
 * gib_gltf_image_ref: 1 for an image, 2 for a mask, 0 for neither; gib_gltf_image_bytes reads
 * its bytes (malloc'd), the file extension its mimeType implies (".png", ".jpg") and the mask's
 * scale (0 for an image). */
int gib_gltf_image_ref(const char *path);
int gib_gltf_image_bytes(const char *ref, unsigned char **bytes, size_t *len, char ext[8],
                         float *mask_scale, char *errbuf, int errbuf_len);

/* ply_check.c: 0 when data (a whole PLY file, len bytes) is well formed: its header ends in
 * end_header within GIB_PLY_HEADER_MAX bytes, its body holds every element the header declares as
 * the header types them, lists at most 1024 long, face indices within the vertices; else -1 with
 * err naming the file and the line or byte. assimp is never handed a PLY that fails it (it hangs
 * or crashes on some). */
#define GIB_PLY_HEADER_MAX 65536
int gib_ply_check(const char *data, size_t len, const char *path, gib_error *err);
/* obj_check.c: 0 when every element statement (f, l, p) of data (a whole OBJ file, len bytes)
 * refers to vertices as v, v/vt, v//vn or v/vt/vn with indices in the file; else -1 with err naming
 * the file and line. assimp reads past its buffer on some that are not. */
int gib_obj_check(const char *data, size_t len, const char *path, gib_error *err);

/* ---------------------------------------------------------------- textures */

typedef struct gib_tex_cache {
    gib_texture *tex;
    int *srgb;                     /* per entry: 1 if decoded from sRGB (a colour texture) */
    uint32_t count, cap;
} gib_tex_cache;

/* Returns the index of the texture at `resolved_path` (already resolved on disk), loading it on
 * first use: colour textures (srgb = 1) have RGB decoded from sRGB to linear, masks (srgb = 0) are
 * kept as stored. Each file is read and hashed into *hash once per decoding. -1 on error. */
int gib_tex_cache_get(gib_tex_cache *c, const char *resolved_path, int srgb, uint64_t *hash,
                      gib_error *err);
/* Loads several textures at once, using threads: paths[i] with srgb[i] -> out_index[i]. */
int gib_tex_cache_get_many(gib_tex_cache *c, const char *const *paths, const int *srgb, int n,
                           int *out_index, uint64_t *hash, gib_error *err);
/* Frees the cache's arrays but not the texture pixels, which move into the scene. */
void gib_tex_cache_release(gib_tex_cache *c);
/* sRGB transfer function decode (IEC 61966-2-1), exact piecewise form. */
float gib_srgb_to_linear(float c);

/* ---------------------------------------------------------------- paths */

/* Resolves `path` on disk, matching each component case-insensitively when the exact name is
 * absent, and reading '\\' as '/' (archives made on Windows). 0 with the path in out, or -1. */
int gib_path_resolve_ci(const char *path, char *out, size_t out_len);
int gib_path_is_dir(const char *path);
int gib_path_is_file(const char *path);
/* The folder part of path ("." when there is none), without the trailing '/'. */
void gib_path_dirname(const char *path, char *out, size_t out_len);
/* dir + '/' + rel (rel returned alone when absolute). -1 if it does not fit. */
int gib_path_join(const char *dir, const char *rel, char *out, size_t out_len);

/* ---------------------------------------------------------------- the parsed .scene file */

enum {
    GIB_MS_ALBEDO = 1u << 0,
    GIB_MS_SPECULAR = 1u << 1,
    GIB_MS_PHONG_N = 1u << 2,
    GIB_MS_MIRROR = 1u << 3,
    GIB_MS_TWO_SIDED = 1u << 4,
};

typedef struct gib_mesh_spec {
    char name[64];
    int line;                      /* of the [mesh.NAME] header */
    char file[GIB_PATH_MAX];       /* relative to the data root; "" for procedural */
    int file_line;
    char procedural[64];
    int procedural_line;
    float scale[3], rotate_deg[3], translate[3];
    char material[128];            /* "" when the mesh keeps its own materials */
    int material_line;
    gib_proc_params params;        /* generator keys (size, radius, tubes, ...) with lines */
    float smooth_angle_deg;
    /* Motion (FORMAT.md, "Motion"): keyframes of a rigid mesh, waves of a `water` mesh. */
    int key_count, keys_line;      /* keys = t0 t1 ...: times in seconds, increasing */
    float key_time[GIB_MOTION_MAX_KEYS];
    int key_rotate_line, key_translate_line; /* 0: not given (all zero) */
    float key_rotate[GIB_MOTION_MAX_KEYS][3], key_translate[GIB_MOTION_MAX_KEYS][3];
    int key_rotate_n, key_translate_n;        /* numbers given, for the count check */
    int pivot_line, loop, loop_line;
    float pivot[3];
    int wave_count, waves_line;    /* waves = a wavelength direction speed, ... */
    float waves[GIB_MOTION_MAX_WAVES][4];
    int gltf_materials;            /* the [scene] gltf file's mesh with `materials = gltf` */
} gib_mesh_spec;

typedef struct gib_material_spec {
    char name[128];
    int line;
    unsigned set;                  /* GIB_MS_* bits: which keys the section gave */
    int key_line[5];               /* line of each key, by bit position */
    float albedo[3], specular[3], phong_n;
    int mirror, two_sided;
} gib_material_spec;

typedef struct gib_light_spec {
    gib_light l;
    int line;
    int type_set, position_set, direction_set, target_set, intensity_set;
    float target[3];
    int direction_line, target_line;
} gib_light_spec;

typedef struct gib_camera_spec {
    gib_camera c;
    int line;
    int eye_set, target_set;
} gib_camera_spec;

typedef struct gib_scene_spec {
    char path[GIB_PATH_MAX];       /* the .scene file as opened */
    char name[64];                 /* file name without .scene */
    char description[512];
    float exposure;
    char data[256];                /* shared data folder the scene needs, "" for none */
    int data_line;
    int closed;                    /* [scene] closed = 1: geometry encloses camera and lights */
    float sky[3];                  /* [scene] sky = r g b: uniform environment radiance */
    float shift[3];                /* [scene] shift = x y z: every position moved after the build */
    int scene_line;
    /* [scene] gltf = FILE and what is taken from it (FORMAT.md, "glTF scenes") */
    char gltf[GIB_PATH_MAX];
    int gltf_line;
    int gltf_camera, camera_line;  /* camera = gltf | gltf:NAME */
    char gltf_camera_name[64];     /* "" for every camera */
    int gltf_lights, lights_line;  /* lights = gltf */
    int gltf_materials, materials_line; /* materials = gltf */
    gib_mesh_spec *meshes;
    int mesh_count;
    gib_material_spec *materials;
    int material_count;
    gib_light_spec *lights;
    int light_count;
    gib_camera_spec *cameras;
    int camera_count;
    int line_count;
} gib_scene_spec;

/* Parses and validates a .scene file (syntax, keys, numbers, required keys); loads nothing else.
 * Errors are "path:line: ...". */
int gib_scene_parse(const char *path, gib_scene_spec *spec, gib_error *err);
void gib_scene_spec_free(gib_scene_spec *spec);

/* Whole-file checks after parsing: required keys, directions normalised, cameras valid. */
int gib_scene_validate(gib_scene_spec *spec, gib_error *err);
/* Formats "path:line: message" into err; returns -1. */
int gib_scene_fail_at(const gib_scene_spec *spec, int line, gib_error *err, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));

/* Checks that the shared data a parsed scene needs is present. Returns 0, or
 * GIB_SCENE_UNAVAILABLE with a message saying where to get it. */
int gib_scene_check_data(const gib_scene_spec *spec, gib_error *err);

/* motion.c: the scene's motions from the spec, after the vertex arrays are final (mesh_vbegin[i]:
 * mesh i's first vertex, [mesh_count] = the end); poses the scene at t = 0 and sets bounds that
 * cover every instant. */
int gib_scene_build_motion(const gib_scene_spec *s, const uint32_t *mesh_vbegin, gib_scene *sc,
                           gib_error *err);
/* Builds the flattened scene from a parsed spec (loads meshes and textures). */
int gib_scene_build(const gib_scene_spec *spec, gib_scene *scene, gib_error *err);

#endif
