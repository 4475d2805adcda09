// One triangle covering the viewport; v_texcoord in [0,1] over the screen (GL rows bottom up).
out vec2 v_texcoord;
void main()
{
    vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
    v_texcoord = p;
    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
