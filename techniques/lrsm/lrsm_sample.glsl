// gibench technique `lrsm` — sampling the layered reflective shadow maps (Algorithm 1, Eq. 5-15):
// the outgoing radiance toward v_c of the surfaces inside the cone sample (x_c, r_c), from every
// light's LRSM (rgb: Eq. 5 summed over the layers, Eq. 14), and the coverage those lit surfaces
// have in the footprint (a: sum A V; lrsm_cone.frag's `coverage`): the cone pass's sample with
// hits 0, and the probe's. lrsm_hits.glsl reads the same layers through the same footprints
// (lrsm_light_sample, lrsm_face_footprint) for hits 1. Needs common/light_view.glsl and
// lrsm/lrsm_common.glsl.
// Choices the paper leaves open (or where it was changed), each with its reason:
//  - Layer selection: the paper samples the layers whose depth range holds z_c (as LVSM). A cone's
//    samples grow to a fraction of the scene (a 60-degree cone's diameter is 1.15 t), and a sphere
//    centred in empty space then reaches surfaces of the next layer only: in the furnace the
//    central cone's last sample (z_c = 0.6 m, r_c = 0.9 m, walls at 1 m) read nothing. Layers
//    whose range meets [z_c - r_c, z_c + r_c] are sampled instead (for r_c -> 0 the paper's rule).
//  - Eq. 15's decay is evaluated at the layer's filtered mean depth mu rather than at z_c: with the
//    wider selection a sample can read two layers that both hold a surface of the overlap band, and
//    the decays at that surface's depth add to 1 (k(t) + k(1 - t) = 1), so it counts once.
//  - Eq. 8's N = <n_mean . v_c> with the opacity-normalised, not renormalised, mean normal, as
//    Algorithm 1 (u_backface 0). It dims a surface seen obliquely by that cosine, although Sec. 4.1
//    derives L as the mean radiance over the area the cone sees (the <n.v> of Eq. 4 cancels in the
//    normalisation) and the voxel alpha already holds the coverage. u_backface 1 keeps Eq. 8 as
//    the backface test only, N = 1 where <n_mean . v_c> > 0: a layer seen edge-on then counts as
//    much as one seen face-on, and a sample's radiance becomes that of whatever lit surface has
//    the most area in the light's view (a spot's lit floor read by cones that see it at grazing).
//    u_backface 2 (the default) is Sec. 4.1's mean over the area the cone sees: each layer's
//    radiance weighted by its projected coverage A V N, the sum over the face divided by sum A V N
//    and multiplied back by the lit coverage sum A V, which the sample's normalisation
//    (lrsm_cone.frag's `coverage`) and Eq. 1 go on using: a surface seen obliquely keeps its
//    radiance, and among the layers a sample reads, those facing the cone count the most (Cornell
//    box indirect at 128^3 0.85 -> 0.91 of the reference's, Sponza rel RMSE 0.88 -> 0.84).
//  - Eq. 12's depth window (u_visibility 1, the default): [z_c - r_c / <n.l>, z_c + r_c / <n.l>]
//    with <n.l> the layer's filtered mean normal against the direction to the light, instead of
//    the sphere's own [z_c - r_c, z_c + r_c] (u_visibility 0, the paper). A surface through the
//    sample tilted by theta from the light is hit, across the footprint (the sphere's projection,
//    2 r_c wide), at depths mu +- r_c tan(theta): with the sphere's window, a wall lit at 60
//    degrees counts about half of its own footprint as outside the sample, and assumption 2 of
//    Sec. 4.1 turns that half into shadowed surface, so every obliquely lit surface lost light
//    (Cornell box indirect 0.71 of the reference's at 128^3). The widened window r_c / cos(theta)
//    >= r_c tan(theta) keeps the whole surface; an occluder in front or a receiver in its shadow
//    behind, farther from mu than that, stays outside (0.81 of the reference's).
//  - The footprint's mip is log2 of the projected diameter in layer texels at the sample centre's
//    distance along the face's axis, clamped below by u_mip_clamp (Sec. 7).
//  - The faces a footprint overlaps (u_seams 1, the default): the paper has one view per light; a
//    point light's cube has six, and a diffuse sample spans 1x1 to 4x4 texels of a coarse mip, so
//    most samples near a seam straddle it. Looking up only the face that holds the centre switches
//    a sample's whole contribution from one face's filtered texels to the other's when the centre
//    crosses the seam plane: one straight edge per sample per seam, facets on every wall. Every
//    face the footprint (a square of the projected diameter) overlaps is read instead, weighted by
//    the fraction of the footprint inside it; a cube's weights are normalised to sum to 1 (its
//    faces tile every direction). A spot's single view is weighted alike without normalising:
//    outside its view there is no light, so a sample at the border fades with the fraction inside
//    instead of being dropped whole when its centre leaves. u_seams 0: the centre's face only,
//    dropped outside it (the literal reading).
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
    ls.zc = ls.kind == 2 ? dot(ls.rel, lv_axis(lv_first_face(i))) : length(ls.rel);
    ls.l = ls.kind == 2 ? -lv_axis(lv_first_face(i)) : -ls.rel / max(ls.zc, 1e-30);
    int centre = ls.kind < 0 ? 0 : lv_face(i, ls.rel);
    ls.first = u_seams != 0 ? lv_first_face(i) : centre;
    ls.last = u_seams != 0 ? ls.first + (ls.kind == 0 ? 5 : 0) : centre;
    return ls;
}

// A sample's footprint (radius rc) on face `face` of light i: its centre uv (on the face's plane),
// its half-width r_uv as a fraction of the face, its mip level, and as the result its weight, the
// fraction of the footprint inside the face (u_seams 1) or whether the centre is (u_seams 0).
float lrsm_face_footprint(int i, int face, LrsmLightSample ls, float rc, out vec2 uv,
                          out float r_uv, out float mip)
{
    float za = dot(ls.rel, lv_axis(face));
    if (ls.kind != 2 && za <= 0.0)
        return 0.0;
    // The projected diameter in layer texels (a layer texel is 2 light-view texels): 2 r_c over
    // 2 s z_a (s: a texel's side on the unit-distance plane), or over 2 s (orthographic, s in
    // world units); as a fraction of the face, half-width r_uv.
    float diameter = ls.kind == 2 ? rc / lv_texel(i) : rc / (za * lv_texel(i));
    r_uv = max(diameter, 1e-6) / float(lv_res());
    uv = lv_project(face, ls.rel).xy;
    bool inside = all(greaterThanEqual(uv, vec2(0.0))) && all(lessThanEqual(uv, vec2(1.0)));
    float w = u_seams != 0 ? lrsm_inside(uv.x, r_uv) * lrsm_inside(uv.y, r_uv) : (inside ? 1.0 : 0.0);
    mip = max(log2(max(diameter, 1e-30)), u_mip_clamp);
    return w;
}

// The sample xc (radius rc, seen from vc) over every light: rgb the lights' sum f A R V N, a the
// lit coverage, the largest light's: lights that light the same surfaces see the same coverage, and
// a sum would count it once per light (two coincident lights of half the power gave half the
// light). Where different lights light different surfaces inside one sample, the union is larger
// than the largest and the radiance over it is overestimated.
vec4 lrsm_sample(vec3 xc, float rc, vec3 vc)
{
    vec4 L = vec4(0.0);
    for (int i = 0; i < u_lrsm_lights; i++) {
        LrsmLightSample ls = lrsm_light_sample(i, xc);
        if (ls.kind < 0)
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
        Li = ls.kind == 0 && u_seams != 0 && wsum > 0.0 ? Li / wsum : Li;
        L = vec4(L.rgb + Li.rgb, max(L.a, Li.a));
    }
    return L;
}
