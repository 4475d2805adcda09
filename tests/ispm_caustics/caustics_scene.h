/* gibench tests of ispm_caustics: the scene they share. A mirror (rho_s 0.9, rho_d 0) 2 m over a
 * diffuse floor (rho_d 0.7), lit by a spot 1 m under the mirror pointing up (25 degrees, cos
 * falloff, 2 W/sr), so the spot reaches the floor only through the mirror: the caustic is the
 * spot seen mirrored at y = 3. A block (0.5 x 0.6 x 0.5) on the floor inside the caustic casts a
 * shadow and hides a part of the lit floor from the camera: receivers hidden behind a surface. */
#ifndef GIB_TEST_CAUSTICS_SCENE_H
#define GIB_TEST_CAUSTICS_SCENE_H

#define CAUSTICS_SCENE_TEXT \
    "[scene]\n" \
    "description = mirror over a floor, an upward spot, a block hiding part of the floor\n" \
    "[mesh.floor]\nprocedural = quad\nsize = 4 4\nmaterial = floor\n" \
    "[mesh.mirror]\nprocedural = quad\nsize = 1.2 1.2\nrotate = 180 0 0\ntranslate = 0 2 0\n" \
    "material = mirror\n" \
    "[mesh.block]\nprocedural = box\nsize = 0.5 0.6 0.5\ntranslate = 0.5 0 -0.2\nmaterial = block\n" \
    "[material.floor]\nalbedo = 0.7 0.7 0.7\n" \
    "[material.mirror]\nalbedo = 0 0 0\nspecular = 0.9 0.9 0.9\nmirror = 1\n" \
    "[material.block]\nalbedo = 0.5 0.5 0.5\n" \
    "[light.spot]\ntype = spot\nposition = 0 1.0 0\ndirection = 0 1 0\nintensity = 2 2 2\n" \
    "exponent = 1\nouter_angle = 25\n" \
    "[camera.main]\neye = 0.3 1.8 -3.4\ntarget = 0 0 0.2\nfov = 50\n"
static const char caustics_scene_text[] = CAUSTICS_SCENE_TEXT;

#endif
