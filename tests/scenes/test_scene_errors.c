/* Every .scene error must name the file and the line a user has to fix (scenes/FORMAT.md). Each
 * case writes a small scene file to a temporary folder, loads it, and checks the return code and
 * that the message holds the file's path, ":LINE:" and a phrase saying what is wrong. */
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "scenes/scene.h"
#include "tests/scenes/scene_test.h"

#define expect scene_expect_load

#define CAMERA "[camera.c]\neye = 0 0 5\ntarget = 0 0 0\n"

int main(void)
{
    if (scene_test_begin("gib_scene_errors") < 0)
        return 1;
    /* Mesh files are looked up under the data root: point it at the (otherwise empty) temp dir,
     * so that "missing mesh file" is an error and not "data unavailable". */
    setenv("GIBENCH_SCENES", tmpdir, 1);

    /* (a) missing mesh file: the line of its `file` key */
    expect("missing mesh file",
           "[scene]\n"
           "description = missing mesh\n"
           "[mesh.statue]\n"
           "file = no_such_mesh.obj\n" /* line 4 */
           CAMERA,
           -1, 4, "no_such_mesh.obj", "not found");

    /* (b) bad number */
    expect("bad number",
           "[scene]\n"
           "[mesh.box]\n"
           "procedural = cornell_box\n"
           "[light.key]\n"
           "type = point\n"
           "position = 0 1 0\n"
           "intensity = 1 abc 2\n" /* line 7 */
           CAMERA,
           -1, 7, "expects 3 numbers, got '1 abc 2'", "light 'key'");

    /* (c) unknown key */
    expect("unknown key",
           "[scene]\n"
           "[mesh.box]\n"
           "procedural = cornell_box\n"
           "\n"
           "[material.white]\n"
           "colour = 1 1 1\n" /* line 6 */
           CAMERA,
           -1, 6, "unknown key 'colour'", "albedo");

    /* (d) unknown section, even one without keys (inih calls no handler for it) */
    expect("unknown empty section",
           "[scene]\n"
           "[mesh.box]\n"
           "procedural = cornell_box\n" CAMERA "; a comment\n"
           "[lamp.key]\n", /* line 8: CAMERA is lines 4-6 */
           -1, 8, "unknown section [lamp.key]", NULL);
    expect("unknown section with keys",
           "[scene]\n"
           "[lamp.key]\n" /* line 2 */
           "type = point\n"
           "[mesh.box]\n"
           "procedural = cornell_box\n" CAMERA,
           -1, 2, "unknown section [lamp.key]", NULL);

    /* further errors the format promises */
    expect("unknown generator", "[scene]\n[mesh.pot]\nprocedural = teapot\n" CAMERA, -1, 3,
           "unknown procedural generator 'teapot'", "cornell_box");
    expect("shift needs 3 numbers", "[scene]\nshift = 1 2\n[mesh.box]\nprocedural = cornell_box\n" CAMERA,
           -1, 2, "shift", NULL);
    expect("unknown light type",
           "[scene]\n[mesh.box]\nprocedural = cornell_box\n[light.sky]\ntype = area\n"
           "intensity = 1 1 1\n" CAMERA,
           -1, 5, "unknown light type 'area'", NULL);
    expect("albedo + specular > 1",
           "[scene]\n[mesh.box]\nprocedural = cornell_box\n[material.white]\n"
           "albedo = 0.8 0.8 0.8\nphong_n = 20\nspecular = 0.1 0.5 0.1\n" /* line 7 */ CAMERA,
           -1, 7, "green channel", "material 'white'");
    expect("new material, sum > 1",
           "[scene]\n[mesh.box]\nprocedural = cornell_box\nmaterial = shiny\n"
           "[material.shiny]\nspecular = 0.6 0.6 0.6\n" /* line 6 */ "mirror = 1\n"
           "albedo = 0.5 0.2 0.2\n" CAMERA,
           -1, 8, "red channel", NULL);
    expect("key given twice",
           "[scene]\nexposure = 1\nexposure = 2\n[mesh.box]\nprocedural = cornell_box\n" CAMERA, -1,
           3, "given twice", NULL);
    expect("syntax error",
           "[scene]\n[mesh.box]\nprocedural = cornell_box\nthis line is no key\n" CAMERA, -1, 4,
           "cannot read this line", NULL);
    expect("unclosed section", "[scene]\n[mesh.box\nprocedural = cornell_box\n" CAMERA, -1, 2,
           "closing ']'", NULL);
    char longline[400];
    snprintf(longline, sizeof longline,
             "[scene]\ndescription = %0250d\n[mesh.box]\n"
             "procedural = cornell_box\n" CAMERA,
             7);
    expect("line too long", longline, -1, 2, "characters long", NULL);
    expect("undefined material",
           "[scene]\n[mesh.box]\nprocedural = cornell_box\nmaterial = gold\n" CAMERA, -1, 4,
           "material 'gold' is not defined", NULL);
    expect("size on cornell_box",
           "[scene]\n[mesh.box]\nprocedural = cornell_box\nsize = 1 2 3\n" CAMERA, -1, 4,
           "'size' applies only", NULL);
    expect("spot without direction",
           "[scene]\n[mesh.box]\nprocedural = cornell_box\n[light.s]\ntype = spot\n"
           "position = 0 1 0\nintensity = 1 1 1\n" CAMERA,
           -1, 4, "needs 'direction", NULL);
    expect("camera without target",
           "[scene]\n[mesh.box]\nprocedural = cornell_box\n[camera.c]\neye = 0 0 1\n", -1, 4,
           "needs 'eye = x y z' and 'target", NULL);
    expect("no camera", "[scene]\n[mesh.box]\nprocedural = cornell_box\n", -1, 1,
           "no [camera.NAME]", NULL);
    expect("section twice", "[scene]\n[mesh.box]\nprocedural = cornell_box\n[mesh.box]\n" CAMERA,
           -1, 4, "appears twice (first at line 2)", NULL);
    expect("key before any section", "exposure = 1\n[scene]\n", -1, 1, "before any section", NULL);

    /* A mesh whose MTL names a texture that is not there: the error points at the mesh's `file`
     * line and names the texture. */
    char p[512];
    write_file("tri.obj",
               "mtllib tri.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n"
               "usemtl painted\nf 1/1 2/2 3/3\n",
               p, sizeof p);
    write_file("tri.mtl", "newmtl painted\nKd 1 1 1\nmap_Kd no_such_texture.png\n", p, sizeof p);
    expect("missing texture", "[scene]\n[mesh.tri]\nfile = tri.obj\n" /* line 3 */ CAMERA, -1, 3,
           "no_such_texture.png", "material 'painted'");

    /* Data that is not there makes the scene unavailable, not broken: its own return code, and a
     * message saying where to get the data and which variable to set. */
    expect("missing data folder",
           "[scene]\ndata = not-downloaded\n[mesh.m]\nfile = not-downloaded/m.obj\n" CAMERA,
           GIB_SCENE_UNAVAILABLE, 2, "GIBENCH_SCENES", "McGuire");

    /* What must NOT be an error: indentation, inline comments, commas, blank lines, CRLF. */
    expect("valid file with indentation",
           "; a comment\r\n# another\r\n[scene]\r\n  description = ok ; inline comment\r\n\r\n"
           "[mesh.box]\r\n    procedural = cornell_box\r\n  translate = 1, 2, 3\r\n"
           "[camera.c]\r\n\teye = 0 0 5\r\n\ttarget = 0 0 0\r\n",
           0, 0, "", NULL);

    return scene_test_end();
}
