// gibench technique `lrsm` — the math of layered reflective shadow maps (Sugihara et al. 2014),
// line for line the CPU mirror techniques/lrsm/lrsm_math.c (the unit tests check that one), and the
// per-light partition table both the construction pass and the cone passes read.
#include "lrsm/lrsm_slots.h"
#include "lrsm/lrsm_shared.h"
#include "common/light_view_shared.h"

// Per light i: lrsm_table[i] = (z0, z1, delta, 0): the light view's depth range over the scene
// bounds and the overlap band's width (lrsm_math.h, "Static depth partitions").
layout(std430, binding = LRSM_SSBO_TABLE) readonly buffer LrsmTable { vec4 lrsm_table[]; };
layout(location = LRSM_LOC_DEPTH_PARTS) uniform int u_depth_parts;  // D
layout(location = LRSM_LOC_NORMAL_PARTS) uniform int u_normal_parts; // N

const float LRSM_MIN_VARIANCE = 1.0 / 32768.0;
// The least <n.l> the widened Eq. 12 window divides by (lrsm_sample.glsl, u_visibility 1): a
// surface lit at grazing (84 degrees) has a window 10 r_c deep at most.
const float LRSM_MIN_COS_NL = 0.1;

// erf by Abramowitz and Stegun 7.1.26, |error| < 1.5e-7.
float lrsm_erf(float x)
{
    float s = x < 0.0 ? -1.0 : 1.0, a = abs(x);
    float t = 1.0 / (1.0 + 0.3275911 * a);
    float y = ((((1.061405429 * t - 1.453152027) * t + 1.421413741) * t - 0.284496736) * t +
               0.254829592) * t;
    return s * (1.0 - y * exp(-a * a));
}

float lrsm_phi(float x) { return 0.5 * (1.0 + lrsm_erf(x * 0.70710678118654752)); }

// Eq. 12 in closed form.
float lrsm_visibility(float zc, float rc, float mu, float sigma2)
{
    float sigma = sqrt(max(sigma2, LRSM_MIN_VARIANCE));
    return lrsm_phi((zc + rc - mu) / sigma) - lrsm_phi((zc - rc - mu) / sigma);
}

// The cap cosine, a plane's share of a sample's rays and a layer's plane spread (parameter hits;
// lrsm_math.h says what each is).
float lrsm_cap_cosine(float cos_axis, float sin_axis, float sin_half)
{
    float a = cos_axis, b = sin_half * sin_axis;
    if (b < 1e-6)
        return max(a, 0.0);
    float u = -a / b;
    if (u <= -1.0)
        return a;
    if (u >= 1.0)
        return 0.0;
    float w = sqrt(1.0 - u * u);
    return 0.63661977 * (a * (0.78539816 - 0.5 * (u * w + asin(u))) + b * w * w * w / 3.0);
}

float lrsm_plane_hits(float delta, float E, float rc, float step, float sigma2_delta)
{
    float h = step * rc * E;
    float S = sqrt(0.25 * rc * rc * max(1.0 - E * E, 0.0) + sigma2_delta + 1e-8 * rc * rc);
    return lrsm_phi((h - delta) / S) - lrsm_phi((-h - delta) / S);
}

float lrsm_plane_spread(float var, float cos_nl, float rc)
{
    return max(var * cos_nl * cos_nl - rc * rc * (1.0 - cos_nl * cos_nl) / 3.0, 0.0);
}

float lrsm_smooth(float t)
{
    t = clamp(t, 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

void lrsm_layer_range(int light, int d, out float zmin, out float zmax)
{
    vec4 e = lrsm_table[light];
    float w = (e.y - e.x) / float(u_depth_parts);
    zmin = e.x + float(d) * w - 0.5 * e.z;
    zmax = e.x + float(d + 1) * w + 0.5 * e.z;
}

bool lrsm_in_depth_layer(int light, int d, float z)
{
    float lo, hi;
    lrsm_layer_range(light, d, lo, hi);
    return (d == 0 || z >= lo) && (d == u_depth_parts - 1 || z <= hi);
}

// Whether layer d's depth range meets [a, b] (outer ends open).
bool lrsm_layer_overlaps(int light, int d, float a, float b)
{
    float lo, hi;
    lrsm_layer_range(light, d, lo, hi);
    return (d == 0 || b >= lo) && (d == u_depth_parts - 1 || a <= hi);
}

// Eq. 15.
float lrsm_decay(int light, int d, float zc)
{
    if (!lrsm_in_depth_layer(light, d, zc))
        return 0.0;
    float lo, hi;
    lrsm_layer_range(light, d, lo, hi);
    float delta = lrsm_table[light].z;
    if (delta <= 0.0)
        return 1.0;
    if (d > 0 && zc < lo + delta)
        return lrsm_smooth((zc - lo) / delta);
    if (d < u_depth_parts - 1 && zc > hi - delta)
        return lrsm_smooth((hi - zc) / delta);
    return 1.0;
}

float lrsm_area_weight(int kind, float z, float zfar, float cos_face, float cosnl)
{
    float tilt = cosnl > LRSM_JACOBIAN_COS ? LRSM_JACOBIAN_COS / cosnl : 1.0;
    if (kind == GIB_LV_KIND_ORTHO)
        return tilt;
    float r = z / zfar;
    return r * r * cos_face * cos_face * cos_face * tilt;
}

int lrsm_normal_part(float cosnl, int parts)
{
    if (!(cosnl > 0.0))
        return -1;
    return min(int(cosnl * float(parts)), parts - 1);
}
