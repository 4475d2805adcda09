/* gibench — the reference renderer's Embree scene: one triangle geometry over the flattened
 * gib_scene (DESIGN.md, "One scene model for both sides": the path tracer sees exactly the
 * triangles, normals, uvs and cut-out masks the GL techniques rasterise), plus ray casting,
 * surface points and robust ray offsets. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "ref_internal.h"

/* ---- textures ---- */

static int ref_wrap(int i, int n)
{
    int r = i % n;
    return r < 0 ? r + n : r;
}

/* Texel centres sit at (i + 0.5) / size, as in GL, so a lookup at a texel centre returns that
 * texel exactly; repeat wrap in both directions; row 0 is the top of the image (scene.h). */
void ref_tex_sample(const gib_texture *t, float u, float v, float out[4])
{
    if (!t || !t->rgba || t->width <= 0 || t->height <= 0) {
        out[0] = out[1] = out[2] = out[3] = 1.0f;
        return;
    }
    if (!isfinite(u))
        u = 0.0f;
    if (!isfinite(v))
        v = 0.0f;
    float s = u - floorf(u);
    float tt = 1.0f - v;
    tt -= floorf(tt);
    float x = s * (float)t->width - 0.5f, y = tt * (float)t->height - 0.5f;
    float xf = floorf(x), yf = floorf(y);
    float ax = x - xf, ay = y - yf;
    int x0 = ref_wrap((int)xf, t->width), x1 = ref_wrap((int)xf + 1, t->width);
    int y0 = ref_wrap((int)yf, t->height), y1 = ref_wrap((int)yf + 1, t->height);
    const float *p00 = t->rgba + ((size_t)y0 * (size_t)t->width + (size_t)x0) * 4;
    const float *p10 = t->rgba + ((size_t)y0 * (size_t)t->width + (size_t)x1) * 4;
    const float *p01 = t->rgba + ((size_t)y1 * (size_t)t->width + (size_t)x0) * 4;
    const float *p11 = t->rgba + ((size_t)y1 * (size_t)t->width + (size_t)x1) * 4;
    for (int c = 0; c < 4; c++) {
        float top = p00[c] + (p10[c] - p00[c]) * ax;
        float bot = p01[c] + (p11[c] - p01[c]) * ax;
        out[c] = top + (bot - top) * ay;
    }
}

/* ---- the scene ---- */

static void ref_interp_uv(const gib_scene *gs, uint32_t prim, float b1, float b2, float uv[2])
{
    uv[0] = uv[1] = 0.0f;
    if (!gs->uvs)
        return;
    const uint32_t *ix = gs->indices + 3 * (size_t)prim;
    const float *t0 = gs->uvs + 2 * (size_t)ix[0], *t1 = gs->uvs + 2 * (size_t)ix[1],
                *t2 = gs->uvs + 2 * (size_t)ix[2];
    float b0 = 1.0f - b1 - b2;
    for (int k = 0; k < 2; k++)
        uv[k] = b0 * t0[k] + b1 * t1[k] + b2 * t2[k];
}

/* Cut-out masks: Embree calls this for every candidate hit, for closest-hit and shadow rays alike,
 * so a hole never hides what lies behind it nor casts a shadow. RTCHitN is opaque in C; its SOA
 * layout (rtcore_ray.h: Ng_x, Ng_y, Ng_z, u, v, primID, each N wide) is read directly. */
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
        unsigned prim = hu[5 * n + i];
        const gib_material *m = &gs->materials[gs->tri_material[prim]];
        if (m->alpha_tex < 0)
            continue;
        float uv[2], a[4];
        ref_interp_uv(gs, prim, hf[3 * n + i], hf[4 * n + i], uv);
        ref_tex_sample(&gs->textures[m->alpha_tex], uv[0], uv[1], a);
        if (a[0] < 0.5f)
            args->valid[i] = 0;
    }
}

static void ref_embree_error(void *user, enum RTCError code, const char *str)
{
    ref_world *w = user;
    snprintf(w->embree_msg, sizeof w->embree_msg, "Embree error %d: %s", (int)code,
             str ? str : "(no message)");
}

/* Ray offset. 1e-4 of the bounding-box diagonal of the vertices: large enough to clear the float
 * error of a hit point on any triangle of the scene, small next to any feature a scene is built
 * to show. Floored at 2^-17 of the largest coordinate magnitude (64 float ulps of it), because
 * a hit point's rounding error grows with its distance from the origin, not with the scene's size
 * (DESIGN.md, "Hard cases": a scene far from the origin). */
float gib_reference_ray_eps(const gib_scene *gs)
{
    if (!gs || !gs->positions || gs->vertex_count == 0)
        return 0.0f;
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    double amax = 0.0;
    for (uint32_t i = 0; i < gs->vertex_count; i++) {
        for (int k = 0; k < 3; k++) {
            double c = gs->positions[3 * (size_t)i + k];
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

static int ref_validate(const gib_scene *gs, int *has_alpha, gib_error *err)
{
    const char *nm = gs->name[0] ? gs->name : "(unnamed)";
    *has_alpha = 0;
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
        if (mt->alpha_tex >= 0)
            *has_alpha = 1;
    }
    return 0;
}

int ref_world_build(ref_world *w, const gib_scene *gs, gib_error *err)
{
    memset(w, 0, sizeof *w);
    w->gs = gs;
    int has_alpha;
    if (ref_validate(gs, &has_alpha, err) < 0)
        return -1;
    w->eps = gib_reference_ray_eps(gs);
    if (gs->triangle_count == 0)
        return 0; /* an empty view: every ray misses (DESIGN.md, "Hard cases") */

    w->device = rtcNewDevice(NULL);
    if (!w->device)
        return gib_fail(err, "cannot create an Embree device (error %d)",
                        (int)rtcGetDeviceError(NULL));
    rtcSetDeviceErrorFunction(w->device, ref_embree_error, w);

    w->scene = rtcNewScene(w->device);
    /* ROBUST: no traversal shortcuts that can let a ray slip through a shared edge, which would
     * leak light or visibility into a reference. HIGH quality: the BVH is built once and traced
     * millions of times. */
    rtcSetSceneFlags(w->scene, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(w->scene, RTC_BUILD_QUALITY_HIGH);

    RTCGeometry g = rtcNewGeometry(w->device, RTC_GEOMETRY_TYPE_TRIANGLE);
    /* Copied into Embree-owned buffers, which Embree pads for its 16-byte vector loads (a shared
     * buffer would have to be padded by the scene loader). */
    float *vb = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                        3 * sizeof(float), gs->vertex_count);
    unsigned *ib = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                           3 * sizeof(unsigned), gs->triangle_count);
    if (!vb || !ib) {
        rtcReleaseGeometry(g);
        gib_fail(err, "scene '%s': %s", gs->name,
                 w->embree_msg[0] ? w->embree_msg : "Embree could not allocate geometry buffers");
        ref_world_free(w);
        return -1;
    }
    memcpy(vb, gs->positions, 3 * sizeof(float) * gs->vertex_count);
    memcpy(ib, gs->indices, 3 * sizeof(unsigned) * gs->triangle_count);
    rtcSetGeometryUserData(g, w);
    if (has_alpha) {
        rtcSetGeometryIntersectFilterFunction(g, ref_alpha_filter);
        rtcSetGeometryOccludedFilterFunction(g, ref_alpha_filter);
    }
    rtcCommitGeometry(g);
    rtcAttachGeometry(w->scene, g);
    rtcReleaseGeometry(g);
    rtcCommitScene(w->scene);
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
    if (w->scene)
        rtcReleaseScene(w->scene);
    if (w->device)
        rtcReleaseDevice(w->device);
    w->scene = NULL;
    w->device = NULL;
}

/* ---- rays ---- */

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

/* The front of a surface is the side its vertex normals point to (the geometric normal is turned
 * to agree with them), so a mesh's winding order does not matter; the GL side must use the same
 * rule for one-sided materials. */
static void ref_fill_hit(const ref_world *w, uint32_t prim, float b1, float b2, const float d[3],
                         ref_hit *h)
{
    const gib_scene *gs = w->gs;
    const uint32_t *ix = gs->indices + 3 * (size_t)prim;
    const float *p0 = gs->positions + 3 * (size_t)ix[0], *p1 = gs->positions + 3 * (size_t)ix[1],
                *p2 = gs->positions + 3 * (size_t)ix[2];
    float b0 = 1.0f - b1 - b2;
    float e1[3], e2[3];
    for (int k = 0; k < 3; k++) {
        h->p[k] = b0 * p0[k] + b1 * p1[k] + b2 * p2[k];
        e1[k] = p1[k] - p0[k];
        e2[k] = p2[k] - p0[k];
    }
    h->ng[0] = e1[1] * e2[2] - e1[2] * e2[1];
    h->ng[1] = e1[2] * e2[0] - e1[0] * e2[2];
    h->ng[2] = e1[0] * e2[1] - e1[1] * e2[0];
    int ng_ok = ref_normalize(h->ng);

    int n_ok = 0;
    if (gs->normals) {
        const float *n0 = gs->normals + 3 * (size_t)ix[0], *n1 = gs->normals + 3 * (size_t)ix[1],
                    *n2 = gs->normals + 3 * (size_t)ix[2];
        for (int k = 0; k < 3; k++)
            h->n[k] = b0 * n0[k] + b1 * n1[k] + b2 * n2[k];
        n_ok = ref_normalize(h->n);
    }
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
    h->mat = &gs->materials[gs->tri_material[prim]];
    ref_interp_uv(gs, prim, b1, b2, h->uv);
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

int ref_trace(const ref_world *w, const float o[3], const float d[3], ref_hit *hit)
{
    if (!w->scene)
        return 0;
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    struct RTCRayHit rh;
    rh.ray.org_x = o[0];
    rh.ray.org_y = o[1];
    rh.ray.org_z = o[2];
    rh.ray.tnear = 0.0f;
    rh.ray.dir_x = d[0];
    rh.ray.dir_y = d[1];
    rh.ray.dir_z = d[2];
    rh.ray.time = 0.0f;
    rh.ray.tfar = INFINITY;
    rh.ray.mask = 0xffffffffu;
    rh.ray.id = 0;
    rh.ray.flags = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(w->scene, &ctx, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID)
        return 0;
    ref_fill_hit(w, rh.hit.primID, rh.hit.u, rh.hit.v, d, hit);
    return 1;
}

int ref_occluded(const ref_world *w, const float o[3], const float d[3], float tfar)
{
    if (!w->scene || !(tfar > 0.0f))
        return 0;
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    struct RTCRay r;
    r.org_x = o[0];
    r.org_y = o[1];
    r.org_z = o[2];
    r.tnear = 0.0f;
    r.dir_x = d[0];
    r.dir_y = d[1];
    r.dir_z = d[2];
    r.time = 0.0f;
    r.tfar = tfar;
    r.mask = 0xffffffffu;
    r.id = 0;
    r.flags = 0;
    rtcOccluded1(w->scene, &ctx, &r);
    return r.tfar == -INFINITY; /* Embree's mark of an occluded ray */
}

void ref_offset_origin(const ref_world *w, const ref_hit *h, const float d[3], float o[3])
{
    float s = ref_dot(h->ng, d) >= 0.0f ? w->eps : -w->eps;
    for (int k = 0; k < 3; k++)
        o[k] = h->p[k] + s * h->ng[k];
}
