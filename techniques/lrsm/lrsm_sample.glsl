// gibench technique `lrsm` — sampling the layered reflective shadow maps (Algorithm 1, Eq. 5-15):
// the outgoing radiance toward v_c of the surfaces inside the cone sample (x_c, r_c), from every
// light's LRSM (rgb: Eq. 5 summed over the layers, Eq. 14), and the coverage those lit surfaces
// have in the footprint (a: sum A V; lrsm_cone.frag's `coverage`), for hits 0 and the probe.
// lrsm_hits.glsl reads the same layers through lrsm_light_sample and lrsm_face_footprint (hits 1).
// Needs common/light_view.glsl and lrsm/lrsm_common.glsl. Where the paper is left open or departed:
//  - Layers: every layer whose depth range meets [z_c - r_c, z_c + r_c], not only the one holding
//    z_c: a wide sample centred in empty space otherwise misses the next layer's walls (the
//    paper's rule as r_c -> 0).
//  - Eq. 15's decay at the layer's filtered mean depth mu, not z_c: a surface in the overlap band
//    read through two layers then counts once (k(t) + k(1 - t) = 1).
//  - Eq. 8's N (u_backface): 0, Algorithm 1's cosine with the opacity-normalised mean normal; 1,
//    Eq. 8 as a backface test only; 2 (default), Sec. 4.1's mean over the area the cone sees (the
//    <n.v> of Eq. 4 cancels in the normalisation): radiance weighted by the projected coverage
//    A V N, divided by sum A V N and multiplied by the lit coverage sum A V, so a surface seen
//    obliquely keeps its radiance and layers facing the cone count the most.
//  - Eq. 12's window (u_visibility 1, default): [z_c - r_c / <n.l>, z_c + r_c / <n.l>] with <n.l>
//    the layer's mean normal against the light. A surface tilted by theta spans mu +- r_c tan theta
//    across the footprint; the sphere's own window (u_visibility 0, the paper) counts part of an
//    obliquely lit surface as outside and Sec. 4.1's assumption 2 makes it shadow. r_c / cos theta
//    >= r_c tan theta keeps the surface; occluders and receivers farther from mu stay outside.
//  - The footprint's mip: log2 of the projected diameter in layer texels at the centre's distance
//    along the face's axis, clamped below by u_mip_clamp (Sec. 7).
//  - Faces (u_seams 1, default): the paper has one view per light, a cube six. Every face the
//    footprint (a square of the projected diameter) overlaps is read, weighted by the fraction
//    inside it, so a sample crossing a seam does not switch whole from one face to the other
//    (straight edges on every wall); a cube's weights are normalised to 1, a spot's single view's
//    are not (a sample at its border fades). u_seams 0: the centre's face only (literal reading).
layout(binding = LRSM_UNIT_RADIANCE) uniform sampler2DArray u_lrsm_radiance;
layout(binding = LRSM_UNIT_NORMAL) uniform sampler2DArray u_lrsm_normal;
layout(binding = LRSM_UNIT_DEPTH) uniform sampler2DArray u_lrsm_depth;
layout(location = LRSM_LOC_MIP_CLAMP) uniform float u_mip_clamp;
layout(location = LRSM_LOC_LIGHTS) uniform int u_lrsm_lights;  // lights in the table (the scene's)
// 0: Eq. 8's cosine; 1: Eq. 8 as a test only
layout(location = LRSM_LOC_BACKFACE) uniform int u_backface;
layout(location = LRSM_LOC_SEAMS) uniform int u_seams;       // 1: every face the footprint overlaps
// 1: Eq. 12's window widened by 1 / <n.l>
layout(location = LRSM_LOC_VISIBILITY) uniform int u_visibility;

// Algorithm 1 in one face of light i: the layers met by [z_c - r_c, z_c + r_c] at uv, at mip level
// `mip` (Eq. 5-15): rgb = sum f A R V N, a = sum f A V (the coverage of the lit surfaces inside
// the sample); with u_backface 2, rgb = (sum f A R V N / sum f A V N) a.
vec4 lrsm_sample_face(int i, int face, vec2 uv, float zc, float rc, vec3 vc, vec3 l, float mip)
{
    vec4 L = vec4(0.0);
    float P = 0.0;
    int layers = u_depth_parts * u_normal_parts;
    for (int d = 0; d < u_depth_parts; d++) {
        float lo, hi;
        lrsm_layer_range(i, d, lo, hi);
        if (!lrsm_layer_overlaps(i, d, zc - rc, zc + rc))
            continue;
        float zw = (zc - lo) / (hi - lo), rw = rc / (hi - lo);
        for (int k = 0; k < u_normal_parts; k++) {
            vec3 at = vec3(uv, float(face * layers + d * u_normal_parts + k));
            vec4 nt = textureLod(u_lrsm_normal, at, mip);
            if (nt.w < 1e-4)
                continue;
            float N = dot(nt.xyz / nt.w, vc);  // Eq. 8: mean normal, not renormalised
            if (N <= 0.0)                      // backface culling
                continue;
            if (u_backface == 1)
                N = 1.0;
            vec4 dt = textureLod(u_lrsm_depth, at, mip);
            if (dt.z < 1e-4)
                continue;
            float mu = dt.x / dt.z;                         // Eq. 10
            float var = dt.y / dt.z - mu * mu;              // Eq. 11
            // Eq. 12, its window widened by the surface's tilt to the light (u_visibility 1)
            float nl = u_visibility != 0 ? max(dot(nt.xyz / nt.w, l), LRSM_MIN_COS_NL) : 1.0;
            float V = lrsm_visibility(zw, rw / nl, mu, var);
            if (V <= 0.0)
                continue;
            // A R (Eq. 14): the area-weighted mean radiance (lrsm_build.comp) times A = alpha
            vec4 rt = textureLod(u_lrsm_radiance, at, mip);
            vec3 AR = rt.a > 0.0 ? rt.rgb * (dt.z / rt.a) : vec3(0.0);
            float f = lrsm_decay(i, d, lo + mu * (hi - lo));    // Eq. 15 at the layer's mean depth
            L += f * vec4(AR * (V * N), dt.z * V);
            P += f * dt.z * V * N;
        }
    }
    if (u_backface == 2)    // the mean over the projected coverage, times the lit coverage
        return P > 0.0 ? vec4(L.rgb * (L.a / P), L.a) : vec4(0.0);
    return L;
}

// The fraction of [c - r, c + r] inside [0, 1].
float lrsm_inside(float c, float r)
{
    return clamp((min(c + r, 1.0) - max(c - r, 0.0)) / (2.0 * r), 0.0, 1.0);
}

// Light i as a cone sample centred at xc sees it: the sample's depth as the light view measures it
// (along the axis for an orthographic view, from the light for a cube or perspective one), the
// direction toward the light, and the faces to read (every face of a cube with u_seams 1).
struct LrsmLightSample {
    vec3 rel;
    float zc;
    vec3 l;
    int kind, first, last;
};

LrsmLightSample lrsm_light_sample(int i, vec3 xc)
{
    LrsmLightSample ls;
    ls.kind = lv_kind(i);
    ls.rel = xc - lv_origin(i);
    ls.zc = ls.kind == GIB_LV_KIND_ORTHO ? dot(ls.rel, lv_axis(lv_first_face(i))) : length(ls.rel);
    ls.l = ls.kind == GIB_LV_KIND_ORTHO ? -lv_axis(lv_first_face(i)) : -ls.rel / max(ls.zc, 1e-30);
    int centre = ls.kind == GIB_LV_KIND_NONE ? 0 : lv_face(i, ls.rel);
    ls.first = u_seams != 0 ? lv_first_face(i) : centre;
    ls.last = u_seams != 0 ? ls.first + (ls.kind == GIB_LV_KIND_CUBE ? 5 : 0) : centre;
    return ls;
}

// A sample's footprint (radius rc) on face `face` of light i: its centre uv (on the face's plane),
// its half-width r_uv as a fraction of the face, its mip level, and as the result its weight, the
// fraction of the footprint inside the face (u_seams 1) or whether the centre is (u_seams 0).
float lrsm_face_footprint(int i, int face, LrsmLightSample ls, float rc, out vec2 uv,
                          out float r_uv, out float mip)
{
    float za = dot(ls.rel, lv_axis(face));
    if (ls.kind != GIB_LV_KIND_ORTHO && za <= 0.0)
        return 0.0;
    // The projected diameter in layer texels (a layer texel is 2 light-view texels): 2 r_c over
    // 2 s z_a (s: a texel's side on the unit-distance plane), or over 2 s (orthographic, s in
    // world units); as a fraction of the face, half-width r_uv.
    float diameter = ls.kind == GIB_LV_KIND_ORTHO ? rc / lv_texel(i) : rc / (za * lv_texel(i));
    r_uv = max(diameter, 1e-6) / float(lv_res());
    uv = lv_project(face, ls.rel).xy;
    bool inside = all(greaterThanEqual(uv, vec2(0.0))) && all(lessThanEqual(uv, vec2(1.0)));
    float w = u_seams != 0 ? lrsm_inside(uv.x, r_uv) * lrsm_inside(uv.y, r_uv) : (inside ? 1.0 : 0.0);
    mip = max(log2(max(diameter, 1e-30)), u_mip_clamp);
    return w;
}

// The sample xc (radius rc, seen from vc) over every light: rgb the lights' sum f A R V N, a the
// lit coverage, the largest light's: lights that light the same surfaces see the same coverage, and
// a sum would count it once per light (two coincident lights of half the power would give half
// the light). Where different lights light different surfaces inside one sample, the union is
// larger than the largest and the radiance over it is overestimated.
vec4 lrsm_sample(vec3 xc, float rc, vec3 vc)
{
    vec4 L = vec4(0.0);
    for (int i = 0; i < u_lrsm_lights; i++) {
        LrsmLightSample ls = lrsm_light_sample(i, xc);
        if (ls.kind == GIB_LV_KIND_NONE)
            continue;
        vec4 Li = vec4(0.0);
        float wsum = 0.0;
        for (int face = ls.first; face <= ls.last; face++) {
            vec2 uv;
            float r_uv, mip;
            float w = lrsm_face_footprint(i, face, ls, rc, uv, r_uv, mip);
            if (w <= 0.0)
                continue;
            Li += w * lrsm_sample_face(i, face, clamp(uv, 0.0, 1.0), ls.zc, rc, vc, ls.l, mip);
            wsum += w;
        }
        Li = ls.kind == GIB_LV_KIND_CUBE && u_seams != 0 && wsum > 0.0 ? Li / wsum : Li;
        L = vec4(L.rgb + Li.rgb, max(L.a, Li.a));
    }
    return L;
}
