// Injection: the point's weighted radiance and normal, summed by additive blending.
in vec4 v_radiance;
in vec4 v_normal;
layout(location = 0) out vec4 o_radiance;
layout(location = 1) out vec4 o_normal;
void main()
{
    o_radiance = v_radiance;
    o_normal = v_normal;
}
