// ispm_caustics (thesis 004, Sec. 3.3): what its shaders share. A photon, the camera's per-pixel
// linked lists (Algorithm 3.4's FragmentNode) and the Phong lobe sampler.
#include "ispm_caustics/ispm_caustics_slots.h"

// One photon, from its first (specular) hit in the light view to its second hit (std430, 80 bytes).
struct Photon {
    vec4 origin; // xyz: the point on the specular surface; w: distance from the light (0: ortho)
    vec4 dir;    // xyz: unit reflected direction; w: t_min, the self-intersection distance
    vec4 flux;   // rgb: flux carried (W); w: the footprint at the light (sr; ortho: -area m^2)
    vec4 hit;    // xyz: second hit; w: splat radius h (0: no hit, or dead)
    vec4 hit_n;  // xyz: the receiver's normal, facing the photon; w: cos of incidence
};

// Algorithm 3.4's node: depth, normal and next (12 bytes). The depth is the camera's linear depth
// (along its forward axis), negative for one-sided materials; the normal is the surface's own
// (not turned toward anyone), octahedral in two snorm16 (the thesis keeps two half floats of
// spherical angles; the octahedral map spreads the same 32 bits evenly over the sphere).
struct Node {
    float depth;
    uint normal;
    uint next;
};
const uint LIST_END = 0xffffffffu;

vec2 oct_wrap(vec2 v) { return (1.0 - abs(v.yx)) * vec2(v.x >= 0.0 ? 1.0 : -1.0, v.y >= 0.0 ? 1.0 : -1.0); }
uint oct_encode(vec3 n)
{
    n /= abs(n.x) + abs(n.y) + abs(n.z);
    vec2 e = n.z >= 0.0 ? n.xy : oct_wrap(n.xy);
    return packSnorm2x16(e);
}
vec3 oct_decode(uint u)
{
    vec2 e = unpackSnorm2x16(u);
    vec3 n = vec3(e, 1.0 - abs(e.x) - abs(e.y));
    if (n.z < 0.0)
        n.xy = oct_wrap(n.xy);
    return normalize(n);
}

// Orthonormal basis about unit z, robust for every z (Duff et al. 2017, "Building an orthonormal
// basis, revisited"); Algorithm 3.3's "parallel to Oy" test is replaced by it.
void onb(vec3 z, out vec3 x, out vec3 y)
{
    float s = z.z >= 0.0 ? 1.0 : -1.0;
    float a = -1.0 / (s + z.z);
    float b = z.x * z.y * a;
    x = vec3(1.0 + s * z.x * z.x * a, s * b, -s * z.x);
    y = vec3(b, s + z.y * z.y * a, -z.y);
}

// Sec. 3.3.1.2, Phong lobe about the mirror direction r: theta = arccos(xi1^(1/(n+1))),
// phi = 2 pi xi2 (the text's arccos(1/xi^(n+1)) is undefined for xi < 1), i.e. the pdf
// (n+1)/(2 pi) cos^n. Directions under the surface (d . normal <= 0) are rejected: returns false
// and the photon dies (resampling would bias the flux). weight = f cos / pdf / rho_s of the
// normalised Phong BRDF rho_s (n+2)/(2 pi) cos^n: (n+2)/(n+1) (d . normal).
bool sample_phong(vec3 r, vec3 normal, float n, float xi1, float xi2, out vec3 d, out float weight)
{
    float c = pow(xi1, 1.0 / (n + 1.0));
    float s = sqrt(max(0.0, 1.0 - c * c));
    float phi = 6.28318530717959 * xi2;
    vec3 x, y;
    onb(r, x, y);
    d = normalize(x * (s * cos(phi)) + y * (s * sin(phi)) + r * c);
    float cn = dot(d, normal);
    weight = (n + 2.0) / (n + 1.0) * cn;
    return cn > 0.0;
}
