// The injection's sums to averages (vct_inject.vert): radiance = sum(w L) / sum(w), alpha 1 where
// light landed (a lit surface is there); normal = the normalised sum of w n, w = 1 there.
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
layout(binding = 0, rgba16f) uniform image3D u_radiance;
layout(binding = 1, rgba16f) uniform image3D u_normal;
void main()
{
    ivec3 c = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(c, imageSize(u_radiance))))
        return;
    vec4 r = imageLoad(u_radiance, c);
    if (!(r.a > 0.0))
        return;
    vec3 n = imageLoad(u_normal, c).xyz;
    float len = length(n);
    imageStore(u_radiance, c, vec4(r.rgb / r.a, 1.0));
    imageStore(u_normal, c, vec4(len > 0.0 ? n / len : vec3(0.0), 1.0));
}
