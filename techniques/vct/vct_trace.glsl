// Cone tracing through the anisotropic voxels (Sugihara et al. 2014, Sec. 3.1, Eq. 1; Crassin et
// al. 2011). A cone is a sequence of sphere samples: at distance t (voxels) from its start the
// diameter is d = max(2 t tan(aperture / 2), 1) voxels, the mip level log2(d) (level 0 = the base
// voxels, level m >= 1 = anisotropic level m - 1, trilinear between levels), and the next sample
// is step_factor x d / 2 (the sample's radius) further. A sample of a cone of direction D is the
// three directional textures facing D's signs weighted by D^2 (Crassin et al. 2011, Sec. 4).
// Each sample's occlusion, pre-integrated over one voxel of its level (d voxels), is corrected to
// the step length (a' = 1 - (1 - a)^(step / d)), so the result does not depend on step_factor
// beyond the sampling itself; then Eq. 1 front to back.
#include "gl/bindings.h"
layout(location = GIB_LOC_VOXEL_FIRST + 0) uniform vec3 u_vct_origin;
layout(location = GIB_LOC_VOXEL_FIRST + 1) uniform float u_vct_size;
layout(location = GIB_LOC_VOXEL_FIRST + 2) uniform int u_vct_res;
layout(location = 7) uniform float u_step_factor;
layout(location = 8) uniform float u_start_offset; // voxels, along the surface normal
layout(binding = GIB_UNIT_VOXELS) uniform sampler3D u_base;          // radiance + occlusion
layout(binding = GIB_UNIT_OWN_FIRST) uniform sampler3D u_aniso[6];   // +x -x +y -y +z -z

float vct_voxel() { return u_vct_size / float(u_vct_res); }

vec4 vct_sample(vec3 uvw, vec3 D, float mip)
{
    vec3 w = D * D;
    float lod = max(mip - 1.0, 0.0);
    vec4 s = w.x * (D.x > 0.0 ? textureLod(u_aniso[0], uvw, lod) : textureLod(u_aniso[1], uvw, lod)) +
             w.y * (D.y > 0.0 ? textureLod(u_aniso[2], uvw, lod) : textureLod(u_aniso[3], uvw, lod)) +
             w.z * (D.z > 0.0 ? textureLod(u_aniso[4], uvw, lod) : textureLod(u_aniso[5], uvw, lod));
    if (mip < 1.0)
        s = mix(textureLod(u_base, uvw, 0.0), s, max(mip, 0.0));
    return s;
}

// Radiance gathered (rgb) and occlusion (a) along the cone from p (offset along n) in direction
// D, with sample centres up to max_dist (world units) away. A shadow cone toward a point
// light (taper = 1) narrows again toward the light, d = 2 tan(a/2) min(t, t_light - t): a point
// light casts its penumbra from the receiver's side only, and a full-width sample at the light
// would take the surfaces next to it (a light under a ceiling) for occluders; it also stops
// start_offset voxels before the light, as it starts that far off the surface.
vec4 vct_cone_ex(vec3 p, vec3 n, vec3 D, float tan_half, float max_dist, bool taper)
{
    float vs = vct_voxel();
    vec3 o = p + n * (u_start_offset * vs);
    float tmax = max_dist / vs - (taper ? u_start_offset : 0.0);
    vec3 I = vec3(0.0);
    float A = 0.0;
    float t = 0.0;
    for (int i = 0; i < 1024 && A < 0.995; i++) {
        float d = max(2.0 * (taper ? min(t, tmax - t) : t) * tan_half, 1.0);
        if (t > tmax)
            break;
        vec3 uvw = (o + D * (t * vs) - u_vct_origin) / u_vct_size;
        if (any(lessThan(uvw, vec3(0.0))) || any(greaterThan(uvw, vec3(1.0))))
            break;
        vec4 s = vct_sample(uvw, D, log2(d));
        float dt = u_step_factor * 0.5 * d;
        float a = 1.0 - pow(clamp(1.0 - s.a, 0.0, 1.0), dt / d);
        vec3 c = s.a > 1e-6 ? s.rgb * (a / s.a) : vec3(0.0);
        I += (1.0 - A) * c;
        A += (1.0 - A) * a;
        t += dt;
    }
    return vec4(I, A);
}
vec4 vct_cone(vec3 p, vec3 n, vec3 D, float tan_half, float max_dist)
{
    return vct_cone_ex(p, n, D, tan_half, max_dist, false);
}

// The 6 diffuse cones: one along n and five around it tilted 60 degrees, 72 degrees apart; a
// 60-degree cone's cosine-weighted share of the hemisphere is sin^2(30) = 0.25 along n, and the
// other five share the remaining 0.75.
vec3 vct_diffuse_dir(int i, vec3 n)
{
    if (i == 0)
        return n;
    vec3 t, b;
    ortho_basis(n, t, b);
    float phi = 6.28318530718 * float(i - 1) / 5.0;
    return normalize(0.5 * n + 0.8660254 * (cos(phi) * t + sin(phi) * b));
}
float vct_diffuse_weight(int i) { return i == 0 ? 0.25 : 0.15; }
