// multires_ir (the thesis, Sec. 3.2.2; Nichols, Shopf and Wyman 2009): the flattened image of all
// levels and the discontinuity test of Algorithm 3.1, shared by its passes (multires.h).
// Layout: level 0 (one pixel a region) at (0, 0), W x H; level k >= 1 (2^k x 2^k pixels a
// region, ceil(W / 2^k) x ceil(H / 2^k) regions) at x = W, stacked upward from y = 0.
// Min-max mips (per region): lo = (min n.x, n.y, n.z, min depth), hi = (max n, max depth), depth
// the distance to the camera (the thesis' linear depth), MR_FAR where no surface; mean = (mean
// position, surface pixels), nsum = (sum of normals, 0).
#include "multires_ir/multires_ir_slots.h"
layout(location = MULTIRES_LOC_SIZE) uniform ivec2 u_size;       // W, H
layout(location = MULTIRES_LOC_LEVELS) uniform int u_levels;
// relative: max - min > t x min
layout(location = MULTIRES_LOC_DEPTH_THRESHOLD) uniform float u_depth_threshold;
layout(location = MULTIRES_LOC_NORMAL_CHORD) uniform float u_normal_chord;     // 2 sin(theta / 2)
const float MR_FAR = 1e30;

ivec4 mr_rect(int k)
{
    if (k == 0)
        return ivec4(0, 0, u_size);
    int y = 0;
    for (int j = 1; j < k; j++)
        y += (u_size.y + (1 << j) - 1) >> j;
    return ivec4(u_size.x, y, (u_size + (1 << k) - 1) >> k);
}

// Level and region of an atlas texel; level -1 outside every level.
int mr_level(ivec2 a, out ivec2 region)
{
    for (int k = 0; k < u_levels; k++) {
        ivec4 r = mr_rect(k);
        if (all(greaterThanEqual(a, r.xy)) && all(lessThan(a, r.xy + r.zw))) {
            region = a - r.xy;
            return k;
        }
    }
    region = ivec2(0);
    return -1;
}

ivec2 mr_texel(int k, ivec2 region)
{
    return mr_rect(k).xy + region;
}

#ifdef MR_READ_MIPS
layout(binding = MULTIRES_UNIT_LO) uniform sampler2D mr_lo;
layout(binding = MULTIRES_UNIT_HI) uniform sampler2D mr_hi;
layout(binding = MULTIRES_UNIT_MEAN) uniform sampler2D mr_mean;
layout(binding = MULTIRES_UNIT_NSUM) uniform sampler2D mr_nsum;

bool mr_empty(int k, ivec2 region)
{
    return texelFetch(mr_lo, mr_texel(k, region), 0).w >= MR_FAR;
}

// discontinuity(r, i) of Algorithm 3.1: the depth range beyond the relative threshold (a region
// mixing surface and background has max depth MR_FAR: split), or a normal component's range beyond
// the chord of the angle threshold (two normals theta apart differ by at most 2 sin(theta/2) in
// any component, so a region whose normals lie within theta is never split by it).
bool mr_discontinuous(int k, ivec2 region)
{
    vec4 lo = texelFetch(mr_lo, mr_texel(k, region), 0);
    vec4 hi = texelFetch(mr_hi, mr_texel(k, region), 0);
    if (hi.w - lo.w > u_depth_threshold * lo.w)
        return true;
    return any(greaterThan(hi.xyz - lo.xyz, vec3(u_normal_chord)));
}

// Algorithm 3.1 with the rules the text leaves out: the coarsest level has no parent and is valid
// where continuous (as if the whole screen were split); a finest-level region is one pixel, never
// discontinuous, valid where its parent is split; regions without a surface are never valid.
// Depth and normal ranges only grow from a region to its parent, so along any pixel's chain of
// ancestors exactly one region is valid.
bool mr_valid(int k, ivec2 region)
{
    if (mr_empty(k, region) || mr_discontinuous(k, region))
        return false;
    return k == u_levels - 1 || mr_discontinuous(k + 1, region >> 1);
}

// A region whose data comes from its parent: continuous, and so is its parent.
bool mr_covered(int k, ivec2 region)
{
    if (k == u_levels - 1 || mr_empty(k, region) || mr_discontinuous(k, region))
        return false;
    return !mr_discontinuous(k + 1, region >> 1);
}
#endif
