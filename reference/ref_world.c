/* gibench — the reference renderer's Embree scene: one triangle geometry over the flattened
 * gib_scene (ARCHITECTURE.md, "One scene model for both sides": the path tracer sees exactly the
 * triangles, normals, uvs and cut-out masks the GL techniques rasterise), plus ray casting,
 * surface points, robust ray offsets and ray differentials.
 *
 * Ray API: single rays (rtcIntersect1 / rtcOccluded1): streams and packets were measured no faster
 * on the path tracer's own rays (reference/PERFORMANCE.md, "The ray API"), and one ray at a time
 * keeps every sample's work in a fixed order. */
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <stdint.h>
#include <string.h>
#include <unistd.h>
#include <sys/mman.h>
#include <time.h>
#if defined(__x86_64__) || defined(__i386__)
#include <x86intrin.h>
#endif

#include "ref_internal.h"

/* ---- the scene ---- */

/* Large, randomly accessed arrays (triangle records, textures) on transparent huge pages where the
 * kernel offers them: on bare metal a random access then rarely misses the TLB as well as the
 * cache (in the development VM the host maps 4 KiB pages, so the TLB still walks them). Mapped
 * fresh (malloc would hand back heap pages the loader already touched, which madvise cannot turn
 * into huge pages) and aligned to 2 MiB by trimming an over-sized mapping. */
#define REF_HUGE ((size_t)2 << 20)
static size_t ref_huge_size(size_t bytes)
{
    return bytes ? (bytes + REF_HUGE - 1) / REF_HUGE * REF_HUGE : REF_HUGE;
}

void *ref_alloc_huge(size_t bytes)
{
    size_t n = ref_huge_size(bytes);
    char *p = mmap(NULL, n + REF_HUGE, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (p == MAP_FAILED)
        return NULL;
    uintptr_t a = ((uintptr_t)p + REF_HUGE - 1) & ~(uintptr_t)(REF_HUGE - 1);
    char *q = (char *)a;
    if (q > p)
        munmap(p, (size_t)(q - p));
    if (q + n < p + n + REF_HUGE)
        munmap(q + n, (size_t)(p + n + REF_HUGE - (q + n)));
#ifdef MADV_HUGEPAGE
    madvise(q, n, MADV_HUGEPAGE);
#endif
    return q;
}

void ref_free_huge(void *p, size_t bytes)
{
    if (p)
        munmap(p, ref_huge_size(bytes));
}

static int ref_normalize(float v[3])
{
    float l2 = ref_dot(v, v);
    if (!(l2 > 0.0f) || !isfinite(l2))
        return 0;
    float inv = 1.0f / sqrtf(l2);
    v[0] *= inv;
    v[1] *= inv;
    v[2] *= inv;
    return 1;
}

static void ref_interp_uv(const ref_world *w, uint32_t prim, float b1, float b2, float uv[2])
{
    const ref_tri *t = &w->tris[prim];
    float b0 = 1.0f - b1 - b2;
    for (int k = 0; k < 2; k++)
        uv[k] = b0 * t->uv[0][k] + b1 * t->uv[1][k] + b2 * t->uv[2][k];
}

/* Cut-out masks: Embree calls this for every candidate hit on the masked geometry, for closest-hit
 * and shadow rays alike, so a hole never hides what lies behind it nor casts a shadow. RTCHitN is
 * opaque in C; its SOA layout (rtcore_ray.h: Ng_x, Ng_y, Ng_z, u, v, primID, each N wide) is read
 * directly. */
static void ref_alpha_filter(const struct RTCFilterFunctionNArguments *args)
{
    const ref_world *w = args->geometryUserPtr;
    const gib_scene *gs = w->gs;
    const unsigned n = args->N;
    const float *hf = (const float *)(const void *)args->hit;
    const unsigned *hu = (const unsigned *)(const void *)args->hit;
    for (unsigned i = 0; i < n; i++) {
        if (args->valid[i] != -1)
            continue;
        unsigned prim = w->geo_base[REF_GEOM_MASKED] + hu[5 * n + i];
        const gib_material *m = &gs->materials[w->tris[prim].mat];
        if (m->alpha_tex < 0)
            continue;
        float uv[2];
        ref_interp_uv(w, prim, hf[3 * n + i], hf[4 * n + i], uv);
        if (ref_mask_sample(&w->masks[m->alpha_tex], uv[0], uv[1]) < 0.5f)
            args->valid[i] = 0;
    }
}

static void ref_embree_error(void *user, enum RTCError code, const char *str)
{
    ref_world *w = user;
    snprintf(w->embree_msg, sizeof w->embree_msg, "Embree error %d: %s", (int)code,
             str ? str : "(no message)");
}

/* Ray offset, in the renderer's frame (gib_scene_frame: a scene far from the origin is moved next
 * to it first). 1e-4 of the bounding-box diagonal of the vertices: large enough to clear the float
 * error of a hit point on any triangle of the scene, small next to any feature a scene is built
 * to show. Floored at 2^-17 of the largest coordinate magnitude in that frame (64 float ulps of
 * it), because a hit point's rounding error grows with its distance from the frame's origin; in
 * the frame that magnitude is at most GIB_FRAME_FAR diagonals, so the floor (6.1e-5 diagonals at
 * most) never exceeds the 1e-4 and the offset does not grow with the distance to the world's
 * origin (ARCHITECTURE.md, "Hard cases": hard_far). */
float gib_reference_ray_eps(const gib_scene *gs)
{
    if (!gs || !gs->positions || gs->vertex_count == 0)
        return 0.0f;
    float org[3];
    gib_scene_frame_origin(gs, org);
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    double amax = 0.0;
    for (uint32_t i = 0; i < gs->vertex_count; i++) {
        for (int k = 0; k < 3; k++) {
            /* the frame's coordinate, rounded as gib_scene_frame_make rounds it */
            double c = (float)((double)gs->positions[3 * (size_t)i + k] - (double)org[k]);
            lo[k] = c < lo[k] ? c : lo[k];
            hi[k] = c > hi[k] ? c : hi[k];
            amax = fabs(c) > amax ? fabs(c) : amax;
        }
    }
    double dx = hi[0] - lo[0], dy = hi[1] - lo[1], dz = hi[2] - lo[2];
    double eps = 1e-4 * sqrt(dx * dx + dy * dy + dz * dz);
    double floor_eps = amax * 0x1p-17;
    return (float)(eps > floor_eps ? eps : floor_eps);
}

static int ref_validate(const gib_scene *gs, gib_error *err)
{
    const char *nm = gs->name[0] ? gs->name : "(unnamed)";
    if (gs->triangle_count == 0)
        return 0;
    if (!gs->positions || !gs->indices || !gs->tri_material)
        return gib_fail(err, "scene '%s': triangles without positions, indices or materials", nm);
    for (uint32_t i = 0; i < 3 * gs->vertex_count; i++)
        if (!isfinite(gs->positions[i]))
            return gib_fail(err, "scene '%s': vertex %u has a non-finite position", nm, i / 3);
    for (uint32_t t = 0; t < gs->triangle_count; t++) {
        for (int k = 0; k < 3; k++)
            if (gs->indices[3 * (size_t)t + k] >= gs->vertex_count)
                return gib_fail(err, "scene '%s': triangle %u indexes vertex %u of %u", nm, t,
                                gs->indices[3 * (size_t)t + k], gs->vertex_count);
        if (gs->tri_material[t] >= gs->material_count)
            return gib_fail(err, "scene '%s': triangle %u uses material %u of %u", nm, t,
                            gs->tri_material[t], gs->material_count);
    }
    for (uint32_t m = 0; m < gs->material_count; m++) {
        const gib_material *mt = &gs->materials[m];
        int tex[2] = {mt->albedo_tex, mt->alpha_tex};
        for (int k = 0; k < 2; k++) {
            if (tex[k] < 0)
                continue;
            if ((uint32_t)tex[k] >= gs->texture_count || !gs->textures[tex[k]].rgba)
                return gib_fail(err,
                                "scene '%s': material '%s' uses texture %d, which is not loaded",
                                nm, mt->name, tex[k]);
        }
    }
    return 0;
}

/* What shading needs of a triangle beyond Embree's hit (distance, barycentrics, geometric
 * normal), in one 64-byte record, one cache line: a hit costs one line instead of the ~11 that
 * the indices, three positions, normals and uvs and the material index cost when read from the
 * scene's arrays. */
static int ref_build_tris(ref_world *w, const gib_scene *gs, gib_error *err)
{
    if (gs->triangle_count == 0)
        return 0;
    w->tris = ref_alloc_huge((size_t)gs->triangle_count * sizeof *w->tris);
    w->rec_tri = gib_calloc(gs->triangle_count, sizeof *w->rec_tri, err);
    if (!w->tris || !w->rec_tri)
        return gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY,
                             "scene '%s': out of memory for %u triangle records", gs->name,
                             gs->triangle_count);
    /* records in Embree's order: the opaque geometry's triangles, then the masked one's */
    uint32_t count0 = 0;
    for (uint32_t t = 0; t < gs->triangle_count; t++)
        count0 += gs->materials[gs->tri_material[t]].alpha_tex < 0;
    w->geo_base[REF_GEOM_OPAQUE] = 0;
    w->geo_base[REF_GEOM_MASKED] = count0;
    uint32_t next[2] = {0, count0};
    for (uint32_t i = 0; i < gs->triangle_count; i++) {
        uint32_t r = next[gs->materials[gs->tri_material[i]].alpha_tex >= 0]++;
        ref_tri *t = &w->tris[r];
        w->rec_tri[r] = i;
        memset(t, 0, sizeof *t);
        const uint32_t *ix = gs->indices + 3 * (size_t)i;
        for (int j = 0; j < 3; j++) {
            if (gs->normals)
                memcpy(t->n[j], gs->normals + 3 * (size_t)ix[j], sizeof t->n[j]);
            if (gs->uvs)
                memcpy(t->uv[j], gs->uvs + 2 * (size_t)ix[j], sizeof t->uv[j]);
        }
        t->mat = gs->tri_material[i];
    }
    return 0;
}

/* The material has a specular lobe as ref_material reads it: a lobe with some reflectance. */
static int ref_is_specular(const gib_material *m)
{
    return m->spec_type != GIB_SPEC_NONE &&
           (m->specular[0] > 0.0f || m->specular[1] > 0.0f || m->specular[2] > 0.0f);
}

/* ... and that lobe is a mirror. */
static int ref_is_mirror(const gib_material *m)
{
    return ref_is_specular(m) && m->spec_type == GIB_SPEC_MIRROR;
}

/* Whether a material's rho_d can be zero anywhere, known without its texels: kd = albedo x the
 * level-0 texel's bilinear blend. The blend of texels whose channel is at least 1e-6 is at least
 * that (a convex combination), and such a value is stored as itself or as an sRGB code of 1 or
 * more (ref_texture.c stores 8-bit sRGB only where every value is within 1e-9 of a code's, and
 * code 1 is 3e-4), so albedo > 1e-6 in that channel makes kd > 0 at every point. */
typedef struct ref_min_job {
    const gib_scene *gs;
    float (*least)[3]; /* per texture: the least of each colour channel over its texels */
} ref_min_job;

static void ref_texture_least(void *ctx, int t)
{
    ref_min_job *j = ctx;
    const gib_texture *tx = &j->gs->textures[t];
    float lo[3] = {INFINITY, INFINITY, INFINITY};
    int nan = 0;
    const size_t n = tx->rgba ? (size_t)tx->width * (size_t)tx->height : 0;
    for (size_t i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) {
            float v = tx->rgba[4 * i + k];
            nan |= isnan(v);
            lo[k] = v < lo[k] ? v : lo[k];
        }
    for (int k = 0; k < 3; k++) /* no texels or a NaN: nothing is known */
        j->least[t][k] = n > 0 && !nan ? lo[k] : 0.0f;
}

static int ref_world_diffuse_known(ref_world *w, const gib_scene *gs, gib_error *err)
{
    w->diffuse_known = gib_calloc(gs->material_count ? gs->material_count : 1, 1, err);
    ref_min_job j = {gs, gs->texture_count ? gib_calloc(gs->texture_count, sizeof *j.least, err)
                                           : NULL};
    if (!w->diffuse_known || (gs->texture_count && !j.least)) {
        free(j.least);
        return -1;
    }
    ref_parallel((int)sysconf(_SC_NPROCESSORS_ONLN), (int)gs->texture_count, ref_texture_least,
                 &j, NULL);
    for (uint32_t m = 0; m < gs->material_count; m++) {
        const gib_material *mt = &gs->materials[m];
        int any = 0, sure = 0, finite = 1;
        for (int k = 0; k < 3; k++) {
            any |= mt->albedo[k] > 0.0f;
            finite &= isfinite(mt->albedo[k]);
            sure |= mt->albedo_tex >= 0 && (uint32_t)mt->albedo_tex < gs->texture_count &&
                    mt->albedo[k] > 1e-6f && j.least[mt->albedo_tex][k] >= 1e-6f;
        }
        w->diffuse_known[m] = (int8_t)(mt->albedo_tex >= 0 ? (sure ? 1 : -1) : finite ? any : -1);
    }
    free(j.least);
    return 0;
}

/* Triangle records, mip pyramids of the albedo textures, the specular flags and the bounding
 * sphere. */
static int ref_world_extras(ref_world *w, const gib_scene *gs, gib_error *err)
{
    if (ref_build_tris(w, gs, err) < 0)
        return -1;
    for (uint32_t m = 0; m < gs->material_count; m++) {
        const gib_material *mt = &gs->materials[m];
        w->has_specular |= ref_is_specular(mt);
        w->has_mirror |= ref_is_mirror(mt);
    }
    if (gs->texture_count > 0 && ref_world_textures(w, gs, err) < 0)
        return -1;
    if (ref_world_diffuse_known(w, gs, err) < 0)
        return -1;
    if (gs->light_count > 0 && !(w->spot_cos = gib_calloc(gs->light_count, sizeof(float), err)))
        return -1;
    for (uint32_t i = 0; i < gs->light_count; i++)
        w->spot_cos[i] = gib_spot_cos_outer(&gs->lights[i]);
    double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    for (uint32_t i = 0; i < gs->vertex_count; i++)
        for (int k = 0; k < 3; k++) {
            double c = gs->positions[3 * (size_t)i + k];
            lo[k] = (i == 0 || c < lo[k]) ? c : lo[k];
            hi[k] = (i == 0 || c > hi[k]) ? c : hi[k];
        }
    double r2 = 0.0;
    for (int k = 0; k < 3; k++) {
        w->bcentre[k] = (float)(0.5 * (lo[k] + hi[k]));
        r2 += 0.25 * (hi[k] - lo[k]) * (hi[k] - lo[k]);
    }
    w->bradius = (float)sqrt(r2) * 1.001f + w->eps;
    return ref_light_pick_build(w, err);
}

/* A scene of the world's device with the flags every one of its scenes is built with. ROBUST: no
 * traversal shortcuts that can let a ray slip through a shared edge, which would leak light or
 * visibility into a reference. HIGH quality: the BVH is built once and traced millions of times. */
static RTCScene ref_new_scene(const ref_world *w)
{
    RTCScene s = rtcNewScene(w->device);
    rtcSetSceneFlags(s, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(s, RTC_BUILD_QUALITY_HIGH);
    return s;
}

/* One triangle geometry of `count` triangles, the scene's triangle of record rec[k] as primitive k,
 * over a copy of every vertex; NULL with err when Embree cannot allocate it. */
static RTCGeometry ref_new_geometry(ref_world *w, const uint32_t *rec, uint32_t count,
                                    gib_error *err)
{
    const gib_scene *gs = w->gs;
    RTCGeometry geo = rtcNewGeometry(w->device, RTC_GEOMETRY_TYPE_TRIANGLE);
    /* Copied into Embree-owned buffers, which Embree pads for its 16-byte vector loads (a shared
     * buffer would have to be padded by the scene loader). */
    float *vb = rtcSetNewGeometryBuffer(geo, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                        3 * sizeof(float), gs->vertex_count);
    unsigned *ib = rtcSetNewGeometryBuffer(geo, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                           3 * sizeof(unsigned), count);
    if (!vb || !ib) {
        rtcReleaseGeometry(geo);
        gib_fail(err, "scene '%s': %s", gs->name,
                 w->embree_msg[0] ? w->embree_msg : "Embree could not allocate geometry buffers");
        return NULL;
    }
    memcpy(vb, gs->positions, 3 * sizeof(float) * gs->vertex_count);
    for (uint32_t k = 0; k < count; k++)
        memcpy(ib + 3 * (size_t)k, gs->indices + 3 * (size_t)w->rec_tri[rec[k]],
               3 * sizeof(unsigned));
    return geo;
}

/* One triangle geometry holding the scene's opaque (g = 0) or masked (g = 1) triangles, with
 * geomID g; its primitive k is triangle record geo_base[g] + k. */
static int ref_add_geometry(ref_world *w, int g, uint32_t count, gib_error *err)
{
    uint32_t *rec = gib_calloc(count, sizeof *rec, err);
    RTCGeometry geo = NULL;
    for (uint32_t k = 0; rec && k < count; k++)
        rec[k] = w->geo_base[g] + k;
    if (rec)
        geo = ref_new_geometry(w, rec, count, err);
    free(rec);
    if (!geo)
        return -1;
    rtcSetGeometryUserData(geo, w);
    if (g == REF_GEOM_MASKED) {
        rtcSetGeometryIntersectFilterFunction(geo, ref_alpha_filter);
        rtcSetGeometryOccludedFilterFunction(geo, ref_alpha_filter);
    }
    rtcCommitGeometry(geo);
    rtcAttachGeometryByID(w->scene, geo, (unsigned)g);
    rtcReleaseGeometry(geo);
    return 0;
}

/* The triangles of the materials `keep` picks in a scene of their own (*out), with the main scene's
 * flags, so that Embree's test of each triangle is the same in both: a ray whose closest hit in
 * the main scene is such a triangle meets that triangle here too, so a ray that meets none here
 * has none as its first hit. No such scene (*out NULL, every ray traced whole) when a picked
 * material has a cut-out mask (the mask's filter would be needed too), or when the picked
 * triangles are many and over a quarter of the scene's (culling little, building much). */
static int ref_build_subset(ref_world *w, int (*keep)(const gib_material *), RTCScene *out,
                            gib_error *err)
{
    const gib_scene *gs = w->gs;
    uint32_t count = 0;
    *out = NULL;
    for (uint32_t r = 0; r < gs->triangle_count; r++) {
        const gib_material *m = &gs->materials[w->tris[r].mat];
        if (keep(m) && m->alpha_tex >= 0)
            return 0;
        count += (uint32_t)keep(m);
    }
    if (count > 65536 && count > gs->triangle_count / 4)
        return 0;
    uint32_t *rec = count ? gib_calloc(count, sizeof *rec, err) : NULL;
    if (count && !rec)
        return -1;
    count = 0;
    for (uint32_t r = 0; r < gs->triangle_count; r++)
        if (keep(&gs->materials[w->tris[r].mat]))
            rec[count++] = r;
    RTCGeometry geo = count ? ref_new_geometry(w, rec, count, err) : NULL;
    free(rec);
    if (count && !geo)
        return -1;
    *out = ref_new_scene(w);
    if (geo) {
        rtcCommitGeometry(geo);
        rtcAttachGeometry(*out, geo);
        rtcReleaseGeometry(geo);
    }
    rtcCommitScene(*out);
    return 0;
}

int ref_world_build(ref_world *w, const gib_scene *scene, gib_error *err)
{
    memset(w, 0, sizeof *w);
    if (ref_validate(scene, err) < 0)
        return -1;
    /* Everything from here on works in the scene's frame (gib_scene_frame): w->gs is the scene
     * moved next to the origin when it lies far from it, else the scene's own coordinates. */
    if (!(w->frame = gib_calloc(1, sizeof *w->frame, err)) ||
        gib_scene_frame_make(scene, w->frame, err) < 0) {
        free(w->frame);
        w->frame = NULL;
        return -1;
    }
    const gib_scene *gs = w->gs = &w->frame->scene;
    w->eps = gib_reference_ray_eps(scene);
    if (ref_world_extras(w, gs, err) < 0) {
        ref_world_free(w);
        return -1;
    }
    if (gs->triangle_count == 0)
        return 0; /* an empty view: every ray misses (ARCHITECTURE.md, "Hard cases") */

    w->device = rtcNewDevice(NULL);
    if (!w->device) {
        gib_fail(err, "cannot create an Embree device (error %d)", (int)rtcGetDeviceError(NULL));
        ref_world_free(w);
        return -1;
    }
    rtcSetDeviceErrorFunction(w->device, ref_embree_error, w);

    w->scene = ref_new_scene(w);

    /* Two geometries: opaque triangles, and those whose material has a cut-out mask, so that only
     * the latter pay for the filter callback. Sponza's plants hold 3% of its triangles; a filter on
     * every triangle cost Embree two thirds of its speed (reference/PERFORMANCE.md). */
    uint32_t count[2] = {0, 0};
    for (uint32_t t = 0; t < gs->triangle_count; t++)
        count[gs->materials[gs->tri_material[t]].alpha_tex >= 0]++;
    for (int g = 0; g < 2; g++) {
        if (count[g] == 0)
            continue;
        if (ref_add_geometry(w, g, count[g], err) < 0) {
            ref_world_free(w);
            return -1;
        }
    }
    rtcCommitScene(w->scene);
    if ((w->has_mirror && ref_build_subset(w, ref_is_mirror, &w->mirrors, err) < 0) ||
        (w->has_specular && ref_build_subset(w, ref_is_specular, &w->speculars, err) < 0)) {
        ref_world_free(w);
        return -1;
    }
    if (rtcGetDeviceError(w->device) != RTC_ERROR_NONE) {
        gib_fail(err, "scene '%s': building the Embree BVH failed: %s", gs->name,
                 w->embree_msg[0] ? w->embree_msg : "(no message)");
        ref_world_free(w);
        return -1;
    }
    return 0;
}

void ref_world_free(ref_world *w)
{
    if (w->mips && w->gs)
        for (uint32_t i = 0; i < w->gs->texture_count; i++)
            ref_mip_free(&w->mips[i]);
    free(w->mips);
    w->mips = NULL;
    if (w->masks && w->gs)
        for (uint32_t i = 0; i < w->gs->texture_count; i++)
            ref_mask_free(&w->masks[i]);
    free(w->masks);
    w->masks = NULL;
    free(w->spot_cos);
    w->spot_cos = NULL;
    free(w->diffuse_known);
    w->diffuse_known = NULL;
    free(w->light_pick);
    w->light_pick = NULL;
    ref_free_huge(w->tris, w->gs ? (size_t)w->gs->triangle_count * sizeof *w->tris : 0);
    w->tris = NULL;
    free(w->rec_tri);
    w->rec_tri = NULL;
    if (w->frame) {
        gib_scene_frame_free(w->frame);
        free(w->frame);
        w->frame = NULL;
        w->gs = NULL;
    }
    if (w->mirrors)
        rtcReleaseScene(w->mirrors);
    if (w->speculars)
        rtcReleaseScene(w->speculars);
    w->mirrors = w->speculars = NULL;
    if (w->scene)
        rtcReleaseScene(w->scene);
    if (w->device)
        rtcReleaseDevice(w->device);
    w->scene = NULL;
    w->device = NULL;
}

/* ---- rays ---- */


/* The front of a surface is the side its vertex normals point to (the geometric normal is turned
 * to agree with them), so a mesh's winding order does not matter; the GL side must use the same
 * rule for one-sided materials. */
/* The hit point is o + t d (Embree's distance), the geometric normal Embree's Ng = e1 x e2. */
static void ref_fill_hit(const ref_world *w, const struct RTCRayHit *rh, uint32_t prim,
                         const float o[3], const float d[3], ref_hit *h)
{
    const ref_tri *t = &w->tris[prim];
    const float b1 = rh->hit.u, b2 = rh->hit.v, b0 = 1.0f - b1 - b2, tt = rh->ray.tfar;
    h->ng[0] = rh->hit.Ng_x;
    h->ng[1] = rh->hit.Ng_y;
    h->ng[2] = rh->hit.Ng_z;
    for (int k = 0; k < 3; k++) {
        h->p[k] = o[k] + tt * d[k];
        h->n[k] = b0 * t->n[0][k] + b1 * t->n[1][k] + b2 * t->n[2][k];
    }
    int ng_ok = ref_normalize(h->ng);
    int n_ok = w->gs->normals && ref_normalize(h->n);
    if (!ng_ok && !n_ok) { /* a degenerate sliver without normals: face the viewer */
        for (int k = 0; k < 3; k++)
            h->ng[k] = h->n[k] = -d[k];
    } else if (!ng_ok) {
        memcpy(h->ng, h->n, sizeof h->ng);
    } else if (!n_ok) {
        memcpy(h->n, h->ng, sizeof h->n);
    } else if (ref_dot(h->ng, h->n) < 0.0f) {
        for (int k = 0; k < 3; k++)
            h->ng[k] = -h->ng[k];
    }

    h->prim = prim;
    h->mat = &w->gs->materials[t->mat];
    for (int k = 0; k < 2; k++)
        h->uv[k] = b0 * t->uv[0][k] + b1 * t->uv[1][k] + b2 * t->uv[2][k];
    /* Facing is decided by the geometric normal (as gl_FrontFacing is), the viewer being at -d. */
    int from_back = ref_dot(h->ng, d) > 0.0f;
    h->back = 0;
    if (from_back && h->mat->two_sided) {
        for (int k = 0; k < 3; k++) {
            h->n[k] = -h->n[k];
            h->ng[k] = -h->ng[k];
        }
    } else if (from_back) {
        h->back = 1;
    }
}

static void ref_log_ray(const ref_world *w, const struct RTCRay *r, int occl)
{
    ref_raylog *log = w->log;
    if (log->n == log->cap) {
        size_t cap = log->cap ? 2 * log->cap : 1 << 16;
        struct RTCRay *nr = realloc(log->rays, cap * sizeof *nr);
        unsigned char *no = nr ? realloc(log->occl, cap) : NULL;
        if (!nr || !no) { /* the bench reports the rays it kept */
            if (nr)
                log->rays = nr;
            return;
        }
        log->rays = nr;
        log->occl = no;
        log->cap = cap;
    }
    log->rays[log->n] = *r;
    log->occl[log->n++] = (unsigned char)occl;
}

uint64_t ref_ticks(void)
{
#if defined(__x86_64__) || defined(__i386__)
    return __rdtsc(); /* the time-stamp counter: a read costs tens of cycles */
#else
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (uint64_t)ts.tv_sec * 1000000000u + (uint64_t)ts.tv_nsec;
#endif
}

static _Thread_local uint64_t ref_embree_ticks;
static _Thread_local long long ref_shadow_count;

long long ref_shadow_rays(void)
{
    return ref_shadow_count;
}

/* What a pair of clock reads around nothing counts, on average: subtracted once per timed call.
 * Calibrated once per process. */
static double ref_ticks_pair;
static pthread_once_t ref_ticks_once = PTHREAD_ONCE_INIT;

static void ref_ticks_calibrate(void)
{
    enum { N = 1 << 16 };
    uint64_t best = UINT64_MAX;
    for (int round = 0; round < 5; round++) { /* the least disturbed of five rounds */
        uint64_t sum = 0;
        for (int i = 0; i < N; i++) {
            uint64_t t0 = ref_ticks();
            sum += ref_ticks() - t0;
        }
        best = sum < best ? sum : best;
    }
    ref_ticks_pair = (double)best / N;
}

double ref_ticks_overhead(void)
{
    pthread_once(&ref_ticks_once, ref_ticks_calibrate);
    return ref_ticks_pair;
}

uint64_t ref_embree_ticks_take(void)
{
    uint64_t t = ref_embree_ticks;
    ref_embree_ticks = 0;
    return t;
}

void ref_ray_init(struct RTCRay *r, const float o[3], const float d[3], float tfar)
{
    r->org_x = o[0];
    r->org_y = o[1];
    r->org_z = o[2];
    r->tnear = 0.0f;
    r->dir_x = d[0];
    r->dir_y = d[1];
    r->dir_z = d[2];
    r->time = 0.0f;
    r->tfar = tfar;
    r->mask = 0xffffffffu;
    r->id = 0;
    r->flags = 0;
}

/* Closest hit within tfar: fills rh, returns 1 on a hit. */
static int ref_intersect(const ref_world *w, const float o[3], const float d[3], float tfar,
                         struct RTCRayHit *rh)
{
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    ref_ray_init(&rh->ray, o, d, tfar);
    rh->hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh->hit.primID = RTC_INVALID_GEOMETRY_ID;
    rh->hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    if (w->log)
        ref_log_ray(w, &rh->ray, 0);
    uint64_t t0 = w->time_embree ? ref_ticks() : 0;
    rtcIntersect1(w->scene, &ctx, rh);
    if (w->time_embree)
        ref_embree_ticks += ref_ticks() - t0;
    return rh->hit.geomID != RTC_INVALID_GEOMETRY_ID;
}

/* 0 when the ray meets no triangle of `subset` (built for materials the world has: `any`). */
static int ref_may_hit(const ref_world *w, int any, RTCScene subset, const float o[3],
                       const float d[3])
{
    if (!any || !w->scene)
        return 0;
    if (!subset)
        return 1;
    struct RTCIntersectContext ctx;
    struct RTCRayHit rh;
    rtcInitIntersectContext(&ctx);
    ref_ray_init(&rh.ray, o, d, INFINITY);
    rh.hit.geomID = rh.hit.primID = rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    uint64_t t0 = w->time_embree ? ref_ticks() : 0;
    rtcIntersect1(subset, &ctx, &rh);
    if (w->time_embree)
        ref_embree_ticks += ref_ticks() - t0;
    return rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
}

int ref_may_hit_mirror(const ref_world *w, const float o[3], const float d[3])
{
    return ref_may_hit(w, w->has_mirror, w->mirrors, o, d);
}

int ref_may_hit_specular(const ref_world *w, const float o[3], const float d[3])
{
    return ref_may_hit(w, w->has_specular, w->speculars, o, d);
}

int ref_trace_start(const ref_world *w, const float o[3], const float d[3], ref_pending *pq)
{
    if (!w->scene || !ref_intersect(w, o, d, INFINITY, &pq->rh))
        return 0;
    pq->prim = w->geo_base[pq->rh.hit.geomID] + pq->rh.hit.primID;
    memcpy(pq->o, o, sizeof pq->o);
    memcpy(pq->d, d, sizeof pq->d);
    __builtin_prefetch(&w->tris[pq->prim]);
    return 1;
}

void ref_trace_finish(const ref_world *w, const ref_pending *pq, ref_hit *hit)
{
    ref_fill_hit(w, &pq->rh, pq->prim, pq->o, pq->d, hit);
    hit->t = pq->rh.ray.tfar;
    hit->has_duv = 0;
    hit->has_kd = 0;
    hit->has_nee = 0;
    int tex = hit->mat->albedo_tex;
    if (tex >= 0 && w->mips && !hit->back)
        ref_mip_prefetch(&w->mips[tex], hit->uv[0], hit->uv[1]);
}

int ref_trace(const ref_world *w, const float o[3], const float d[3], ref_hit *hit)
{
    ref_pending pq;
    if (!ref_trace_start(w, o, d, &pq))
        return 0;
    ref_trace_finish(w, &pq, hit);
    return 1;
}

float ref_hit_distance(const ref_world *w, const float o[3], const float d[3], float tfar)
{
    if (!w->scene || !(tfar > 0.0f))
        return INFINITY;
    struct RTCRayHit rh;
    return ref_intersect(w, o, d, tfar, &rh) ? rh.ray.tfar : INFINITY;
}

int ref_occluded(const ref_world *w, const float o[3], const float d[3], float tfar)
{
    if (!w->scene || !(tfar > 0.0f))
        return 0;
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    struct RTCRay r;
    ref_ray_init(&r, o, d, tfar);
    ref_shadow_count++;
    if (w->log)
        ref_log_ray(w, &r, 1);
    uint64_t t0 = w->time_embree ? ref_ticks() : 0;
    rtcOccluded1(w->scene, &ctx, &r);
    if (w->time_embree)
        ref_embree_ticks += ref_ticks() - t0;
    return r.tfar == -INFINITY; /* Embree's mark of an occluded ray */
}
