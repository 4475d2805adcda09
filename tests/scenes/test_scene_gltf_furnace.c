/* glTF scenes (b): the furnace from a glTF file. A .glb written here holds a closed sphere seen
 * from inside (an icosahedron split 4 times, 5120 flat faces, vertices on the sphere of R = 1 m,
 * faces toward the centre), one material of baseColor 0.5 and metallic 0 (so, by FORMAT.md's
 * mapping, Lambertian of albedo a = 0.5), a KHR_lights_punctual point light of 683 cd at the
 * centre (1 W/sr at 683 lm/W) and a camera inside looking sideways; the .scene takes all three
 * from it. The reference renders it, and its images must match the furnace's closed forms (as
 * scenes/furnace.scene and tests/reference/ref_sphere.c state them):
 *   direct = (a / pi) I / R^2, full = direct (1 - a^D) / (1 - a) with D = max_depth vertices,
 * each within the tessellation's interval [h_min / R, (R / h_min)^2] (h_min: the faces' least
 * distance from the centre, measured on the loaded mesh): direct in every pixel (deterministic),
 * full's image mean within 3 of the renderer's own standard errors of that interval. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness/imaging/image.h"
#include "reference/reference.h"
#include "scene_test.h"
#include "tests/scenes/gltf_writer.h"

int main(void)
{
    if (scene_test_begin("gib_gltf_furnace"))
        return 1;
    setenv("GIBENCH_SCENES", tmpdir, 1);
    gw_prim p;
    memset(&p, 0, sizeof p);
    gw_icosphere(&p, 1.0f, 4);
    p.material = 0;
    char path[512];
    snprintf(path, sizeof path, "%s/furnace.glb", tmpdir);
    /* node 1: the light at the centre; node 2: the camera at (0, 0, -0.6) turned -90 degrees
     * about +y, looking down +x (as scenes/furnace.scene's camera) */
    gw_write(path, 1, &p, 1,
             "{\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}}},"
             "{\"camera\":0,\"translation\":[0,0,-0.6],\"rotation\":[0,-0.70710678,0,0.70710678]}",
             ",1,2",
             "\"extensionsUsed\":[\"KHR_lights_punctual\"],"
             "\"extensions\":{\"KHR_lights_punctual\":{\"lights\":[{\"type\":\"point\","
             "\"intensity\":683}]}},"
             "\"cameras\":[{\"type\":\"perspective\",\"perspective\":{\"yfov\":1.0471976,"
             "\"znear\":0.01}}],"
             "\"materials\":[{\"name\":\"wall\",\"doubleSided\":true,\"pbrMetallicRoughness\":"
             "{\"baseColorFactor\":[0.5,0.5,0.5,1],\"metallicFactor\":0,\"roughnessFactor\":1}}],",
             NULL, 0);
    gw_prim_free(&p);
    char sp[512];
    write_file("furnace.scene",
               "[scene]\nclosed = 1\ngltf = furnace.glb\ncamera = gltf\nlights = gltf\n"
               "materials = gltf\n", sp, sizeof sp);
    gib_scene s;
    gib_error err;
    err.msg[0] = '\0';
    int rc = gib_scene_load(sp, &s, &err);
    CHECK(rc == 0, "load: %s", err.msg);
    if (rc)
        return scene_test_end();
    const double a = 0.5, I = 1.0, R = 1.0;
    CHECK(s.material_count == 1 && fabsf(s.materials[0].albedo[0] - 0.5f) < 1e-7f &&
              s.materials[0].spec_type == GIB_SPEC_NONE,
          "one Lambertian material of albedo 0.5 expected (baseColor 0.5, metallic 0)");
    CHECK(s.light_count == 1 && fabsf(s.lights[0].intensity[0] - 1.0f) < 1e-6f,
          "one light of 1 W/sr expected (683 cd)");
    /* h_min from the loaded triangles */
    double hmin = INFINITY;
    for (uint32_t t = 0; t < s.triangle_count; t++) {
        const float *A = s.positions + 3 * s.indices[3 * t], *B = s.positions + 3 * s.indices[3 * t + 1],
                    *C = s.positions + 3 * s.indices[3 * t + 2];
        double e1[3], e2[3], c[3];
        for (int k = 0; k < 3; k++)
            e1[k] = (double)B[k] - A[k], e2[k] = (double)C[k] - A[k];
        c[0] = e1[1] * e2[2] - e1[2] * e2[1];
        c[1] = e1[2] * e2[0] - e1[0] * e2[2];
        c[2] = e1[0] * e2[1] - e1[1] * e2[0];
        const double l = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
        hmin = fmin(hmin, fabs(c[0] * A[0] + c[1] * A[1] + c[2] * A[2]) / l);
    }
    hmin *= 1.0 - 1e-6;
    const double lo = hmin / R, hi = (R / hmin) * (R / hmin), direct = a / M_PI * I / (R * R);
    printf("furnace from glTF: %u triangles, h_min/R = %.6f, interval [%.6f, %.6f]\n",
           s.triangle_count, hmin / R, lo, hi);

    const int W = 16, H = 12;
    gib_ref_params rp;
    memset(&rp, 0, sizeof rp);
    rp.component = GIB_COMP_DIRECT;
    rp.width = W;
    rp.height = H;
    rp.spp = 1;
    rp.seed = 1;
    rp.quiet = 1;
    gib_image img, sd;
    gib_ref_stats st;
    rc = gib_reference_render(&s, &rp, &img, &sd, &st, &err);
    CHECK(rc == 0, "direct render: %s", err.msg);
    if (rc == 0) {
        int out = 0;
        double mean = 0;
        for (int i = 0; i < W * H; i++) {
            const double v = img.px[3 * i];
            mean += v / (W * H);
            out += v < direct * (lo - 1e-5) || v > direct * (hi + 1e-5);
        }
        CHECK(out == 0, "direct: %d pixels outside [%.6f, %.6f]", out, direct * lo, direct * hi);
        printf("direct: closed form %.6f, mean %.6f, %d pixels outside the interval\n", direct,
               mean, out);
        gib_image_free(&img);
        gib_image_free(&sd);
    }
    const int D = 24;
    rp.component = GIB_COMP_FULL;
    rp.spp = 16;
    rp.max_depth = D;
    rp.min_depth = D; /* no Russian roulette: its noise would dominate */
    rc = gib_reference_render(&s, &rp, &img, &sd, &st, &err);
    CHECK(rc == 0, "full render: %s", err.msg);
    if (rc == 0) {
        double mean = 0, var = 0;
        for (int i = 0; i < W * H; i++) {
            mean += img.px[3 * i] / (W * H);
            var += (double)sd.px[3 * i] * sd.px[3 * i];
        }
        const double se = sqrt(var) / (W * H), full = direct * (1 - pow(a, D)) / (1 - a);
        const double dev = mean < full * lo ? full * lo - mean : mean > full * hi ? mean - full * hi
                                                                                  : 0.0;
        CHECK(dev <= 3 * se + 1e-9, "full: mean %.6f, %.3g outside [%.6f, %.6f] (3 se = %.3g)",
              mean, dev, full * lo, full * hi, 3 * se);
        printf("full (max_depth %d): closed form %.6f, interval [%.6f, %.6f], mean %.6f, "
               "stderr of the mean %.2g\n", D, full, full * lo, full * hi, mean, se);
        gib_image_free(&img);
        gib_image_free(&sd);
    }
    gib_scene_free(&s);
    return scene_test_end();
}
