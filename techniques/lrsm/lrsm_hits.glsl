// gibench technique `lrsm` — a cone sample as the share of the cone's rays that meet the lit
// surfaces inside it (parameter hits 1, the default; lrsm_cone.frag says why the cone pass departs
// from Eq. 5 and 1 there). Needs common/light_view.glsl, lrsm/lrsm_common.glsl and
// lrsm/lrsm_sample.glsl (the layers, the light's view of the sample, the faces' footprints).
//  - Each layer the footprint reads is one plane: its mean normal, normalised, through its mean
//    depth mu (Eq. 10) on the light's ray through the sample's centre. Its distance from the centre
//    along the normal is <n.l> (mu - z_c), uncertain by the layer's depth variance (Eq. 11) less
//    what the plane's own tilt to the light spreads over the footprint (lrsm_plane_spread).
//  - Eq. 8's <n.v> becomes the mean of the clamped cosine over the cone's cap (lrsm_cap_cosine): a
//    60-degree cone along a lit floor still meets it with its lower rays, which the axis's cosine
//    (exactly 0) would cull: a wall's central cone in a box lit from above would read no light.
//  - The plane's share of the sample's rays is the share that crosses it within the sample's step
//    (lrsm_plane_hits), times its coverage A of the footprint: successive touching spheres meet a
//    plane facing the axis once, and a plane along the axis a little in each sample, the less the
//    farther from the axis. The layer's light is that share of its radiance R (Eq. 14).
//  - Eq. 12's V (with the window `visibility` sets) still measures the lit coverage A V inside the
//    sample, which lrsm_cone.frag takes out of the voxels' alpha before the rest blocks as unlit.
//  - The footprint is read as 2 x 2 taps, each a quarter of it, half a mip level finer: a coarse
//    texel mixes the floor and a box's top into one plane at their mean depth, and finer taps keep
//    more of them apart; half a level (LRSM_TAP_FINER), not a whole one, which loses on Sibenik.
struct LrsmHits {
    vec3 light;  // sum f A R H: the light of the lit planes' hits
    float hit;   // sum f A H: the share of the sample's rays they stop
    float lit;   // sum f A V: the lit coverage inside the sample (Eq. 12)
};

const float LRSM_TAP_FINER = 0.5; // mip levels finer than the footprint's

LrsmHits lrsm_hits_face(int i, int face, vec2 uv, LrsmLightSample ls, float rc, vec3 vc,
                        float sin_half, float step, float mip)
{
    LrsmHits h = LrsmHits(vec3(0.0), 0.0, 0.0);
    int layers = u_depth_parts * u_normal_parts;
    for (int d = 0; d < u_depth_parts; d++) {
        float lo, hi;
        lrsm_layer_range(i, d, lo, hi);
        if (!lrsm_layer_overlaps(i, d, ls.zc - rc, ls.zc + rc))
            continue;
        float zw = (ls.zc - lo) / (hi - lo), rw = rc / (hi - lo);
        for (int k = 0; k < u_normal_parts; k++) {
            vec3 at = vec3(uv, float(face * layers + d * u_normal_parts + k));
            vec4 nt = textureLod(u_lrsm_normal, at, mip);
            vec4 dt = textureLod(u_lrsm_depth, at, mip);
            if (nt.w < 1e-4 || dt.z < 1e-4)
                continue;
            vec3 n = nt.xyz / max(length(nt.xyz), 1e-30);
            float cv = dot(n, vc);
            float E = lrsm_cap_cosine(cv, sqrt(max(1.0 - cv * cv, 0.0)), sin_half);
            if (E <= 0.0)   // Eq. 8 over the cap: the plane faces away from every ray
                continue;
            float mu = dt.x / dt.z, var = dt.y / dt.z - mu * mu;   // Eq. 10, 11
            float nl = max(dot(n, ls.l), 0.0);
            float delta = nl * (mu - zw) * (hi - lo);
            float spread = lrsm_plane_spread(max(var, LRSM_MIN_VARIANCE) * (hi - lo) * (hi - lo), nl, rc);
            float H = lrsm_plane_hits(delta, E, rc, step, spread);
            float nlv = u_visibility != 0 ? max(dot(nt.xyz / nt.w, ls.l), LRSM_MIN_COS_NL) : 1.0;
            float V = lrsm_visibility(zw, rw / nlv, mu, var);
            vec4 rt = textureLod(u_lrsm_radiance, at, mip);
            vec3 AR = rt.a > 0.0 ? rt.rgb * (dt.z / rt.a) : vec3(0.0);
            float f = lrsm_decay(i, d, lo + mu * (hi - lo));    // Eq. 15 at the layer's mean depth
            h.light += f * H * AR;
            h.hit += f * H * dt.z;
            h.lit += f * V * dt.z;
        }
    }
    return h;
}

// The sample xc (radius rc) of a cone along dir (half-aperture's sine sin_half, step `step` times
// the sample's diameter) over every light: light summed; hit and lit the largest light's, as
// lrsm_sample's coverage (lights that light the same surface see it once).
LrsmHits lrsm_hits(vec3 xc, float rc, vec3 dir, float sin_half, float step)
{
    LrsmHits h = LrsmHits(vec3(0.0), 0.0, 0.0);
    for (int i = 0; i < u_lrsm_lights; i++) {
        LrsmLightSample ls = lrsm_light_sample(i, xc);
        if (ls.kind == GIB_LV_KIND_NONE)
            continue;
        LrsmHits li = LrsmHits(vec3(0.0), 0.0, 0.0);   // light i's, before the cube's weights
        float wsum = 0.0;
        for (int face = ls.first; face <= ls.last; face++) {
            vec2 uv;
            float r_uv, mip;
            float w = lrsm_face_footprint(i, face, ls, rc, uv, r_uv, mip);
            if (w <= 0.0)
                continue;
            float tap_mip = max(mip - LRSM_TAP_FINER, u_mip_clamp);
            for (int q = 0; q < 4; q++) {
                vec2 o = 0.5 * r_uv * vec2((q & 1) != 0 ? 1.0 : -1.0, (q & 2) != 0 ? 1.0 : -1.0);
                LrsmHits t = lrsm_hits_face(i, face, clamp(uv + o, 0.0, 1.0), ls, rc, -dir,
                                            sin_half, step, tap_mip);
                li.light += 0.25 * w * t.light;
                li.hit += 0.25 * w * t.hit;
                li.lit += 0.25 * w * t.lit;
            }
            wsum += w;
        }
        float norm = ls.kind == GIB_LV_KIND_CUBE && u_seams != 0 && wsum > 0.0 ? 1.0 / wsum : 1.0;
        h.light += norm * li.light;
        h.hit = max(h.hit, norm * li.hit);
        h.lit = max(h.lit, norm * li.lit);
    }
    return h;
}
