// Cone tracing through the anisotropic voxels (Sugihara et al. 2014, Sec. 3.1, Eq. 1; Crassin et
// al. 2011), with the grid, the 6 diffuse cones and the sampling conventions of the occlusion
// voxels (common/voxel_cone.glsl; u_voxels is bound to the base radiance + occlusion here). A cone
// is a sequence of sphere samples: at distance t (voxels) the diameter is
// d = max(2 t tan(aperture / 2), 1) voxels, the mip level log2(d) (level 0 = the base voxels,
// level m >= 1 = anisotropic level m - 1, trilinear between levels), and the next sample is
// step_factor x d further (spheres that touch, Fig. 4). A sample of a cone of direction D is the
// three directional textures facing D's signs weighted by D^2 (Crassin et al. 2011, Sec. 4). Its
// occlusion, pre-integrated over one cell of the level it is read from (c voxels), is corrected to
// the step, a' = 1 - (1 - a)^(step_factor d / c), and its premultiplied radiance scaled alike;
// then Eq. 1 front to back.
//
// The level read: u_level_bias levels finer than the paper's log2(d) (vct's `sample_level`). At
// the paper's level the trilinear footprint spans up to two cells, 2d, and the first samples reach
// into the receiver's own cells (pre-integrated as seen from outside, opaque along +n): a cone over
// open ground reads its opacity from the ground it leaves. One level finer (bias 1, the default)
// the footprint is the sample's own width, and the step crosses 2 cells.
// A sample's data is also kept in front of the receiver's plane: a cone tilted toward the plane
// would otherwise read the receiver, the lit ground around it and, through a wall, the other
// side's light. At level log2(d) - 1 the cells are c = d/2 wide and the fetch's data reaches
// 1.5 c = 0.75 d from the centre. `clearance` 0 shrinks the sample to d <= h, its centre's height
// above the plane (h/4 clear; d <= 2 h, the sphere alone clear, reads behind it). That narrows a
// tilted cone to half its width, so it reads the light around its axis, not the cap its weight
// stands for: `clearance` 1 (the default) keeps the width and lifts the sample along n. The two
// levels a fractional level blends are fetched apart, each lifted until 1.5 of its own cells
// (2^level wide) clear the plane, and mixed by the level's fraction: one lift for both either lets
// the coarser level read a lit floor's own cells (the level's width) or jumps as the level crosses
// an integer (the coarser level's cells). PERFORMANCE.md, "Quality behind the voxel techniques'
// defaults" and "The lift of each level", has the measurements.
#include "common/voxel_cone.glsl"
#include "vct/vct_slots.h"
layout(location = VCT_LOC_STEP_FACTOR) uniform float u_step_factor;
// voxels, along the surface normal
layout(location = VCT_LOC_START_OFFSET) uniform float u_start_offset;
layout(location = VCT_LOC_LEVEL_BIAS) uniform float u_level_bias;   // levels finer than log2(d)
// How a sample is kept in front of the receiver's plane: 0 its diameter at most its height, 1 lifted
layout(location = VCT_LOC_CLEARANCE) uniform int u_clearance;
layout(binding = VCT_UNIT_ANISO_FIRST) uniform sampler3D u_aniso[6];   // +x -x +y -y +z -z
layout(binding = VCT_UNIT_LOBE_FIRST) uniform sampler3D u_lobe[3];     // per axis (Y+, P+, Y-, P-)
layout(location = VCT_LOC_FRONT_FACES) uniform int u_front_faces;

vec4 vct_sample(vec3 uvw, vec3 D, float mip)
{
    vec3 w = D * D;
    float lod = max(mip - 1.0, 0.0);
    vec4 s = w.x * (D.x > 0.0 ? textureLod(u_aniso[0], uvw, lod) : textureLod(u_aniso[1], uvw, lod)) +
             w.y * (D.y > 0.0 ? textureLod(u_aniso[2], uvw, lod) : textureLod(u_aniso[3], uvw, lod)) +
             w.z * (D.z > 0.0 ? textureLod(u_aniso[4], uvw, lod) : textureLod(u_aniso[5], uvw, lod));
    if (mip < 1.0)
        s = mix(textureLod(u_voxels, uvw, 0.0), s, max(mip, 0.0));
    return s;
}

// The share of a sample's light that leaves its surfaces on the side of the cone's apex (vct's
// `front_faces` 1, the default), from the emission lobes (vct_lobes.comp). The anisotropic mips
// cannot tell the sides of a surface apart (a wall's lit face is seen edge-on from either side),
// so a cone on the dark side of a wall thinner than a cell would read the lit side's light
// (thick_wall_leak). A lobe counts in full while the apex is in front of its back-most plane b and
// fades out within 1/FRONT_GAIN (about 1/8 radian, no seam at the plane); each lobe is weighted by
// the share of the D^2 blend that shows it (not its own axis's texture when the cone travels the
// way it faces: vct_aniso.comp hides it there). 1 where no lit surface is there.
const float FRONT_GAIN = 8.0;
float vct_front_share(vec3 uvw, float lod, vec3 apex_uvw, vec3 D)
{
    float lit = 0.0, front = 0.0;
    float dist = max(length(uvw - apex_uvw), 0.5 / float(u_voxel_res));
    for (int k = 0; k < 3; k++) {
        vec4 l = textureLod(u_lobe[k], uvw, lod);
        for (int h = 0; h < 2; h++) {
            float y = h == 0 ? l.x : l.z, s = h == 0 ? 1.0 : -1.0;
            if (y <= 1e-9)
                continue;
            float back = (h == 0 ? l.y : l.w) / y;  // the lobe's back-most plane
            float shown = y * (1.0 - (s * D[k] > 0.0 ? D[k] * D[k] : 0.0));
            lit += shown;
            front += shown * clamp(1.0 + FRONT_GAIN * s * (apex_uvw[k] - back) / dist, 0.0, 1.0);
        }
    }
    return lit > 1e-9 ? front / lit : 1.0;
}

// The sample centred at `at` (world) read at a fractional `level`: the two levels it blends,
// each lifted along n (with `lift`) until 1.5 of its own cells (times the receiver's layer for a
// tapered cone) clear the receiver's plane, h voxels below the centre, and mixed by the fraction.
// rgb: the premultiplied light, scaled by the front share where front_faces is on; a: the opacity.
vec4 vct_lifted_sample(vec3 at, vec3 n, float h, float level, vec3 D, vec3 apex_uvw, bool lift,
                       bool taper)
{
    float fine = floor(level), vs = voxel_size_world();
    vec4 s = vec4(0.0);
    for (int k = 0; k < 2; k++) {
        float w = k == 0 ? 1.0 - (level - fine) : level - fine, lv = fine + float(k);
        if (w <= 0.0)
            continue;
        float reach = 1.5 * exp2(lv) * (taper ? receiver_layer(n) : 1.0);
        float up = lift ? max(reach - h, 0.0) : 0.0;
        vec3 uvw = (at + n * (up * vs) - u_voxel_origin) / u_voxel_size;
        vec4 sk = vct_sample(uvw, D, lv);
        float share = u_front_faces != 0 ? vct_front_share(uvw, max(lv - 1.0, 0.0), apex_uvw, D)
                                         : 1.0;
        s += w * vec4(sk.rgb * share, sk.a);
    }
    return s;
}

// Radiance gathered (rgb) and occlusion (a) along the cone from p (offset start_offset voxels
// along n) in direction D, sample centres up to max_dist (world units) away, the first one voxel
// out, as in shadow_cone. The cone stops once its sphere has left the grid. Beyond the grid the
// scene is empty: the textures clamp to a transparent border, so a sample partly outside reads the
// part inside (edge-clamped, they would repeat the outer cells as lit half-planes; PERFORMANCE.md,
// "The voxel grid's margin"); the grid's margin (common/voxels.c) keeps walls off the outer cells.
// A shadow cone toward a point light (taper) narrows again toward it and stops start_offset +
// TAPER_STOP voxels before it, and its lift clears the receiver's voxel layer, |n|_1 times the
// reach, both as shadow_cone_ex (voxel_cone.glsl says why). The diffuse cones lift by the reach
// alone, which scores better for them.
vec4 vct_cone_ex(vec3 p, vec3 n, vec3 D, float tan_half, float max_dist, bool taper)
{
    float vs = voxel_size_world();
    vec3 o = p + n * (u_start_offset * vs);
    vec3 apex_uvw = (o - u_voxel_origin) / u_voxel_size;
    float tmax = max_dist / vs - (taper ? u_start_offset + TAPER_STOP : 0.0);
    vec3 I = vec3(0.0);
    float A = 0.0;
    float t = 1.0, t_prev = 0.0;
    for (int i = 0; i < 1024 && A < 0.995; i++) {
        // The share of this sample's step inside the cone's length: the last sample fades out
        // as the steps move rather than drops whole.
        float part = t <= tmax ? 1.0 : taper ? 0.0 : (tmax - t_prev) / (t - t_prev);
        if (part <= 0.0)
            break;
        float d = max(cone_diameter(t, tmax, tan_half, taper), 1.0);
        float h = u_start_offset + t * dot(D, n); // the centre's height above the plane
        bool lift = u_clearance == 1;
        d = lift ? d : min(d, max(h, 1.0));
        vec3 at = o + D * (t * vs), centre = (at - u_voxel_origin) / u_voxel_size;
        float r = 0.5 * d / float(u_voxel_res);
        if (any(lessThan(centre, vec3(-r))) || any(greaterThan(centre, vec3(1.0 + r))))
            break; // the sphere has left the grid
        float level = max(log2(d) - u_level_bias, 0.0);
        vec4 s = vct_lifted_sample(at, n, h, level, D, apex_uvw, lift, taper);
        float a = 1.0 - pow(clamp(1.0 - s.a, 0.0, 1.0), part * u_step_factor * d / exp2(level));
        vec3 c = s.a > 1e-6 ? s.rgb * (a / s.a) : vec3(0.0);
        I += (1.0 - A) * c;
        A += (1.0 - A) * a;
        if (part < 1.0)
            break;
        t_prev = t;
        t += u_step_factor * d;
    }
    return vec4(I, A);
}

vec4 vct_cone(vec3 p, vec3 n, vec3 D, float tan_half, float max_dist)
{
    return vct_cone_ex(p, n, D, tan_half, max_dist, false);
}
