// gibench - the work-group sizes of the compute passes, one table for C and GLSL (both include
// this file: only #define lines and // comments, valid in both languages). A shader declares its
// layout(local_size_*) with these names; its dispatch divides by the same name (gib_groups,
// techniques/common/compute.h).
#ifndef GIB_GROUPS_SHARED_H
#define GIB_GROUPS_SHARED_H

#define GIB_GROUP_1D 64               // local_size_x: one invocation per item
#define GIB_GROUP_2D 8                // local_size_x = local_size_y: one invocation per texel
#define GIB_GROUP_3D 4                // local_size_x = _y = _z: one invocation per voxel

#endif
