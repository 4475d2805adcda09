// gibench - the LRSM constants the C math (lrsm_math.c) and the shaders (lrsm_common.glsl) share,
// for C and GLSL alike: only #define lines and // comments, valid in both languages.
#ifndef LRSM_SHARED_H
#define LRSM_SHARED_H

// lrsm_area_weight: <n.l> below which a texel's Jacobian 1 / <n.l> stops growing (a surface lit at
// grazing counts up to 1 / 0.1 times a face-on one, not without bound).
#define LRSM_JACOBIAN_COS 0.1

#endif
