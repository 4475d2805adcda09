// Horizon-based ambient occlusion (Bavoil, Sainz and Dimitrov 2008), evaluated on the G-buffer.
//
// For each pixel, N_d screen directions (rotated by a per-pixel hash) each define a slice: the
// plane through the eye that contains the pixel's view ray and the screen line. In the slice we
// find the tangent angle t of the surface (from the G-buffer normal, plus the angle bias) and march
// N_s texel-snapped steps (first step jittered per pixel) out to the projection of R = d_max,
// raising the horizon angle h whenever a sample within R lies above it. Occlusion accumulates per
// horizon rise, weighted by the attenuation W(r) at the sample (Bavoil et al.'s per-sample form):
//     AO = 1 - (1/N_d) sum_dirs sum_rises W(r) (sin h_new - sin h_old),
// which with W = 1 telescopes to 1 - (1/N_d) sum (sin h - sin t).
//
// Angles are elevations above the plane perpendicular to the pixel's view ray V (not the image
// plane, as in the original): for a symmetric perspective with square pixels every screen line
// through the pixel lies in a plane through the eye that contains V, so the slices are exact at any
// field of view. Samples are texel-snapped and so fall slightly off their slice; each sample's
// elevation is therefore measured from the tangent of its own slice and carried over (see below),
// which keeps flat receivers free of self-occlusion without relying on the angle bias. All vectors
// are in world space (the G-buffer holds world positions); the camera axes give the screen
// directions. The uniform solid-angle weighting (no cosine) is Bavoil et al.'s definition.
#include "hbao/hbao_slots.h"
layout(binding = GIB_UNIT_GBUF_POSITION) uniform sampler2D g_position;
layout(binding = GIB_UNIT_GBUF_NORMAL) uniform sampler2D g_normal;
layout(location = HBAO_LOC_EYE) uniform vec3 u_eye;
layout(location = HBAO_LOC_RIGHT) uniform vec3 u_right;    // world direction of screen +x
// world direction of screen +y (GL rows bottom up)
layout(location = HBAO_LOC_UP) uniform vec3 u_up;
layout(location = HBAO_LOC_FORWARD) uniform vec3 u_forward;  // viewing direction
// pixels per unit of (lateral offset / depth)
layout(location = HBAO_LOC_FOCAL_PX) uniform float u_focal_px;
layout(location = HBAO_LOC_RADIUS) uniform float u_radius;   // R = d_max, world units
layout(location = HBAO_LOC_DIRS) uniform int u_dirs;
layout(location = HBAO_LOC_STEPS) uniform int u_steps;
layout(location = HBAO_LOC_BIAS) uniform float u_bias;     // tangent angle bias, radians
// 1: W = 1 - r^2/R^2, 0: W = 1 inside R
layout(location = HBAO_LOC_FALLOFF) uniform int u_falloff;
layout(location = HBAO_LOC_MAX_RADIUS_PX) uniform float u_max_radius_px; // 0: no clamp
// 1: write (ao, ao, ao, 1), 0: write ao to R only
layout(location = HBAO_LOC_FINAL) uniform int u_final;
layout(location = 0) out vec4 o_ao;

const float TWO_PI = 6.28318530717959;
const float HALF_PI = 1.57079632679490;

// Integer hash of Jarzynski and Olano 2020 ("Hash functions for GPU rendering", pcg): a pure
// function of the pixel, so every frame is bit-identical.
uint pcg_hash(uint v)
{
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

// Elevation (from the plane perpendicular to V) of the surface's tangent in the slice spanned by V
// and the unit direction u perpendicular to V. N.V > 0 (viewer-facing normal), so |t| < pi/2.
float tangent_angle(vec3 N, vec3 V, vec3 u)
{
    return atan(-dot(N, u), max(dot(N, V), 1e-6));
}

void emit(float ao)
{
    o_ao = u_final != 0 ? vec4(ao, ao, ao, 1.0) : vec4(ao, 0.0, 0.0, 0.0);
}

void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    ivec2 size = textureSize(g_position, 0);
    vec4 pos = texelFetch(g_position, px, 0);
    if (pos.w < 0.5) { // nothing hit: AO is defined as 0 there (ARCHITECTURE.md)
        emit(0.0);
        return;
    }
    vec3 P = pos.xyz;
    vec3 N = normalize(texelFetch(g_normal, px, 0).xyz);
    vec3 Pe = P - u_eye;
    float depth = dot(Pe, u_forward);
    vec3 V = -normalize(Pe);
    float r_px = u_radius * u_focal_px / depth;
    if (u_max_radius_px > 0.0)
        r_px = min(r_px, u_max_radius_px);
    // A kernel under one pixel reaches no neighbour: nothing can be found, as in the original.
    if (!(r_px >= 1.0)) {
        emit(1.0);
        return;
    }
    uint h1 = pcg_hash(uint(px.x) + pcg_hash(uint(px.y)));
    uint h2 = pcg_hash(h1);
    float rotation = float(h1 >> 8) * (1.0 / 16777216.0); // [0, 1)
    float jitter = float(h2 >> 8) * (1.0 / 16777216.0);
    float R2 = u_radius * u_radius;
    float step_px = (r_px - 1.0) / float(u_steps);
    float occlusion = 0.0;
    for (int i = 0; i < u_dirs; i++) {
        float phi = TWO_PI * (float(i) + rotation) / float(u_dirs);
        vec2 d = vec2(cos(phi), sin(phi));
        vec3 dw = d.x * u_right + d.y * u_up; // the screen direction as a world direction
        // The slice through the eye, P and the screen line contains V; u is its direction
        // perpendicular to V that moves the projection along +d. The surface's tangent in the
        // slice, T = cos(t) u + sin(t) V with N.T = 0, gives tan t = -(N.u) / (N.V).
        vec3 u = normalize(dw - dot(dw, V) * V);
        float t = tangent_angle(N, V, u);
        float sin_h = sin(min(t + u_bias, HALF_PI));
        for (int j = 0; j < u_steps; j++) {
            // Steps in [1, r_px) pixels, snapped to texel centres: interpolating positions across
            // a depth edge would invent surfaces that are not there.
            float s = 1.0 + (float(j) + jitter) * step_px;
            ivec2 q = ivec2(floor(gl_FragCoord.xy + d * s));
            if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size)))
                break; // off screen: the depth buffer knows nothing there
            vec4 sp = texelFetch(g_position, q, 0);
            if (sp.w < 0.5)
                continue;
            vec3 D = sp.xyz - P;
            float r2 = dot(D, D);
            if (r2 >= R2 || r2 <= 0.0)
                continue;
            float inv_r = inversesqrt(r2);
            float sin_a = dot(D, V) * inv_r;
            // Snapping moves the sample off the slice (by up to half a texel, i.e. tens of
            // degrees of azimuth for the first steps), and on an oblique receiver the tangent
            // angle changes fast with azimuth: a sample lying on the receiver itself would rise
            // above t. So the elevation is measured from the tangent of the sample's own slice
            // and carried over to this slice: a = t + (a_s - t_s).
            vec3 a_dir = D * inv_r - sin_a * V;
            float la = length(a_dir);
            if (la > 1e-6)
                sin_a = sin(min(t + asin(clamp(sin_a, -1.0, 1.0)) -
                                tangent_angle(N, V, a_dir / la), HALF_PI));
            if (sin_a > sin_h) {
                float w = u_falloff != 0 ? 1.0 - r2 / R2 : 1.0;
                occlusion += w * (sin_a - sin_h);
                sin_h = sin_a;
            }
        }
    }
    emit(clamp(1.0 - occlusion / float(u_dirs), 0.0, 1.0));
}
