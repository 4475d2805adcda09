// Cone tracing through the occlusion voxels (techniques/common/voxels.h), LRSM paper Sec. 3.1: a
// cone is a sequence of sphere samples; a sample of diameter d (in voxels) reads its integrated
// occlusion alpha from the voxel mip level log2(d), trilinearly (quadrilinear over the chain), and
// samples are accumulated front to back (Eq. 1). The techniques write their own radiance cones with
// these pieces; shadow_cone is Eq. 1 with L = 0 (only the transmittance). Apertures are full apex
// angles (a 60-degree cone has a 30-degree half-angle).
#include "gl/bindings.h"
#include "common/basis.glsl"

layout(binding = GIB_UNIT_VOXELS) uniform sampler3D u_voxels;
layout(location = GIB_LOC_VOXEL_ORIGIN) uniform vec3 u_voxel_origin;
layout(location = GIB_LOC_VOXEL_SIZE) uniform float u_voxel_size;  // grid side
layout(location = GIB_LOC_VOXEL_RES) uniform int u_voxel_res;
// How a sample's mean occupancy becomes the opacity of a cone step (voxel_step_alpha); 0 unless a
// pass sets it.
layout(location = GIB_LOC_VOXEL_DENSITY) uniform int u_voxel_density;

float voxel_size_world() { return u_voxel_size / float(u_voxel_res); }

// Alpha of a sphere sample of `diameter` (world units) centred at p (scene frame): the mean
// occupancy of the mip level log2(diameter in voxels) (Sec. 3.1), clamped to [0, top of the chain];
// samples smaller than a voxel read level 0. Outside the grid: 0 (the border).
float voxel_occlusion(vec3 p, float diameter)
{
    float top = float(textureQueryLevels(u_voxels) - 1);
    float mip = clamp(log2(max(diameter / voxel_size_world(), 1.0)), 0.0, top);
    return textureLod(u_voxels, (p - u_voxel_origin) / u_voxel_size, mip).r;
}

// Opacity of one cone step of length step_factor x d through a sphere sample of diameter d at p.
// u_voxel_density 0, the paper's reading (Sec. 3.1): the mip's mean occupancy per sample diameter,
//   1 - (1 - occ)^step_factor; a one-voxel wall in a sample d voxels wide reads occ ~ 1/d.
// u_voxel_density 1: the occupancy is a density (filled voxels per voxel of path), over the step's
//   step_factor d / voxel voxel lengths, read one level finer (diameter d/2) since a trilinear
//   fetch at level L spans 2^(L+1) voxels. A one-voxel wall then stops 1 - e^-2 of the cone per
//   sample at every level.
float voxel_step_alpha(vec3 p, float d, float step_factor)
{
    float occ = voxel_occlusion(p, u_voxel_density != 0 ? 0.5 * d : d);
    float lengths = u_voxel_density != 0 ? max(d / voxel_size_world(), 1.0) : 1.0;
    return 1.0 - pow(max(1.0 - occ, 0.0), step_factor * lengths);
}

// The 6 diffuse cones of 60 degrees (the set of Crassin et al. 2011 and most VCT code): one along n
// and five at 60 degrees from it, every 72 degrees in azimuth. A cone of half-angle a around an
// axis at angle t from n collects the cosine-weighted solid angle cos(t) pi sin^2(a): pi/4 for
// the central cone, pi/8 for each tilted one; normalised to sum to 1 (2/7 and 1/7), the gaps
// between caps go to the cones in proportion (the common 0.25 / 0.15 split overweights the ring).
const int DIFFUSE_CONES = 6;
const float DIFFUSE_TILT = 1.0471976;   // 60 degrees
int diffuse_cone_count() { return DIFFUSE_CONES; }
float diffuse_cone_weight(int i) { return i == 0 ? 2.0 / 7.0 : 1.0 / 7.0; }
// A technique's `cone` parameter: < 0 the gather of every cone; i alone with weight 1 (the
// per-cone images `gibench reference --cone i` renders the truth of). Set in diffuse passes only.
layout(location = GIB_LOC_VOXEL_CONE_ONLY) uniform int u_cone_only;
float diffuse_cone_share(int i)
{
    return u_cone_only < 0 ? diffuse_cone_weight(i) : (i == u_cone_only ? 1.0 : 0.0);
}
vec3 diffuse_cone_dir(int i, vec3 n)
{
    if (i == 0)
        return n;
    vec3 t, b;
    ortho_basis(n, t, b);
    float phi = float(i - 1) * 1.2566371;   // 72 degrees
    return normalize(cos(DIFFUSE_TILT) * n + sin(DIFFUSE_TILT) * (cos(phi) * t + sin(phi) * b));
}

// Visibility (0..1) along a cone from the surface point p (normal n) in direction dir over a
// distance dist: transmittance prod (1 - alpha_i) of Eq. 1 with L = 0. The start is offset
// `start_offset` voxels along n (the surface's own voxels would occlude it). Samples: diameter
// d = max(voxel, 2 t tan(aperture / 2)) at distance t, stepping by step_factor x d (1 = spheres that
// touch, as in Fig. 4), alpha from voxel_step_alpha. Stops when visibility < 1/256 or the sample
// leaves the grid.
// `taper` (a point or spot light dist away): the cone narrows again toward the light,
// d = max(voxel, 2 tan(aperture / 2) min(t, dist - t)), since a point light casts its penumbra from
// the receiver's side only; at full width the last samples reach the surfaces next to the light
// (a ceiling just above it) and take them for occluders, in rings around the light. It stops
// start_offset + TAPER_STOP voxels before the light, where its last sample's trilinear data no
// longer reaches the light's neighbours. vct's shadow cone tapers alike (vct_trace.glsl).
// A sample's data is kept clear of the receiver's own voxels: a surface of normal n occupies voxels
// whose centres lie within |n|_1 / 2 voxels of its plane (mips of cells c voxels wide: c |n|_1 / 2),
// and a trilinear fetch blends the cell centres within c of the sample on each axis, c |n|_1 along
// n; a sample whose centre is less than 1.5 c |n|_1 above the plane (c of the coarser of the two
// levels it blends) is lifted along n until it is, keeping its width (vct's `clearance` alike): a
// cone toward a light at grazing runs along its receiver for many samples, and would read it in
// stripes where the grid's columns cross the face.
// How many voxels beyond start_offset a tapered shadow cone stops short of its light: its last
// sample's trilinear data reaches 1.5 voxels.
const float TAPER_STOP = 1.5;

// A cone sample's diameter at t (before its floor of one voxel): 2 t tan(a/2), or, tapered toward a
// light at tmax, 2 min(t, tmax - t) tan(a/2).
float cone_diameter(float t, float tmax, float tan_half, bool taper)
{
    return 2.0 * (taper ? min(t, tmax - t) : t) * tan_half;
}

// How thick, along n, a surface's own voxel layer is in voxels: |n|_1 (a trilinear fetch reaches
// that far per cell along n).
float receiver_layer(vec3 n)
{
    vec3 an = abs(n);
    return an.x + an.y + an.z;
}

float shadow_cone_ex(vec3 p, vec3 n, vec3 dir, float dist, float aperture_rad, float step_factor,
                     float start_offset, bool taper)
{
    float voxel = voxel_size_world();
    float layer = receiver_layer(n);
    vec3 o = p + n * (start_offset * voxel);
    float tan_half = tan(0.5 * aperture_rad);
    float tmax = taper ? dist - (start_offset + TAPER_STOP) * voxel : dist;
    float visibility = 1.0;
    float t = voxel;
    for (int i = 0; i < 512 && t < tmax && visibility > 1.0 / 256.0; i++) {
        float d = max(voxel, cone_diameter(t, tmax, tan_half, taper));
        float cell = exp2(ceil(log2(max((u_voxel_density != 0 ? 0.5 : 1.0) * d / voxel, 1.0))));
        float h = start_offset * voxel + t * dot(dir, n);
        float up = max(1.5 * layer * cell * voxel - h, 0.0);
        vec3 q = o + dir * t + n * up;
        if (any(lessThan(q, u_voxel_origin - d)) || any(greaterThan(q, u_voxel_origin + u_voxel_size + d)))
            break; // left the grid: nothing further occludes
        visibility *= 1.0 - voxel_step_alpha(q, d, step_factor);
        t += step_factor * d;
    }
    return visibility;
}

float shadow_cone(vec3 p, vec3 n, vec3 dir, float dist, float aperture_rad)
{
    return shadow_cone_ex(p, n, dir, dist, aperture_rad, 1.0, 1.5, false);
}
