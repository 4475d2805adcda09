// Splatting (Sec. 3.3.2.3): one point per photon, expanded by splat.geom.
void main()
{
    gl_Position = vec4(0.0, 0.0, 0.0, 1.0);
}
