// The light views' table (techniques/common/light_view.c): for light i, which layers of the
// light-view arrays hold its faces and how a point projects into them.
//   lv_data[0]             x = lights, y = faces, z = resolution
//   lv_data[1 + 2i]        x = first face, y = kind (GIB_LV_KIND_*), z = texel
//                          (side on the unit-distance plane; ortho: world units)
//   lv_data[2 + 2i]        xyz = origin (the light; ortho: the plane behind the scene)
//   lv_data[1 + 2L + 7f]   4 columns of face f's view-projection (of p - origin), then its axis,
//                          right and up vectors (a texel's steps in x and y)
#include "gl/bindings.h"
#include "common/light_view_shared.h"
layout(std430, binding = GIB_SSBO_LIGHT_VIEWS) readonly buffer LightViews { vec4 lv_data[]; };

int lv_res() { return int(lv_data[0].z); }
int lv_first_face(int i) { return int(lv_data[1 + 2 * i].x); }
int lv_kind(int i) { return int(lv_data[1 + 2 * i].y); }
float lv_texel(int i) { return lv_data[1 + 2 * i].z; }
vec3 lv_origin(int i) { return lv_data[2 + 2 * i].xyz; }
int lv_face_base(int face) { return 1 + 2 * int(lv_data[0].x) + 7 * face; }
vec3 lv_axis(int face) { return lv_data[lv_face_base(face) + 4].xyz; }
vec3 lv_right(int face) { return lv_data[lv_face_base(face) + 5].xyz; }
vec3 lv_up(int face) { return lv_data[lv_face_base(face) + 6].xyz; }
mat4 lv_view_proj(int face)
{
    int b = lv_face_base(face);
    return mat4(lv_data[b], lv_data[b + 1], lv_data[b + 2], lv_data[b + 3]);
}

// The face of light i whose view holds direction d (from the origin): a cube's by d's major axis.
int lv_face(int i, vec3 d)
{
    int f = lv_first_face(i);
    if (lv_kind(i) != GIB_LV_KIND_CUBE)
        return f;
    vec3 a = abs(d);
    if (a.x >= a.y && a.x >= a.z)
        return f + (d.x >= 0.0 ? 0 : 1);
    if (a.y >= a.z)
        return f + (d.y >= 0.0 ? 2 : 3);
    return f + (d.z >= 0.0 ? 4 : 5);
}

// Texture coordinates (xy) and layer (z) of the point at `rel` from the origin in face `face`.
vec3 lv_project(int face, vec3 rel)
{
    vec4 c = lv_view_proj(face) * vec4(rel, 1.0);
    return vec3(c.xy / c.w * 0.5 + 0.5, float(face));
}
