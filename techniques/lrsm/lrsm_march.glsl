// How an lrsm cone marches through the occlusion voxels (Sec. 3.1, Eq. 1; common/voxel_cone.glsl),
// for the cone passes (lrsm_cone.frag) and the probe (lrsm_cone_probe.comp): from x + n start_offset
// voxels, sphere samples of diameter d = max(voxel, 2 t tan(a/2)) at distance t from one voxel on,
// t advancing by step_factor d (1: spheres that touch, Fig. 4), until the sample leaves the grid or
// passes max_distance grid sides. A sample stays in front of the receiver's plane: its diameter at
// most its centre's height above that plane (lrsm_cone.frag says why).
#include "lrsm/lrsm_slots.h"
layout(location = LRSM_CONE_LOC_START_OFFSET) uniform float u_start_offset; // voxels
layout(location = LRSM_CONE_LOC_STEP_FACTOR) uniform float u_step_factor;
layout(location = LRSM_CONE_LOC_MAX_DISTANCE) uniform float u_max_distance; // grid sides

struct LrsmCone {
    vec3 q, n, dir;   // start, the receiver's normal, direction
    float tan_half, tmax, t;
};

LrsmCone lrsm_cone_start(vec3 x, vec3 n, vec3 dir, float aperture)
{
    float vs = voxel_size_world();
    return LrsmCone(x + n * (u_start_offset * vs), n, dir, tan(0.5 * aperture),
                    u_max_distance * u_voxel_size, vs);
}

// The current sample's centre c and diameter d (world units); false once the cone has passed its
// length or its sample has left the grid.
bool lrsm_cone_sample(LrsmCone k, out vec3 c, out float d)
{
    float vs = voxel_size_world();
    d = max(vs, 2.0 * k.t * k.tan_half);
    d = min(d, max(u_start_offset * vs + k.t * dot(k.dir, k.n), vs));
    c = k.q + k.dir * k.t;
    return k.t < k.tmax && !any(lessThan(c, u_voxel_origin - d)) &&
           !any(greaterThan(c, u_voxel_origin + u_voxel_size + d));
}

void lrsm_cone_advance(inout LrsmCone k, float d) { k.t += u_step_factor * d; }
