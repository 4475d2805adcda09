/* gibench — from a parsed .scene file to the flattened gib_scene both renderers read: meshes
 * loaded and transformed to world space, materials merged with the file's overrides, unused
 * materials dropped, textures loaded, triangles sorted into per-material draw ranges, normals
 * repaired, bounds, features and the content hash. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness/base/hash.h"
#include "scene_internal.h"

/* ------------------------------------------------------------------ transforms */

typedef struct xform {
    float m[3][3];  /* R * S, applied to positions */
    float nm[3][3]; /* R * S^-1: the inverse transpose of m, applied to normals */
    float t[3];
    int flips; /* det < 0: mirrored, so the winding must be reversed */
} xform;

static void mat_mul(const float a[3][3], const float b[3][3], float out[3][3])
{
    float r[3][3];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            r[i][j] = a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j];
    memcpy(out, r, sizeof r);
}

/* Rotation about x, then y, then z (the order FORMAT.md states): R = Rz * Ry * Rx. */
void gib_euler_rotation(const float deg[3], float r[3][3])
{
    const double k = M_PI / 180.0;
    const float cx = (float)cos(deg[0] * k), sx = (float)sin(deg[0] * k);
    const float cy = (float)cos(deg[1] * k), sy = (float)sin(deg[1] * k);
    const float cz = (float)cos(deg[2] * k), sz = (float)sin(deg[2] * k);
    const float rx[3][3] = {{1, 0, 0}, {0, cx, -sx}, {0, sx, cx}};
    const float ry[3][3] = {{cy, 0, sy}, {0, 1, 0}, {-sy, 0, cy}};
    const float rz[3][3] = {{cz, -sz, 0}, {sz, cz, 0}, {0, 0, 1}};
    float t[3][3];
    mat_mul(ry, rx, t);
    mat_mul(rz, t, r);
}

static void make_xform(const gib_mesh_spec *m, xform *x)
{
    float r[3][3];
    gib_euler_rotation(m->rotate_deg, r);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            x->m[i][j] = r[i][j] * m->scale[j];
            x->nm[i][j] = r[i][j] / m->scale[j];
        }
    memcpy(x->t, m->translate, sizeof x->t);
    x->flips = (m->scale[0] < 0) ^ (m->scale[1] < 0) ^ (m->scale[2] < 0);
}

static void apply3(const float m[3][3], const float *v, float *out)
{
    const float x = v[0], y = v[1], z = v[2];
    out[0] = m[0][0] * x + m[0][1] * y + m[0][2] * z;
    out[1] = m[1][0] * x + m[1][1] * y + m[1][2] * z;
    out[2] = m[2][0] * x + m[2][1] * y + m[2][2] * z;
}

/* World point to the mesh's own coordinates: S^-1 R^T (p - t). */
static void to_local(const gib_mesh_spec *m, const float p[3], float out[3])
{
    float r[3][3], d[3] = {p[0] - m->translate[0], p[1] - m->translate[1], p[2] - m->translate[2]};
    gib_euler_rotation(m->rotate_deg, r);
    for (int j = 0; j < 3; j++)
        out[j] = (r[0][j] * d[0] + r[1][j] * d[1] + r[2][j] * d[2]) / m->scale[j];
}

/* Moves a mesh's geometry into the scene's, transformed to world space. */
static int append_mesh(gib_geom *dst, gib_geom *src, const xform *x, int mesh_index, gib_error *err)
{
    if (gib_geom_reserve(dst, src->vcount, src->tcount, err))
        return -1;
    const uint32_t vbase = dst->vcount, mbase = dst->mcount;
    for (uint32_t i = 0; i < src->mcount; i++) {
        src->mats[i].mesh_index = mesh_index;
        if (gib_geom_material(dst, &src->mats[i], err) < 0)
            return -1;
    }
    for (uint32_t v = 0; v < src->vcount; v++) {
        float p[3], n[3];
        apply3(x->m, src->pos + 3 * (size_t)v, p);
        p[0] += x->t[0];
        p[1] += x->t[1];
        p[2] += x->t[2];
        apply3(x->nm, src->nrm + 3 * (size_t)v, n);
        gib_geom_vertex(dst, p, n, src->uv + 2 * (size_t)v);
    }
    for (uint32_t t = 0; t < src->tcount; t++) {
        const uint32_t *i = src->idx + 3 * (size_t)t;
        if (x->flips)
            gib_geom_triangle(dst, vbase + i[0], vbase + i[2], vbase + i[1], mbase + src->mat[t]);
        else
            gib_geom_triangle(dst, vbase + i[0], vbase + i[1], vbase + i[2], mbase + src->mat[t]);
    }
    return 0;
}

/* ------------------------------------------------------------------ materials */

static const char *const channel_names[3] = {"red", "green", "blue"};

/* Applies a [material.NAME] section to a material and checks the result. */
static int apply_material(const gib_scene_spec *s, const gib_material_spec *ms, gib_mat_desc *d,
                          gib_error *err)
{
    gib_material *m = &d->m;
    const int was_phong = m->spec_type == GIB_SPEC_PHONG;
    if (ms->set & GIB_MS_ALBEDO)
        memcpy(m->albedo, ms->albedo, sizeof m->albedo);
    if (ms->set & GIB_MS_SPECULAR)
        memcpy(m->specular, ms->specular, sizeof m->specular);
    if (ms->set & GIB_MS_PHONG_N)
        m->phong_n = ms->phong_n;
    if (ms->set & GIB_MS_TWO_SIDED)
        m->two_sided = ms->two_sided;
    const int has_spec = m->specular[0] > 0 || m->specular[1] > 0 || m->specular[2] > 0;
    if ((ms->set & GIB_MS_MIRROR) && ms->mirror)
        m->spec_type = GIB_SPEC_MIRROR;
    else if (has_spec && (m->spec_type != GIB_SPEC_MIRROR || (ms->set & GIB_MS_MIRROR)))
        m->spec_type = GIB_SPEC_PHONG;
    else if (!has_spec)
        m->spec_type = GIB_SPEC_NONE;

    int line = ms->line;
    for (int k = 0; k < 2; k++)
        if ((ms->set & (1u << k)) && ms->key_line[k] > line)
            line = ms->key_line[k];
    if (m->spec_type == GIB_SPEC_PHONG && !was_phong && !(ms->set & GIB_MS_PHONG_N))
        return gib_scene_fail_at(s, line, err,
                                 "material '%s' has a specular lobe but no 'phong_n' "
                                 "(give the Phong exponent, or 'mirror = 1' for a perfect mirror)",
                                 ms->name);
    for (int c = 0; c < 3; c++)
        if (m->albedo[c] + m->specular[c] > 1.0f + 1e-6f)
            return gib_scene_fail_at(
                s, line, err,
                "material '%s': albedo + specular = %g + %g > 1 in the "
                "%s channel; rho_d + rho_s <= 1 is required for energy conservation",
                ms->name, (double)m->albedo[c], (double)m->specular[c], channel_names[c]);
    return 0;
}

/* Loads the textures the materials name (only materials that triangles use reach here). */
static int load_textures(const gib_scene_spec *s, gib_mat_desc *mats, uint32_t n,
                         gib_tex_cache *cache, uint64_t *hash, gib_error *err)
{
    char(*paths)[GIB_PATH_MAX] = gib_calloc((size_t)n * 2 + 1, GIB_PATH_MAX, err);
    const char **pp = gib_calloc((size_t)n * 2 + 1, sizeof *pp, err);
    int *srgb = gib_calloc((size_t)n * 2 + 1, sizeof *srgb, err);
    int *index = gib_calloc((size_t)n * 2 + 1, sizeof *index, err);
    int *owner = gib_calloc((size_t)n * 2 + 1, sizeof *owner, err);
    int rc = (paths && pp && srgb && index && owner) ? 0 : -1, count = 0;
    for (uint32_t i = 0; i < n && rc == 0; i++) {
        for (int kind = 0; kind < 2 && rc == 0; kind++) {
            const char *want = kind == 0 ? mats[i].albedo_path : mats[i].alpha_path;
            if (!want[0])
                continue;
            if (gib_gltf_image_ref(want)) /* embedded in a glTF: read from it (textures.c) */
                snprintf(paths[count], GIB_PATH_MAX, "%s", want);
            else if (gib_path_resolve_ci(want, paths[count], GIB_PATH_MAX) != 0 ||
                !gib_path_is_file(paths[count])) {
                const gib_mesh_spec *ms =
                    mats[i].mesh_index >= 0 ? &s->meshes[mats[i].mesh_index] : NULL;
                rc = gib_scene_fail_at(
                    s, ms ? ms->file_line : s->scene_line, err,
                    "mesh '%s': material "
                    "'%s': %s texture '%s' not found (names are matched ignoring case)",
                    ms ? ms->name : "?", mats[i].m.name, kind == 0 ? "albedo" : "alpha", want);
                break;
            }
            pp[count] = paths[count];
            srgb[count] = kind == 0; /* colour is sRGB-encoded; masks are coverage values */
            owner[count] = (int)(2 * i + (uint32_t)kind);
            count++;
        }
    }
    if (rc == 0 && count > 0)
        rc = gib_tex_cache_get_many(cache, pp, srgb, count, index, hash, err);
    for (int k = 0; k < count && rc == 0; k++) {
        gib_material *m = &mats[owner[k] / 2].m;
        if (owner[k] % 2 == 0)
            m->albedo_tex = index[k];
        else
            m->alpha_tex = index[k];
    }
    free(paths);
    free(pp);
    free(srgb);
    free(index);
    free(owner);
    return rc;
}

/* ------------------------------------------------------------------ final arrays */

/* Zero-length or non-finite normals (degenerate triangles, meshes without normals) get the
 * area-weighted normal of the triangles around the vertex, else +y: no NaN ever reaches a
 * renderer. All normals are made unit length. */
static void repair_normals(gib_geom *g)
{
    unsigned char *bad = calloc(g->vcount ? g->vcount : 1, 1);
    if (!bad)
        return;
    int any = 0;
    for (uint32_t v = 0; v < g->vcount; v++) {
        float *n = g->nrm + 3 * (size_t)v;
        float l = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        if (!isfinite(l) || l < 1e-20f) {
            bad[v] = 1;
            any = 1;
            n[0] = n[1] = n[2] = 0.0f;
        } else {
            n[0] /= l;
            n[1] /= l;
            n[2] /= l;
        }
    }
    if (any) {
        for (uint32_t t = 0; t < g->tcount; t++) {
            const uint32_t *i = g->idx + 3 * (size_t)t;
            if (!bad[i[0]] && !bad[i[1]] && !bad[i[2]])
                continue;
            const float *a = g->pos + 3 * (size_t)i[0], *b = g->pos + 3 * (size_t)i[1],
                        *c = g->pos + 3 * (size_t)i[2];
            const float e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
            const float e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
            const float fn[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                                 e1[0] * e2[1] - e1[1] * e2[0]};
            if (!isfinite(fn[0] + fn[1] + fn[2]))
                continue;
            for (int k = 0; k < 3; k++)
                if (bad[i[k]])
                    for (int j = 0; j < 3; j++)
                        g->nrm[3 * (size_t)i[k] + (size_t)j] += fn[j];
        }
        for (uint32_t v = 0; v < g->vcount; v++) {
            if (!bad[v])
                continue;
            float *n = g->nrm + 3 * (size_t)v;
            float l = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            if (isfinite(l) && l > 0.0f) {
                n[0] /= l;
                n[1] /= l;
                n[2] /= l;
            } else {
                n[0] = 0.0f;
                n[1] = 1.0f;
                n[2] = 0.0f;
            }
        }
    }
    free(bad);
}

/* Counting sort of the triangles by material: one draw range per used material. */
static int sort_ranges(gib_scene *sc, const gib_geom *g, uint32_t nmat, gib_error *err)
{
    uint32_t *count = gib_calloc((size_t)nmat + 1, sizeof *count, err);
    sc->indices = gib_calloc((size_t)g->tcount * 3, sizeof *sc->indices, err);
    sc->tri_material = gib_calloc(g->tcount, sizeof *sc->tri_material, err);
    sc->ranges = gib_calloc(nmat, sizeof *sc->ranges, err);
    if (!count || !sc->indices || !sc->tri_material || !sc->ranges) {
        free(count);
        return -1;
    }
    for (uint32_t t = 0; t < g->tcount; t++)
        count[g->mat[t] + 1]++;
    for (uint32_t m = 0; m < nmat; m++)
        count[m + 1] += count[m]; /* count[m] = first triangle of material m */
    sc->range_count = 0;
    for (uint32_t m = 0; m < nmat; m++) {
        uint32_t n = count[m + 1] - count[m];
        if (n == 0)
            continue;
        gib_draw_range *r = &sc->ranges[sc->range_count++];
        r->first_index = 3 * count[m];
        r->index_count = 3 * n;
        r->material = m;
    }
    for (uint32_t t = 0; t < g->tcount; t++) {
        uint32_t dst = count[g->mat[t]]++;
        memcpy(sc->indices + 3 * (size_t)dst, g->idx + 3 * (size_t)t, 3 * sizeof(uint32_t));
        sc->tri_material[dst] = g->mat[t];
    }
    sc->triangle_count = g->tcount;
    free(count);
    return 0;
}

static unsigned room_encloses(const gib_scene_spec *s)
{
    for (int i = 0; i < s->mesh_count; i++) {
        const gib_mesh_spec *m = &s->meshes[i];
        if (strcmp(m->procedural, "room") != 0)
            continue;
        const float w = (float)gib_proc_get(&m->params, GIB_PK_SIZE, 0, 4.0);
        const float h = (float)gib_proc_get(&m->params, GIB_PK_SIZE, 1, 3.0);
        const float d = (float)gib_proc_get(&m->params, GIB_PK_SIZE, 2, 4.0);
        int inside = 1;
        for (int k = 0; k < s->camera_count + s->light_count && inside; k++) {
            const float *p;
            if (k < s->camera_count) {
                p = s->cameras[k].c.eye;
            } else {
                const gib_light *l = &s->lights[k - s->camera_count].l;
                if (l->type == GIB_LIGHT_DIRECTIONAL) {
                    inside = 0; /* comes from outside: no closed room lets it in */
                    break;
                }
                p = l->position;
            }
            float q[3];
            to_local(m, p, q);
            inside = fabsf(q[0]) < 0.5f * w && q[1] > 0.0f && q[1] < h && fabsf(q[2]) < 0.5f * d;
        }
        if (inside)
            return GIB_FEAT_CLOSED;
    }
    return 0;
}

/* ------------------------------------------------------------------ the build */

/* [scene] shift: every vertex, light and camera position moved by t once the scene is built in
 * floats (each sum rounded to float), so a scene built far from the origin can be brought back
 * with the rounding it had there (cornell_far_rounded: hard_far's box at the origin). */
static void scene_shift(gib_scene *sc, const float t[3])
{
    if (t[0] == 0.0f && t[1] == 0.0f && t[2] == 0.0f)
        return;
    for (size_t i = 0; i < 3 * (size_t)sc->vertex_count; i++)
        sc->positions[i] = (float)((double)sc->positions[i] + t[i % 3]);
    for (uint32_t i = 0; i < sc->light_count; i++)
        for (int k = 0; k < 3; k++)
            if (sc->lights[i].type != GIB_LIGHT_DIRECTIONAL)
                sc->lights[i].position[k] = (float)((double)sc->lights[i].position[k] + t[k]);
    for (uint32_t i = 0; i < sc->camera_count; i++)
        for (int k = 0; k < 3; k++) {
            sc->cameras[i].eye[k] = (float)((double)sc->cameras[i].eye[k] + t[k]);
            sc->cameras[i].target[k] = (float)((double)sc->cameras[i].target[k] + t[k]);
        }
}

/* What the build steps below share. */
typedef struct build_state {
    const gib_scene_spec *s;
    gib_scene *sc;
    gib_geom g;                 /* every mesh, in world space */
    gib_tex_cache cache;
    uint32_t *tri_mesh_begin;   /* mesh i's first triangle; [mesh_count] = the end */
    uint32_t *vert_mesh_begin;  /* mesh i's first vertex; [mesh_count] = the end */
    uint32_t nmat;              /* materials kept (drop_unused_materials) */
    uint64_t hash;
    gib_error *err;
    gib_gltf_info gltf;         /* what [scene] gltf's file gives (FORMAT.md, "glTF scenes") */
} build_state;

/* The [scene] gltf file's mesh (the last, gib_scene_validate appends it): reads what the scene
 * takes from the file, and hands its materials to the imported geometry (gib_gltf_match finds
 * which of the file's materials each of assimp's is; primitives without a material get gibench's
 * `default`, Lambertian 0.8). */
static int gltf_import(build_state *b, const gib_mesh_spec *m, const char *path, gib_geom *local)
{
    const gib_scene_spec *s = b->s;
    const unsigned want = (s->gltf_camera ? GIB_GLTF_CAMERAS : 0u) |
                          (s->gltf_lights ? GIB_GLTF_LIGHTS : 0u) |
                          (s->gltf_materials ? GIB_GLTF_MATERIALS : 0u);
    if (gib_gltf_read(path, want, &b->gltf, b->err))
        return gib_error_prefix(b->err, "%s:%d: [scene] gltf", s->path, s->gltf_line);
    b->hash = gib_hash_str(b->hash, "gltf mapping 2");
    b->hash = gib_hash_u64(b->hash, want);
    if (gib_mesh_import_ex(path, m->smooth_angle_deg, want & GIB_GLTF_MATERIALS
                                                          ? GIB_IMPORT_NO_TEXTURES : 0u,
                           local, &b->hash, b->err))
        return gib_error_prefix(b->err, "%s:%d: [scene] gltf", s->path, s->gltf_line);
    if (!(want & GIB_GLTF_MATERIALS))
        return 0;
    for (uint32_t k = 0; k < local->mcount; k++) {
        const int gi = gib_gltf_match(&b->gltf, &local->mats[k], path, b->err);
        if (gi == -2)
            return gib_error_prefix(b->err, "%s:%d: [scene] gltf", s->path, s->gltf_line);
        local->mats[k] = gi >= 0 ? b->gltf.mats[gi]
                                 : gib_mat_desc_diffuse("default", 0.8f, 0.8f, 0.8f);
    }
    return 0;
}

/* Mesh i (generated, or imported from the data root) appended in world space. */
static int load_mesh(build_state *b, int i, const char *root)
{
    const gib_scene_spec *s = b->s;
    gib_error *err = b->err;
    const gib_mesh_spec *m = &s->meshes[i];
    int rc = 0;
    gib_geom local;
    memset(&local, 0, sizeof local);
    b->tri_mesh_begin[i] = b->g.tcount;
    b->vert_mesh_begin[i] = b->g.vcount;
    if (m->procedural[0]) {
        if (gib_procedural_build(m->procedural, &m->params, &local, &b->hash, err))
            rc = gib_error_prefix(err, "%s:%d: mesh '%s'", s->path, m->procedural_line, m->name);
    } else {
        char joined[GIB_PATH_MAX], path[GIB_PATH_MAX];
        if (!root)
            rc = gib_scene_fail_at(s, m->file_line, err,
                                   "mesh '%s': file '%s' needs the data root; "
                                   "set GIBENCH_SCENES",
                                   m->name, m->file);
        else if (gib_path_join(root, m->file, joined, sizeof joined) ||
                 gib_path_resolve_ci(joined, path, sizeof path) || !gib_path_is_file(path))
            rc = gib_scene_fail_at(s, m->file_line, err,
                                   "mesh '%s': file '%s' not found under the "
                                   "data root '%s' ($GIBENCH_SCENES, default ../shared/scenes)",
                                   m->name, m->file, root);
        else if (s->gltf[0] && i == s->mesh_count - 1)
            rc = gltf_import(b, m, path, &local);
        else if (gib_mesh_import(path, m->smooth_angle_deg, &local, &b->hash, err))
            rc = gib_error_prefix(err, "%s:%d: mesh '%s'", s->path, m->file_line, m->name);
    }
    if (rc == 0) {
        xform x;
        make_xform(m, &x);
        rc = append_mesh(&b->g, &local, &x, i, err);
    }
    gib_geom_free(&local);
    return rc;
}

static int load_meshes(build_state *b)
{
    const char *root = gib_scene_data_root();
    for (int i = 0; i < b->s->mesh_count; i++)
        if (load_mesh(b, i, root))
            return -1;
    b->tri_mesh_begin[b->s->mesh_count] = b->g.tcount;
    b->vert_mesh_begin[b->s->mesh_count] = b->g.vcount;
    return 0;
}

/* [material.NAME] sections override every material of that name, or create one. */
static int apply_material_sections(build_state *b)
{
    const gib_scene_spec *s = b->s;
    gib_geom *g = &b->g;
    int rc = 0;
    for (int i = 0; i < s->material_count && rc == 0; i++) {
        const gib_material_spec *ms = &s->materials[i];
        int found = 0;
        for (uint32_t k = 0; k < g->mcount && rc == 0; k++)
            if (strcmp(g->mats[k].m.name, ms->name) == 0) {
                found = 1;
                rc = apply_material(s, ms, &g->mats[k], b->err);
            }
        if (!found && rc == 0) {
            gib_mat_desc d = gib_mat_desc_diffuse(ms->name, 0.8f, 0.8f, 0.8f);
            rc = apply_material(s, ms, &d, b->err);
            if (rc == 0 && gib_geom_material(g, &d, b->err) < 0)
                rc = -1;
        }
    }
    return rc;
}

/* `material = NAME` on a mesh: all its triangles take the first material of that name. */
static int assign_mesh_materials(build_state *b)
{
    const gib_scene_spec *s = b->s;
    gib_geom *g = &b->g;
    for (int i = 0; i < s->mesh_count; i++) {
        const gib_mesh_spec *m = &s->meshes[i];
        if (!m->material[0])
            continue;
        uint32_t k = 0;
        while (k < g->mcount && strcmp(g->mats[k].m.name, m->material) != 0)
            k++;
        if (k == g->mcount)
            return gib_scene_fail_at(s, m->material_line, b->err,
                                     "mesh '%s': material '%s' is not defined; add "
                                     "a [material.%s] section or use a name the mesh file defines",
                                     m->name, m->material, m->material);
        for (uint32_t t = b->tri_mesh_begin[i]; t < b->tri_mesh_begin[i + 1]; t++)
            g->mat[t] = k;
    }
    return 0;
}

/* Keep only materials some triangle uses, then load their textures: no texture is loaded for
 * nothing. */
static int drop_unused_materials(build_state *b)
{
    gib_geom *g = &b->g;
    int *remap = gib_calloc(g->mcount + 1, sizeof *remap, b->err);
    if (!remap)
        return -1;
    uint32_t nmat = 0;
    for (uint32_t k = 0; k < g->mcount; k++)
        remap[k] = -1;
    for (uint32_t t = 0; t < g->tcount; t++)
        remap[g->mat[t]] = 0;
    for (uint32_t k = 0; k < g->mcount; k++)
        if (remap[k] == 0) {
            remap[k] = (int)nmat;
            g->mats[nmat++] = g->mats[k]; /* nmat <= k: moves only backward */
        }
    for (uint32_t t = 0; t < g->tcount; t++)
        g->mat[t] = (uint32_t)remap[g->mat[t]];
    g->mcount = nmat;
    b->nmat = nmat;
    free(remap);
    return load_textures(b->s, g->mats, nmat, &b->cache, &b->hash, b->err);
}

static void scene_bounds(gib_scene *sc)
{
    for (int k = 0; k < 3; k++) {
        sc->bounds_min[k] = INFINITY;
        sc->bounds_max[k] = -INFINITY;
    }
    for (uint32_t v = 0; v < sc->vertex_count; v++)
        for (int k = 0; k < 3; k++) {
            float p = sc->positions[3 * (size_t)v + (size_t)k];
            sc->bounds_min[k] = fminf(sc->bounds_min[k], p);
            sc->bounds_max[k] = fmaxf(sc->bounds_max[k], p);
        }
}

/* enum gib_feature bits of the built scene. */
static unsigned scene_features(const gib_scene_spec *s, const gib_scene *sc)
{
    unsigned f = 0;
    for (uint32_t k = 0; k < sc->material_count; k++) {
        const gib_material *m = &sc->materials[k];
        if (m->albedo_tex >= 0)
            f |= GIB_FEAT_TEXTURES;
        if (m->alpha_tex >= 0)
            f |= GIB_FEAT_ALPHA_MASK;
        if (m->spec_type == GIB_SPEC_PHONG)
            f |= GIB_FEAT_SPECULAR;
        if (m->spec_type == GIB_SPEC_MIRROR)
            f |= GIB_FEAT_MIRROR;
    }
    for (uint32_t i = 0; i < sc->light_count; i++)
        f |= sc->lights[i].type == GIB_LIGHT_POINT  ? GIB_FEAT_POINT_LIGHT
             : sc->lights[i].type == GIB_LIGHT_SPOT ? GIB_FEAT_SPOT_LIGHT
                                                    : GIB_FEAT_DIR_LIGHT;
    if (s->closed)
        f |= GIB_FEAT_CLOSED;
    if (s->sky[0] > 0 || s->sky[1] > 0 || s->sky[2] > 0)
        f |= GIB_FEAT_SKY;
    return f | room_encloses(s);
}

/* camera = gltf (every camera of the file, in node order) or gltf:NAME (the one whose camera or
 * node has that name): they come first, so the first is the default view. */
static int gltf_cameras(build_state *b)
{
    const gib_scene_spec *s = b->s;
    gib_scene *sc = b->sc;
    const gib_gltf_info *g = &b->gltf;
    if (!s->gltf_camera)
        return 0;
    for (int i = 0; i < g->camera_count; i++)
        if (!s->gltf_camera_name[0] || strcmp(g->cameras[i].name, s->gltf_camera_name) == 0 ||
            strcmp(g->camera_alias[i], s->gltf_camera_name) == 0)
            sc->cameras[sc->camera_count++] = g->cameras[i];
    if (sc->camera_count > 0)
        return 0;
    char names[256] = "";
    for (int i = 0; i < g->camera_count; i++) {
        size_t n = strlen(names);
        snprintf(names + n, sizeof names - n, "%s'%s'", i ? ", " : "", g->cameras[i].name);
    }
    if (s->gltf_camera_name[0])
        return gib_scene_fail_at(s, s->camera_line, b->err,
                                 "[scene]: glTF '%s' has no camera named '%s' (its cameras: %s)",
                                 s->gltf, s->gltf_camera_name, names[0] ? names : "none");
    return gib_scene_fail_at(s, s->camera_line, b->err,
                             "[scene]: camera = gltf, but glTF '%s' has no camera in its scene",
                             s->gltf);
}

/* The scene's arrays from the geometry (moved, not copied), the cache's textures and the spec's
 * lights and cameras; then shift, bounds, features, hash and motion. */
static int fill_scene(build_state *b)
{
    const gib_scene_spec *s = b->s;
    gib_scene *sc = b->sc;
    gib_geom *g = &b->g;
    sc->materials = gib_calloc(b->nmat, sizeof *sc->materials, b->err);
    sc->lights = gib_calloc((size_t)s->light_count + (size_t)b->gltf.light_count + 1,
                            sizeof *sc->lights, b->err);
    sc->cameras = gib_calloc((size_t)s->camera_count + (size_t)b->gltf.camera_count + 1,
                             sizeof *sc->cameras, b->err);
    if (!sc->materials || !sc->lights || !sc->cameras)
        return -1;
    snprintf(sc->name, sizeof sc->name, "%s", s->name);
    snprintf(sc->file, sizeof sc->file, "%s", s->path);
    snprintf(sc->description, sizeof sc->description, "%s", s->description);
    sc->exposure = s->exposure;
    memcpy(sc->sky, s->sky, sizeof sc->sky);
    /* The vertex arrays move into the scene as they are (every vertex is referenced). */
    sc->vertex_count = g->vcount;
    sc->positions = g->pos;
    sc->normals = g->nrm;
    sc->uvs = g->uv;
    g->pos = g->nrm = g->uv = NULL;
    for (uint32_t k = 0; k < b->nmat; k++)
        sc->materials[k] = g->mats[k].m;
    sc->material_count = b->nmat;
    sc->textures = b->cache.tex;
    sc->texture_count = b->cache.count;
    b->cache.tex = NULL;
    b->cache.count = 0;
    for (int i = 0; i < s->light_count; i++)
        sc->lights[i] = s->lights[i].l;
    sc->light_count = (uint32_t)s->light_count;
    for (int i = 0; i < b->gltf.light_count; i++) /* lights = gltf: after the file's own */
        sc->lights[sc->light_count++] = b->gltf.lights[i];
    if (gltf_cameras(b))
        return -1;
    for (int i = 0; i < s->camera_count; i++)
        sc->cameras[sc->camera_count++] = s->cameras[i].c;
    snprintf(sc->ignored, sizeof sc->ignored, "%s", b->gltf.ignored);
    scene_shift(sc, s->shift);
    scene_bounds(sc);
    sc->features = scene_features(s, sc);
    sc->content_hash = b->hash;
    return gib_scene_build_motion(s, b->vert_mesh_begin, sc, b->err);
}

/* The steps in order; the first that fails ends the build. */
static int build_steps(build_state *b)
{
    const gib_scene_spec *s = b->s;
    if (gib_hash_file(&b->hash, s->path) != 0)
        return gib_fail(b->err, "%s: cannot read the scene file to hash it", s->path);
    if (load_meshes(b) || apply_material_sections(b) || assign_mesh_materials(b) ||
        drop_unused_materials(b))
        return -1;
    if (b->g.tcount == 0)
        return gib_scene_fail_at(s, s->scene_line, b->err, "the scene has no triangles");
    repair_normals(&b->g);
    if (sort_ranges(b->sc, &b->g, b->nmat, b->err))
        return -1;
    return fill_scene(b);
}

int gib_scene_build(const gib_scene_spec *s, gib_scene *sc, gib_error *err)
{
    memset(sc, 0, sizeof *sc);
    build_state b;
    memset(&b, 0, sizeof b);
    b.s = s;
    b.sc = sc;
    b.err = err;
    b.hash = gib_hash_str(GIB_HASH_INIT, GIB_SCENE_LOADER_VERSION);
    b.tri_mesh_begin = gib_calloc((size_t)s->mesh_count + 1, sizeof(uint32_t), err);
    b.vert_mesh_begin = gib_calloc((size_t)s->mesh_count + 1, sizeof(uint32_t), err);
    int rc = b.tri_mesh_begin && b.vert_mesh_begin ? build_steps(&b) : -1;
    for (uint32_t k = 0; k < b.cache.count; k++)
        free(b.cache.tex[k].rgba);
    free(b.cache.tex);
    gib_tex_cache_release(&b.cache);
    gib_geom_free(&b.g);
    gib_gltf_info_free(&b.gltf);
    free(b.tri_mesh_begin);
    free(b.vert_mesh_begin);
    if (rc != 0) {
        gib_scene_free(sc);
        return -1;
    }
    return 0;
}
