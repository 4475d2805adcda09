// gibench technique `lrsm` — sampling the layered reflective shadow maps (Algorithm 1, Eq. 5-15):
// the outgoing radiance toward v_c of the surfaces inside the cone sample (x_c, r_c), from every
// light's LRSM. Needs common/light_view.glsl and lrsm/lrsm_common.glsl.
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
//    normalisation) and the voxel alpha already holds the coverage: u_backface 1 (the default) keeps
//    Eq. 8 as the backface test only, N = 1 where <n_mean . v_c> > 0.
//  - The footprint's mip is log2 of the projected diameter in layer texels at the sample centre's
//    distance along the view axis, clamped below by u_mip_clamp (Sec. 7); a sample is looked up in
//    the face of a cube light view its centre falls in (spheres across a cube seam read one face).
layout(binding = GIB_UNIT_OWN_FIRST + 0) uniform sampler2DArray u_lrsm_radiance;
layout(binding = GIB_UNIT_OWN_FIRST + 1) uniform sampler2DArray u_lrsm_normal;
layout(binding = GIB_UNIT_OWN_FIRST + 2) uniform sampler2DArray u_lrsm_depth;
layout(location = 7) uniform float u_mip_clamp;
layout(location = 8) uniform int u_lrsm_lights;   // lights in the table (the scene's)
layout(location = 14) uniform int u_backface;     // 0: Eq. 8's cosine; 1: Eq. 8 as a test only

vec3 lrsm_sample(vec3 xc, float rc, vec3 vc)
{
    vec3 L = vec3(0.0);
    int layers = u_depth_parts * u_normal_parts;
    for (int i = 0; i < u_lrsm_lights; i++) {
        int kind = lv_kind(i);
        if (kind < 0)
            continue;
        vec3 rel = xc - lv_origin(i);
        int face = lv_face(i, rel);
        vec3 axis = lv_axis(face);
        // The sample's depth as the light view measures it, and its projected diameter in layer
        // texels (a layer texel is 2 light-view texels): 2 r_c over 2 s z_axis (s: a texel's side
        // on the unit-distance plane), or 2 r_c over 2 s (orthographic, s in world units).
        float zc, diameter;
        if (kind == 2) {
            zc = dot(rel, axis);
            diameter = rc / lv_texel(i);
        } else {
            float za = dot(rel, axis);
            if (za <= 0.0)
                continue;
            zc = length(rel);
            diameter = rc / (za * lv_texel(i));
        }
        vec3 uv = lv_project(face, rel);
        if (any(lessThan(uv.xy, vec2(0.0))) || any(greaterThan(uv.xy, vec2(1.0))))
            continue;
        float mip = max(log2(max(diameter, 1e-30)), u_mip_clamp);
        for (int d = 0; d < u_depth_parts; d++) {
            float lo, hi;
            lrsm_layer_range(i, d, lo, hi);
            if (!lrsm_layer_overlaps(i, d, zc - rc, zc + rc))
                continue;
            float zw = (zc - lo) / (hi - lo), rw = rc / (hi - lo);
            for (int k = 0; k < u_normal_parts; k++) {
                vec3 at = vec3(uv.xy, float(face * layers + d * u_normal_parts + k));
                vec4 nt = textureLod(u_lrsm_normal, at, mip);
                if (nt.w < 1e-4)
                    continue;
                float N = dot(nt.xyz / nt.w, vc);  // Eq. 8: mean normal, not renormalised
                if (N <= 0.0)                      // backface culling
                    continue;
                if (u_backface != 0)
                    N = 1.0;
                vec4 dt = textureLod(u_lrsm_depth, at, mip);
                if (dt.z < 1e-4)
                    continue;
                float mu = dt.x / dt.z;                         // Eq. 10
                float var = dt.y / dt.z - mu * mu;              // Eq. 11
                float V = lrsm_visibility(zw, rw, mu, var);     // Eq. 12
                if (V <= 0.0)
                    continue;
                vec3 AR = textureLod(u_lrsm_radiance, at, mip).rgb; // unnormalised: A R (Eq. 14)
                float f = lrsm_decay(i, d, lo + mu * (hi - lo));    // Eq. 15 at the layer's mean depth
                L += f * AR * (V * N);
            }
        }
    }
    return L;
}
