/* Occlusion voxels (techniques/common/voxels.*): the GPU voxelisation against an exact CPU
 * triangle/box overlap (Akenine-Moller's separating-axis test, in double), voxel by voxel, on
 * procedural scenes: a thin slanted wall, a diagonal plane (one voxel thin), a tessellated sphere
 * (small triangles), the moving Cornell box at a later instant (positions read back from the
 * GPU, so the posed triangles are the ones checked) and hard_sliver (slivers and zero-area
 * triangles); and an alpha-masked quad (check_alpha).
 *
 * Checks, per case:
 *  - zero misses: every voxel the CPU says a triangle touches (closed boxes, exact) is set;
 *  - no false positive beyond rounding: every set voxel is touched by a triangle when the box is
 *    dilated by 2e-3 voxel (the shader dilates by 1e-3 voxel so that float rounding of voxel
 *    coordinates, ~1e-4 voxel at 512, can only add voxels); the false-positive rate against the
 *    exact test is printed;
 *  - a plane and a wall voxelise without holes: their set voxels are one 6-connected component;
 *  - the mip chain: every texel of level k is the mean of its 8 children at level k - 1 within
 *    0.5/255 + 1e-6 (the mean of the stored bytes, rounded once to the nearest 1/255 by the R8
 *    store), so each level's mean is the base level's occupancy within k x 0.5/255.
 * voxel_cone.glsl has its own test (test_voxel_cone.c).
 *
 * `test_voxels --bench SCENE RES...` times gib_voxels_build (median of 5 after one warm-up) and
 * `test_voxels --png DIR SCENE RES` writes slices and projections of the voxels, for looking. */
#include <glad/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "harness/gl/timers.h"
#include "harness/imaging/image.h"
#include "techniques/common/voxels.h"
#include "tests/common/gl_fixture.h"
#include "tests/common/check.h"

static int failures;

/* ---- exact CPU triangle/box overlap (Akenine-Moller 2001), box centred at c, half side h ---- */

static void sub3(const double a[3], const double b[3], double o[3])
{
    for (int k = 0; k < 3; k++)
        o[k] = a[k] - b[k];
}

static void cross3(const double a[3], const double b[3], double o[3])
{
    o[0] = a[1] * b[2] - a[2] * b[1];
    o[1] = a[2] * b[0] - a[0] * b[2];
    o[2] = a[0] * b[1] - a[1] * b[0];
}

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* Not separated along axis a: the triangle's projection meets the box's [-r, r]. */
static int axis_overlaps(const double a[3], const double v[3][3], double h)
{
    double p0 = dot3(a, v[0]), p1 = dot3(a, v[1]), p2 = dot3(a, v[2]);
    double lo = fmin(p0, fmin(p1, p2)), hi = fmax(p0, fmax(p1, p2));
    double r = h * (fabs(a[0]) + fabs(a[1]) + fabs(a[2]));
    return lo <= r && hi >= -r;
}

static int tri_box_overlap(const double c[3], double h, const double tri[3][3])
{
    double v[3][3], e[3][3], n[3];
    for (int i = 0; i < 3; i++)
        sub3(tri[i], c, v[i]);
    for (int i = 0; i < 3; i++)
        sub3(v[(i + 1) % 3], v[i], e[i]);
    cross3(e[0], e[1], n);
    if (n[0] == 0 && n[1] == 0 && n[2] == 0)
        return 0; /* zero area: covers nothing (the shader skips it too) */
    for (int i = 0; i < 3; i++) /* the box's normals */
        for (int k = 0; k < 3; k++) {
            double a[3] = {0, 0, 0};
            a[k] = 1;
            if (!axis_overlaps(a, v, h))
                return 0;
        }
    if (!axis_overlaps(n, v, h)) /* the triangle's normal */
        return 0;
    for (int i = 0; i < 3; i++) /* the 9 edge x box-normal axes */
        for (int k = 0; k < 3; k++) {
            double u[3] = {0, 0, 0}, a[3];
            u[k] = 1;
            cross3(u, e[i], a);
            if (!axis_overlaps(a, v, h))
                return 0;
        }
    return 1;
}

/* ---- reading the voxels back ---- */

static unsigned char *read_level(const gib_voxels *v, int level, int *r)
{
    *r = v->res >> level;
    size_t n = (size_t)*r * *r * *r;
    unsigned char *b = malloc(n);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTextureImage(v->texture, level, GL_RED, GL_UNSIGNED_BYTE, (GLsizei)n, b);
    return b;
}

/* The triangles as the GPU has them (a moving scene's posed positions), in voxel units. */
static float *read_positions(const gib_gpu_scene *g, size_t *count)
{
    GLint64 bytes = 0;
    glGetNamedBufferParameteri64v(g->positions, GL_BUFFER_SIZE, &bytes);
    float *p = malloc((size_t)bytes);
    glGetNamedBufferSubData(g->positions, 0, (GLsizeiptr)bytes, p);
    *count = (size_t)bytes / 12;
    return p;
}

/* Marks (bit 1) the voxels each triangle touches exactly and (bit 2) those it touches dilated by
 * `dilate` voxel. */
static void cpu_voxelise(const gib_voxels *v, const gib_gpu_scene *g, unsigned char *mark,
                         double dilate)
{
    size_t nv;
    float *pos = read_positions(g, &nv);
    const gib_scene *s = g->scene;
    const float inv = (float)v->res / v->size; /* the shader's uniform */
    const int R = v->res;
    for (uint32_t t = 0; t < s->triangle_count; t++) {
        double tri[3][3], lo[3], hi[3];
        for (int i = 0; i < 3; i++)
            for (int k = 0; k < 3; k++)
                tri[i][k] = ((double)pos[3 * s->indices[3 * t + i] + k] - v->origin[k]) * inv;
        for (int k = 0; k < 3; k++) {
            lo[k] = fmin(tri[0][k], fmin(tri[1][k], tri[2][k]));
            hi[k] = fmax(tri[0][k], fmax(tri[1][k], tri[2][k]));
        }
        int a[3], b[3];
        for (int k = 0; k < 3; k++) {
            a[k] = (int)floor(lo[k] - 1 - dilate);
            b[k] = (int)floor(hi[k] + dilate);
            a[k] = a[k] < 0 ? 0 : a[k];
            b[k] = b[k] > R - 1 ? R - 1 : b[k];
        }
        for (int z = a[2]; z <= b[2]; z++)
            for (int y = a[1]; y <= b[1]; y++)
                for (int x = a[0]; x <= b[0]; x++) {
                    size_t i = ((size_t)z * R + y) * R + x;
                    const double c[3] = {x + 0.5, y + 0.5, z + 0.5};
                    if (!(mark[i] & 1) && tri_box_overlap(c, 0.5, tri))
                        mark[i] |= 1;
                    if (!(mark[i] & 2) && tri_box_overlap(c, 0.5 + dilate, tri))
                        mark[i] |= 2;
                }
    }
    free(pos);
}

/* Number of 6-connected components of the set voxels. */
static int components6(const unsigned char *vox, int R)
{
    size_t n = (size_t)R * R * R;
    unsigned char *seen = calloc(n, 1);
    size_t *stack = malloc(n * sizeof *stack);
    int count = 0;
    for (size_t s = 0; s < n; s++) {
        if (!vox[s] || seen[s])
            continue;
        count++;
        size_t top = 0;
        stack[top++] = s;
        seen[s] = 1;
        while (top) {
            size_t i = stack[--top];
            int x = (int)(i % R), y = (int)(i / R % R), z = (int)(i / R / R);
            const int d[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
            for (int k = 0; k < 6; k++) {
                int X = x + d[k][0], Y = y + d[k][1], Z = z + d[k][2];
                if (X < 0 || Y < 0 || Z < 0 || X >= R || Y >= R || Z >= R)
                    continue;
                size_t j = ((size_t)Z * R + Y) * R + X;
                if (vox[j] && !seen[j]) {
                    seen[j] = 1;
                    stack[top++] = j;
                }
            }
        }
    }
    free(seen);
    free(stack);
    return count;
}

/* Each texel of every level above 0 against the mean of its 8 children, and each level's mean
 * against the base level's. */
static void check_mips(const char *name, const gib_voxels *v)
{
    int r0;
    unsigned char *prev = read_level(v, 0, &r0);
    double base = 0;
    for (size_t i = 0; i < (size_t)r0 * r0 * r0; i++)
        base += prev[i] / 255.0;
    base /= (double)r0 * r0 * r0;
    int levels = gib_mip_levels(v->res, v->res, v->res), bad = 0, rp = r0;
    double worst_texel = 0, worst_mean = 0;
    for (int l = 1; l < levels; l++) {
        int r;
        unsigned char *cur = read_level(v, l, &r);
        double mean = 0;
        for (int z = 0; z < r; z++)
            for (int y = 0; y < r; y++)
                for (int x = 0; x < r; x++) {
                    double sum = 0;
                    for (int c = 0; c < 8; c++)
                        sum += prev[((size_t)(2 * z + (c >> 2)) * rp + 2 * y + (c >> 1 & 1)) * rp +
                                    2 * x + (c & 1)];
                    double got = cur[((size_t)z * r + y) * r + x] / 255.0;
                    double err = fabs(got - sum / 8 / 255.0);
                    worst_texel = fmax(worst_texel, err);
                    bad += err > 0.5 / 255 + 1e-6;
                    mean += got;
                }
        mean /= (double)r * r * r;
        double dm = fabs(mean - base);
        worst_mean = fmax(worst_mean, dm / l);
        char what[160];
        snprintf(what, sizeof what, "%s: mip %d mean %.6f, |drift| from the base occupancy %.6f",
                 name, l, mean, base);
        CHECK_AT_MOST(what, dm, l * 0.5 / 255 + 1e-9,
                      "each level's R8 store rounds once to the nearest 1/255: k x 0.5/255");
        free(prev);
        prev = cur;
        rp = r;
    }
    free(prev);
    CHECK(!bad, "%s: %d mip texels differ from their 8 children's mean by more than 0.5/255 "
          "(worst %.5f)", name, bad, worst_texel);
    printf("  %s: mips: base occupancy %.5f, worst texel error %.2f/255, worst mean drift %.2f/255 "
           "per level\n", name, base, worst_texel * 255, worst_mean * 255);
}

static int open_scene(gib_gl_fixture *fx, const char *dir, const char *name, const char *text)
{
    if (gib_fixture_open_text(fx, dir, name, text) < 0) {
        failures++;
        return -1;
    }
    return 0;
}

static void check_case(const char *dir, const char *name, const char *text, int res,
                       double time, int connected)
{
    gib_gl_fixture fx;
    if (text ? open_scene(&fx, dir, name, text) < 0 : gib_fixture_open(&fx, name) < 0) {
        failures += !text;
        return;
    }
    gib_error err;
    if (time > 0 && gib_gpu_scene_set_time(&fx.gpu, time, &err) < 0) {
        CHECK(0, "%s: %s", name, err.msg);
        gib_fixture_close(&fx);
        return;
    }
    gib_ledger ledger;
    gib_ledger_init(&ledger);
    gib_voxels v;
    if (gib_voxels_create(&v, &fx.gpu, res, "voxels", &ledger, &err) < 0) {
        CHECK(0, "%s: %s", name, err.msg);
        gib_fixture_close(&fx);
        return;
    }
    CHECK(ledger.entries[0].bytes == gib_voxels_bytes(res),
          "%s: the ledger counts %llu bytes, the plan %llu", name,
          (unsigned long long)ledger.entries[0].bytes,
          (unsigned long long)gib_voxels_bytes(res));
    gib_voxels_build(&v, &fx.gpu, NULL, "voxelization");
    CHECK(!(gib_gl_check("building the voxels", &err) < 0), "%s: %s", name, err.msg);
    int R;
    unsigned char *gpu = read_level(&v, 0, &R);
    size_t n = (size_t)R * R * R;
    unsigned char *mark = calloc(n, 1);
    cpu_voxelise(&v, &fx.gpu, mark, 2e-3);
    size_t set = 0, touched = 0, misses = 0, extras = 0, loose = 0;
    for (size_t i = 0; i < n; i++) {
        int g = gpu[i] != 0;
        if (gpu[i] != 0 && gpu[i] != 255) {
            CHECK(0, "%s: voxel %zu holds %d, not 0 or 255", name, i, gpu[i]);
            break;
        }
        set += g;
        touched += mark[i] & 1;
        misses += (mark[i] & 1) && !g;
        extras += g && !(mark[i] & 2);
        loose += g && !(mark[i] & 1);
    }
    printf("  %s (%u triangles, %d^3): %zu voxels set, %zu touched exactly, %zu missed, "
           "%zu beyond 2e-3 voxel, false positives %.3f%%\n", name, fx.scene.triangle_count, R,
           set, touched, misses, extras, set ? 100.0 * loose / set : 0.0);
    CHECK(!(!touched || misses || extras),
          "%s: %zu voxels missed, %zu set beyond the dilated overlap (or none touched)",
          name, misses, extras);
    if (connected) {
        int c = components6(gpu, R);
        CHECK(c == 1, "%s: the set voxels form %d 6-connected components, not 1", name, c);
    }
    check_mips(name, &v);
    free(gpu);
    free(mark);
    gib_voxels_destroy(&v, &ledger);
    CHECK(!ledger.count, "%s: %d ledger entries left after destroy", name, ledger.count);
    gib_fixture_close(&fx);
}

/* An alpha-masked quad (an OBJ whose MTL has map_d): the tilted plane y = 0.3 x + 0.2 z over
 * x, z in [-0.5, 0.5], uv = (x + 0.5, z + 0.5), solid where u < 0.5 and a hole elsewhere. Voxels
 * the quad touches (exactly, on the CPU) more than 2 voxels inside the solid half must be set,
 * and no voxel more than 2 voxels inside the hole (nor from its far edge u = 1, where the
 * repeating texture's filter reaches the solid texels at u = 0, as in the G-buffer): the shader filters the mask over a voxel's
 * footprint (about one voxel here) at the point nearest the voxel's centre, which lies within
 * 0.3 voxel of the centre's x. */
static void check_alpha(const char *dir)
{
    char path[600];
    snprintf(path, sizeof path, "%s/quad.obj", dir);
    FILE *f = fopen(path, "w");
    if (!f) {
        CHECK(0, "alpha: cannot write %s", path);
        return;
    }
    fprintf(f, "mtllib quad.mtl\nusemtl leaf\n");
    const float xz[4][2] = {{-0.5f, -0.5f}, {0.5f, -0.5f}, {0.5f, 0.5f}, {-0.5f, 0.5f}};
    for (int i = 0; i < 4; i++)
        fprintf(f, "v %g %g %g\n", xz[i][0], 0.3f * xz[i][0] + 0.2f * xz[i][1], xz[i][1]);
    for (int i = 0; i < 4; i++)
        fprintf(f, "vt %g %g\n", xz[i][0] + 0.5f, xz[i][1] + 0.5f);
    fprintf(f, "f 1/1 3/3 2/2\nf 1/1 4/4 3/3\n");
    fclose(f);
    snprintf(path, sizeof path, "%s/quad.mtl", dir);
    if ((f = fopen(path, "w"))) {
        fprintf(f, "newmtl leaf\nKd 0.5 0.5 0.5\nmap_d mask.png\n");
        fclose(f);
    }
    gib_image mask;
    gib_error err;
    snprintf(path, sizeof path, "%s/mask.png", dir);
    if (gib_image_alloc(&mask, 64, 64, 1, &err) < 0) {
        CHECK(0, "alpha: %s", err.msg);
        return;
    }
    for (int y = 0; y < 64; y++)
        for (int x = 0; x < 64; x++)
            mask.px[y * 64 + x] = x < 32 ? 1.0f : 0.0f;
    int rc = gib_png_write_preview(path, &mask, 1.0f, &err);
    gib_image_free(&mask);
    if (rc < 0) {
        CHECK(0, "alpha: %s", err.msg);
        return;
    }
    setenv("GIBENCH_SCENES", dir, 1);
    gib_gl_fixture fx;
    int opened = open_scene(&fx, dir, "alpha", "[scene]\ndescription = voxels: alpha-masked quad\n"
                            "[mesh.quad]\nfile = quad.obj\n"
                            "[camera.c]\neye = 0 1 3\ntarget = 0 0 0\nup = 0 1 0\nfov = 60\n");
    unsetenv("GIBENCH_SCENES");
    if (opened < 0)
        return;
    gib_ledger ledger;
    gib_ledger_init(&ledger);
    gib_voxels v;
    if (gib_voxels_create(&v, &fx.gpu, 64, "voxels", &ledger, &err) < 0) {
        CHECK(0, "alpha: %s", err.msg);
        gib_fixture_close(&fx);
        return;
    }
    gib_voxels_build(&v, &fx.gpu, NULL, "voxelization");
    int R;
    unsigned char *gpu = read_level(&v, 0, &R);
    unsigned char *mark = calloc((size_t)R * R * R, 1);
    cpu_voxelise(&v, &fx.gpu, mark, 2e-3);
    const float vs = v.size / (float)R;
    size_t solid = 0, solid_set = 0, hole = 0, hole_set = 0;
    for (int z = 0; z < R; z++)
        for (int y = 0; y < R; y++)
            for (int x = 0; x < R; x++) {
                size_t i = ((size_t)z * R + y) * R + x;
                if (!(mark[i] & 1))
                    continue;
                float u = v.origin[0] + (x + 0.5f) * vs + 0.5f;
                if (u < 0.5f - 2 * vs) {
                    solid++;
                    solid_set += gpu[i] != 0;
                } else if (u > 0.5f + 2 * vs && u < 1 - 2 * vs) {
                    hole++;
                    hole_set += gpu[i] != 0;
                }
            }
    printf("  alpha: solid half %zu/%zu voxels set, hole half %zu/%zu set\n", solid_set, solid,
           hole_set, hole);
    CHECK(!(!solid || !hole || solid_set != solid || hole_set),
          "alpha: the mask is not honoured (solid %zu of %zu set, hole %zu of %zu)",
          solid_set, solid, hole_set, hole);
    free(gpu);
    free(mark);
    gib_voxels_destroy(&v, &ledger);
    gib_fixture_close(&fx);
}

/* Times gib_voxels_build: median of 5 builds after one warm-up, wall time with glFinish. */
static int bench(const char *scene, char **res, int count)
{
    gib_gl_fixture fx;
    if (gib_fixture_open(&fx, scene) < 0) {
        printf("SKIP: scene '%s' not available\n", scene);
        return 0;
    }
    const gib_scene *s = fx.gpu.scene;
    uint32_t masked = 0;
    for (uint32_t r = 0; r < s->range_count; r++)
        if (s->materials[s->ranges[r].material].alpha_tex >= 0)
            masked += s->ranges[r].index_count / 3;
    printf("GL_RENDERER: %s; %s: %u triangles (%u alpha-masked), %u draw ranges\n",
           fx.info.renderer, scene, s->triangle_count, masked, s->range_count);
    for (int i = 0; i < count; i++) {
        gib_ledger ledger;
        gib_ledger_init(&ledger);
        gib_voxels v;
        gib_error err;
        if (gib_voxels_create(&v, &fx.gpu, atoi(res[i]), "voxels", &ledger, &err) < 0) {
            CHECK(0, "%s", err.msg);
            gib_fixture_close(&fx);
            return 1;
        }
        /* Per repetition: the whole build, then its clear and its mips alone (the voxelisation's
         * two dispatches are the difference). */
        double build[5], clear[5], mips[5], vox[5];
        for (int k = -1; k < 5; k++) {
            double t[4];
            glFinish();
            t[0] = gib_now_ms();
            gib_voxels_build(&v, &fx.gpu, NULL, "voxelization");
            glFinish();
            t[1] = gib_now_ms();
            const unsigned char zero = 0;
            glClearTexImage(v.texture, 0, GL_RED, GL_UNSIGNED_BYTE, &zero);
            glFinish();
            t[2] = gib_now_ms();
            gib_voxels_mips(&v);
            glFinish();
            t[3] = gib_now_ms();
            if (k < 0)
                continue;
            build[k] = t[1] - t[0];
            clear[k] = t[2] - t[1];
            mips[k] = t[3] - t[2];
            vox[k] = build[k] - clear[k] - mips[k];
        }
        gib_voxels_build(&v, &fx.gpu, NULL, "voxelization");
        int R;
        unsigned char *base = read_level(&v, 0, &R);
        size_t set = 0;
        for (size_t j = 0; j < (size_t)R * R * R; j++)
            set += base[j] != 0;
        free(base);
        double m[4], lo[4], hi;
        gib_stats_median(build, 5, &m[0], &lo[0], &hi);
        gib_stats_median(clear, 5, &m[1], &lo[1], &hi);
        gib_stats_median(vox, 5, &m[2], &lo[2], &hi);
        gib_stats_median(mips, 5, &m[3], &lo[3], &hi);
        printf("  %d^3: build %.1f ms (min %.1f) = clear %.1f + voxelise %.1f (min %.1f) + mips "
               "%.1f (min %.1f); %zu voxels set; %llu bytes\n", v.res, m[0], lo[0], m[1], m[2], lo[2],
               m[3], lo[3], set, (unsigned long long)gib_voxels_bytes(v.res));
        gib_voxels_destroy(&v, &ledger);
    }
    gib_fixture_close(&fx);
    return 0;
}

/* Slices through the middle and max projections along each axis, as PNGs. */
static int dump_png(const char *dir, const char *scene, int res)
{
    gib_gl_fixture fx;
    if (gib_fixture_open(&fx, scene) < 0)
        return 1;
    gib_ledger ledger;
    gib_ledger_init(&ledger);
    gib_voxels v;
    gib_error err;
    if (gib_voxels_create(&v, &fx.gpu, res, "voxels", &ledger, &err) < 0) {
        CHECK(0, "%s", err.msg);
        return 1;
    }
    gib_voxels_build(&v, &fx.gpu, NULL, "voxelization");
    int R;
    unsigned char *vox = read_level(&v, 0, &R);
    gib_image img;
    for (int axis = 0; axis < 3; axis++)
        for (int proj = 0; proj < 2; proj++) {
            gib_image_alloc(&img, R, R, 1, &err);
            for (int a = 0; a < R; a++)
                for (int b = 0; b < R; b++) {
                    float val = 0;
                    for (int c = proj ? 0 : R / 2; c < (proj ? R : R / 2 + 1); c++) {
                        int p[3];
                        p[axis] = c;
                        p[(axis + 1) % 3] = a;
                        p[(axis + 2) % 3] = b;
                        val += vox[((size_t)p[2] * R + p[1]) * R + p[0]] / 255.0f;
                    }
                    img.px[(size_t)(R - 1 - b) * R + a] = proj ? val / (float)R * 4 : val;
                }
            char path[600];
            snprintf(path, sizeof path, "%s/voxels_%c_%s.png", dir, "xyz"[axis],
                     proj ? "sum" : "slice");
            gib_png_write_preview(path, &img, 1.0f, &err);
            gib_image_free(&img);
        }
    free(vox);
    gib_voxels_destroy(&v, &ledger);
    gib_fixture_close(&fx);
    return 0;
}

int main(int argc, char **argv)
{
    if (argc >= 4 && !strcmp(argv[1], "--bench"))
        return bench(argv[2], argv + 3, argc - 3);
    if (argc == 5 && !strcmp(argv[1], "--png"))
        return dump_png(argv[2], argv[3], atoi(argv[4]));
    char dir[] = "/tmp/gib_voxels_XXXXXX";
    if (!mkdtemp(dir)) {
        CHECK(0, "cannot make a temporary folder");
        return 1;
    }
    const char *cam = "[camera.c]\neye = 0 0 3\ntarget = 0 0 0\nup = 0 1 0\nfov = 60\n"
                      "[light.l]\ntype = point\nposition = 0 2 2\nintensity = 1 1 1\n";
    char text[1024];
    /* A wall 2 mm thick (a tenth of a voxel at 64^3), tilted about two axes. */
    snprintf(text, sizeof text, "[scene]\ndescription = voxels: thin slanted wall\n"
             "[mesh.wall]\nprocedural = box\nsize = 0.002 1 1.2\nrotate = 10 30 20\n%s", cam);
    /* The plan (Table 2's figures: 19.17 MB at 256^3, 153.39 MB at 512^3, decimal, full chain):
     * the sum of (res / 2^i)^3 bytes, counted without a context. */
    for (int res = 64; res <= 512; res *= 2) {
        uint64_t want = 0;
        for (int r = res; r >= 1; r /= 2)
            want += (uint64_t)r * r * r;
        CHECK(gib_voxels_bytes(res) == want,
              "plan: gib_voxels_bytes(%d) = %llu, expected %llu", res,
              (unsigned long long)gib_voxels_bytes(res), (unsigned long long)want);
    }
    printf("  plan: %.2f MB at 256^3, %.2f MB at 512^3\n", gib_voxels_bytes(256) / 1e6,
           gib_voxels_bytes(512) / 1e6);
    check_case(dir, "thin_wall", text, 64, 0, 1);
    /* A plane along no axis: every voxel column crosses it at a different height. */
    snprintf(text, sizeof text, "[scene]\ndescription = voxels: diagonal plane\n"
             "[mesh.plane]\nprocedural = quad\nsize = 1 1.3\nrotate = 37 0 29\n%s", cam);
    check_case(dir, "diagonal_plane", text, 128, 0, 1);
    /* Many small triangles (the first pass alone) inside a box with large faces. */
    snprintf(text, sizeof text, "[scene]\ndescription = voxels: sphere\n"
             "[mesh.sphere]\nprocedural = sphere_interior\nradius = 0.5\nsubdivisions = 4\n"
             "rotate = 5 7 11\n[mesh.box]\nprocedural = box\nsize = 1.4 1.3 1.2\n%s", cam);
    check_case(dir, "sphere_box", text, 64, 0, 0);
    /* A moving scene at a later instant: the posed positions are voxelised. */
    check_case(dir, "cornell_moving", NULL, 64, 1.0, 0);
    /* Sliver and zero-area triangles (a fan of 1024 slivers making a quad): no holes. */
    check_case(dir, "hard_sliver", NULL, 64, 0, 1);
    check_alpha(dir);
    char cmd[600];
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    if (system(cmd) != 0)
        printf("note: could not remove %s\n", dir);
    if (failures)
        printf("%d failure(s)\n", failures);
    else
        printf("PASS\n");
    return failures ? 1 : 0;
}
