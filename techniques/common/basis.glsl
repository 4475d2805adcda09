// Orthonormal t, b completing the unit direction d (t x b = d): the basis of every orthographic view
// (directional shadow maps, LDMs). gib_ortho_basis() in harness/gl/view.c is the same on the C side.
void ortho_basis(vec3 d, out vec3 t, out vec3 b)
{
    vec3 up = abs(d.y) < 0.99 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
    t = normalize(cross(up, d));
    b = cross(d, t);
}
