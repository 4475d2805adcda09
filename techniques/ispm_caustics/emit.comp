// Photon emission (thesis Sec. 3.3.1): one photon per texel of mip level u_level of the specular
// mask that is exactly 1 (Fig. 3.5: all 4^l light-view texels below it specular), so the count is
// s(l) of Sec. 3.3.1.1. The photon stands at one of those 4^l texels, picked with the
// pre-generated random numbers (the same every frame, Ch. 4: temporal coherence), and carries 4^l
// times that texel's flux: an unbiased estimate of the flux the block receives.
// Reflection (Sec. 3.3.1.2): Russian roulette with P_r = max(d + s), P_d = sum d / sum(d + s) P_r,
// P_s = P_r - P_d on the same random numbers; only specular photons are traced, with flux
// Phi s / P_s; then mirror reflection, or a Phong lobe sample (caustics.glsl) whose weight
// (n+2)/(n+1) cos the thesis leaves out (it is 1 only on average over a normal-incidence lobe).
#include "common/scene.glsl"
#include "common/light_view.glsl"
#include "ispm_caustics/caustics.glsl"
#include "common/groups_shared.h"
layout(local_size_x = GIB_GROUP_2D, local_size_y = GIB_GROUP_2D) in;
layout(binding = GIB_UNIT_LV_POSITION) uniform sampler2DArray lv_position;
layout(binding = GIB_UNIT_LV_NORMAL) uniform sampler2DArray lv_normal;
layout(binding = GIB_UNIT_LV_FLUX) uniform sampler2DArray lv_flux;
layout(binding = GIB_UNIT_LV_SPECULAR) uniform sampler2DArray lv_specular;
layout(binding = ISPM_EMIT_UNIT_MASK) uniform sampler2DArray u_mask;
layout(std430, binding = ISPM_SSBO_PHOTONS) writeonly buffer Photons { Photon photons[]; };
layout(std430, binding = ISPM_SSBO_RANDOM) readonly buffer Random { vec4 rnd[]; };
// lines {2, N, 0, 0}, points {N, 1, 0, 0}
layout(std430, binding = ISPM_SSBO_COMMAND) buffer Command { uint cmd[8]; };
layout(std430, binding = ISPM_SSBO_STATUS) buffer Status {
    uint list_count, list_overflow, photon_overflow, list_longest;
};
layout(location = ISPM_EMIT_LOC_LEVEL) uniform int u_level;
layout(location = ISPM_EMIT_LOC_RES) uniform int u_res_l;     // the mask level's side
layout(location = ISPM_EMIT_LOC_CAPACITY) uniform uint u_capacity; // photons
layout(location = ISPM_EMIT_LOC_EYE) uniform vec3 u_eye;
layout(location = ISPM_EMIT_LOC_FORWARD) uniform vec3 u_forward;
// a ray-resolution pixel's side at depth 1
layout(location = ISPM_EMIT_LOC_PIXEL_SCALE) uniform float u_pixel_scale;
layout(location = ISPM_EMIT_LOC_TMIN_FLOOR) uniform float u_tmin_floor;  // scene units

int light_of_face(int face)
{
    int lights = int(lv_data[0].x);
    for (int i = 0; i < lights; i++) {
        int first = lv_first_face(i), count = lv_kind(i) == GIB_LV_KIND_CUBE ? 6 : 1;
        if (face >= first && face < first + count)
            return i;
    }
    return -1;
}

void main()
{
    ivec3 p = ivec3(gl_GlobalInvocationID);
    if (p.x >= u_res_l || p.y >= u_res_l)
        return;
    if (texelFetch(u_mask, p, u_level).r < 1.0)
        return;
    int li = light_of_face(p.z);
    if (li < 0)
        return;
    uint slot = uint((p.z * u_res_l + p.y) * u_res_l + p.x);
    vec4 r0 = rnd[2u * slot], r1 = rnd[2u * slot + 1u];
    int block = 1 << u_level;
    ivec3 t = ivec3(p.xy * block + min(ivec2(r0.xy * float(block)), ivec2(block - 1)), p.z);
    vec4 pos = texelFetch(lv_position, t, 0);
    vec4 nrm = texelFetch(lv_normal, t, 0);
    vec4 spec = texelFetch(lv_specular, t, 0);
    if (pos.w < 0.5 || nrm.w < 0.5)
        return;
    // The flux reaching the texel, as light_view.frag computes it (FLUX is rho_d times it).
    Light L = lights[li];
    float s = lv_texel(li);
    vec3 flux_in, win;
    float dist0 = 0.0, footprint;
    if (lv_kind(li) == GIB_LV_KIND_ORTHO) {
        win = L.direction_exponent.xyz;
        flux_in = L.intensity_outer.rgb * (s * s);
        footprint = -s * s * float(block * block);
    } else {
        vec3 rel = pos.xyz - lv_origin(li);
        dist0 = length(rel);
        win = rel / max(dist0, 1e-30);
        float c = dot(win, lv_axis(p.z));
        vec3 wi;
        float d;
        vec3 E = light_eval(L, pos.xyz, wi, d);
        flux_in = E * (d * d) * (s * s * c * c * c);
        footprint = s * s * c * c * c * float(block * block);
    }
    flux_in *= float(block * block);
    vec3 rho_d = texelFetch(lv_flux, t, 0).rgb / max(flux_in / float(block * block), vec3(1e-30));
    vec3 rho_s = spec.rgb;
    float pr = max(rho_d.r + rho_s.r, max(rho_d.g + rho_s.g, rho_d.b + rho_s.b));
    float sd = rho_d.r + rho_d.g + rho_d.b, ss = rho_s.r + rho_s.g + rho_s.b;
    float pd = sd + ss > 0.0 ? sd / (sd + ss) * pr : 0.0;
    float ps = pr - pd;
    if (!(r0.z > pd && r0.z <= pd + ps) || ps <= 0.0)
        return; // diffuse (not this technique's light) or absorbed
    vec3 flux = flux_in * rho_s / ps;
    vec3 n = normalize(nrm.xyz);
    vec3 r = reflect(win, n);
    vec3 d = r;
    if (nrm.w > 1.5) {
        float w;
        if (!sample_phong(r, n, spec.w, r0.w, r1.x, d, w))
            return;
        flux *= w;
    }
    if (max(flux.r, max(flux.g, flux.b)) <= 0.0)
        return;
    uint k = atomicAdd(cmd[1], 1u);
    if (k >= u_capacity) {
        atomicAdd(photon_overflow, 1u);
        return;
    }
    atomicAdd(cmd[4], 1u);
    // t_min (Sec. 3.3.2.2, Fig. 3.11: self-intersection): two ray-resolution pixels at the
    // origin's depth, where neighbouring list nodes of the same curved surface can still be met,
    // and never under 1e-4 of the scene's diagonal.
    float z0 = max(dot(pos.xyz - u_eye, u_forward), 0.0);
    float tmin = max(u_tmin_floor, 2.0 * z0 * u_pixel_scale);
    photons[k].origin = vec4(pos.xyz, dist0);
    photons[k].dir = vec4(d, tmin);
    photons[k].flux = vec4(flux, footprint);
    photons[k].hit = vec4(0.0);
    photons[k].hit_n = vec4(0.0);
}
