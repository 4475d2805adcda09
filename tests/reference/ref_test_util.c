#include "ref_test_util.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "tests/common/check.h"


int failures = 0;

static void *rt_grow(void *p, size_t n, size_t size)
{
    void *q = realloc(p, n * size);
    if (!q) {
        fprintf(stderr, "out of memory\n");
        abort();
    }
    return q;
}

void rt_scene_init(gib_scene *s, const char *name)
{
    memset(s, 0, sizeof *s);
    snprintf(s->name, sizeof s->name, "%s", name);
    s->exposure = 1.0f;
    s->content_hash = 0x0123456789abcdefull;
}

void rt_scene_free(gib_scene *s)
{
    free(s->positions);
    free(s->normals);
    free(s->uvs);
    free(s->indices);
    free(s->tri_material);
    free(s->ranges);
    free(s->materials);
    for (uint32_t i = 0; i < s->texture_count; i++)
        free(s->textures[i].rgba);
    free(s->textures);
    free(s->lights);
    free(s->cameras);
    memset(s, 0, sizeof *s);
}

int rt_material(gib_scene *s, float r, float g, float b)
{
    s->materials = rt_grow(s->materials, s->material_count + 1, sizeof *s->materials);
    gib_material *m = &s->materials[s->material_count];
    memset(m, 0, sizeof *m);
    snprintf(m->name, sizeof m->name, "m%u", s->material_count);
    m->albedo[0] = r;
    m->albedo[1] = g;
    m->albedo[2] = b;
    m->albedo_tex = -1;
    m->alpha_tex = -1;
    m->spec_type = GIB_SPEC_NONE;
    return (int)s->material_count++;
}

int rt_texture(gib_scene *s, int w, int h, const float *rgba)
{
    s->textures = rt_grow(s->textures, s->texture_count + 1, sizeof *s->textures);
    gib_texture *t = &s->textures[s->texture_count];
    memset(t, 0, sizeof *t);
    snprintf(t->path, sizeof t->path, "test%u", s->texture_count);
    t->width = w;
    t->height = h;
    t->rgba = rt_grow(NULL, (size_t)w * (size_t)h * 4, sizeof(float));
    memcpy(t->rgba, rgba, (size_t)w * (size_t)h * 4 * sizeof(float));
    return (int)s->texture_count++;
}

void rt_quad(gib_scene *s, const float p0[3], const float p1[3], const float p2[3],
             const float p3[3], const float normal[3], int material)
{
    uint32_t v = s->vertex_count, t = s->triangle_count;
    s->positions = rt_grow(s->positions, 3 * (size_t)(v + 4), sizeof(float));
    s->normals = rt_grow(s->normals, 3 * (size_t)(v + 4), sizeof(float));
    s->uvs = rt_grow(s->uvs, 2 * (size_t)(v + 4), sizeof(float));
    s->indices = rt_grow(s->indices, 3 * (size_t)(t + 2), sizeof(uint32_t));
    s->tri_material = rt_grow(s->tri_material, (size_t)(t + 2), sizeof(uint32_t));
    const float *p[4] = {p0, p1, p2, p3};
    static const float uv[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (int i = 0; i < 4; i++) {
        memcpy(s->positions + 3 * (size_t)(v + i), p[i], 3 * sizeof(float));
        memcpy(s->normals + 3 * (size_t)(v + i), normal, 3 * sizeof(float));
        s->uvs[2 * (size_t)(v + i)] = uv[i][0];
        s->uvs[2 * (size_t)(v + i) + 1] = uv[i][1];
    }
    const uint32_t ix[6] = {v, v + 1, v + 2, v, v + 2, v + 3};
    memcpy(s->indices + 3 * (size_t)t, ix, sizeof ix);
    s->tri_material[t] = s->tri_material[t + 1] = (uint32_t)material;
    s->vertex_count += 4;
    s->triangle_count += 2;
    for (int i = 0; i < 4; i++)
        for (int k = 0; k < 3; k++) {
            if ((v == 0 && i == 0) || p[i][k] < s->bounds_min[k])
                s->bounds_min[k] = p[i][k];
            if ((v == 0 && i == 0) || p[i][k] > s->bounds_max[k])
                s->bounds_max[k] = p[i][k];
        }
}

void rt_floor(gib_scene *s, float h, float x0, float x1, float z0, float z1, int material)
{
    /* Counter-clockwise seen from above (+y). */
    const float a[3] = {x0, h, z1}, b[3] = {x1, h, z1}, c[3] = {x1, h, z0}, d[3] = {x0, h, z0};
    const float n[3] = {0.0f, 1.0f, 0.0f};
    rt_quad(s, a, b, c, d, n, material);
}

static gib_light *rt_light(gib_scene *s)
{
    s->lights = rt_grow(s->lights, s->light_count + 1, sizeof *s->lights);
    gib_light *l = &s->lights[s->light_count];
    memset(l, 0, sizeof *l);
    snprintf(l->name, sizeof l->name, "l%u", s->light_count);
    s->light_count++;
    return l;
}

void rt_point_light(gib_scene *s, float x, float y, float z, float r, float g, float b)
{
    gib_light *l = rt_light(s);
    l->type = GIB_LIGHT_POINT;
    l->position[0] = x;
    l->position[1] = y;
    l->position[2] = z;
    l->direction[1] = -1.0f;
    l->intensity[0] = r;
    l->intensity[1] = g;
    l->intensity[2] = b;
    s->features |= GIB_FEAT_POINT_LIGHT;
}

void rt_spot_light(gib_scene *s, const float pos[3], const float dir[3], float intensity,
                   float exponent, float outer_deg)
{
    gib_light *l = rt_light(s);
    l->type = GIB_LIGHT_SPOT;
    memcpy(l->position, pos, sizeof l->position);
    memcpy(l->direction, dir, sizeof l->direction);
    l->intensity[0] = l->intensity[1] = l->intensity[2] = intensity;
    l->spot_exponent = exponent;
    l->spot_outer_deg = outer_deg;
    s->features |= GIB_FEAT_SPOT_LIGHT;
}

void rt_camera(gib_scene *s, const float eye[3], const float target[3], const float up[3],
               float vfov_deg)
{
    s->cameras = rt_grow(s->cameras, s->camera_count + 1, sizeof *s->cameras);
    gib_camera *c = &s->cameras[s->camera_count];
    memset(c, 0, sizeof *c);
    snprintf(c->name, sizeof c->name, "c%u", s->camera_count);
    memcpy(c->eye, eye, sizeof c->eye);
    memcpy(c->target, target, sizeof c->target);
    memcpy(c->up, up, sizeof c->up);
    c->vfov_deg = vfov_deg;
    s->camera_count++;
}

gib_ref_params rt_params(int component, int w, int h, int spp)
{
    gib_ref_params p;
    memset(&p, 0, sizeof p);
    p.component = component;
    p.width = w;
    p.height = h;
    p.spp = spp;
    p.dmax = 0.0f;
    p.seed = 1;
    p.threads = 0;
    p.camera = 0;
    p.quiet = 1;
    return p;
}

void rt_render(const gib_scene *s, const gib_ref_params *p, gib_image *img, gib_image *sd,
               gib_ref_stats *st)
{
    gib_error err = {0};
    if (gib_reference_render(s, p, img, sd, st, &err) < 0) {
        CHECK(0, "render of '%s' failed: %s", s->name, err.msg);
        exit(1);
    }
}

int rt_hit_plane_y(const gib_scene *s, int cam, int w, int h, int x, int y, double plane_y,
                   double P[3])
{
    float o[3], d[3];
    gib_camera_ray(&s->cameras[cam], w, h, (float)x + 0.5f, (float)y + 0.5f, o, d);
    if (d[1] == 0.0f)
        return 0;
    double t = (plane_y - (double)o[1]) / (double)d[1];
    if (!(t > 0.0))
        return 0;
    for (int k = 0; k < 3; k++)
        P[k] = (double)o[k] + t * (double)d[k];
    return 1;
}

void rt_sky(gib_scene *s, float r, float g, float b)
{
    s->sky[0] = r;
    s->sky[1] = g;
    s->sky[2] = b;
    s->features |= GIB_FEAT_SKY;
}

void rt_scene_mixed(gib_scene *s)
{
    rt_scene_init(s, "determinism");
    int m = rt_material(s, 0.6f, 0.6f, 0.6f);
    rt_floor(s, 0.0f, -4.0f, 4.0f, -4.0f, 4.0f, m);
    /* A checkerboard cut-out above the floor. */
    float rgba[8 * 8 * 4];
    for (int y = 0; y < 8; y++)
        for (int x = 0; x < 8; x++)
            for (int c = 0; c < 4; c++)
                rgba[(y * 8 + x) * 4 + c] = ((x + y) & 1) ? 1.0f : 0.0f;
    int mc = rt_material(s, 0.3f, 0.6f, 0.9f);
    s->materials[mc].alpha_tex = rt_texture(s, 8, 8, rgba);
    s->materials[mc].two_sided = 1;
    s->materials[mc].spec_type = GIB_SPEC_PHONG;
    s->materials[mc].specular[0] = s->materials[mc].specular[1] =
        s->materials[mc].specular[2] = 0.3f;
    s->materials[mc].phong_n = 8.0f;
    s->features |= GIB_FEAT_ALPHA_MASK | GIB_FEAT_SPECULAR | GIB_FEAT_MIRROR;
    rt_floor(s, 0.4f, -1.0f, 1.0f, -1.0f, 1.0f, mc);
    int mirror = rt_material(s, 0.1f, 0.1f, 0.1f);
    s->materials[mirror].spec_type = GIB_SPEC_MIRROR;
    s->materials[mirror].specular[0] = s->materials[mirror].specular[1] =
        s->materials[mirror].specular[2] = 0.8f;
    const float a[3] = {1.5f, 0, 1.5f}, b[3] = {1.5f, 0, -1.5f}, c[3] = {1.5f, 1.5f, -1.5f},
                d[3] = {1.5f, 1.5f, 1.5f}, n[3] = {-1, 0, 0};
    rt_quad(s, a, b, c, d, n, mirror);
    rt_point_light(s, -0.5f, 2.0f, 0.5f, 5.0f, 5.0f, 5.0f);
    const float eye[3] = {-2.5f, 2.5f, 2.5f}, tgt[3] = {0.5f, 0.0f, 0.0f}, up[3] = {0, 1, 0};
    rt_camera(s, eye, tgt, up, 55.0f);
}

static double rt_angle(const double a[3], const double b[3])
{
    double c[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
    return atan2(sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]),
                 a[0] * b[0] + a[1] * b[1] + a[2] * b[2]);
}

double rt_form_factor_up(double R[][3], int n)
{
    double sum = 0.0;
    for (int i = 0; i < n; i++) {
        const double *a = R[i], *b = R[(i + 1) % n];
        double c[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                       a[0] * b[1] - a[1] * b[0]};
        double len = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
        if (len > 0.0)
            sum += rt_angle(a, b) * c[1] / len;
    }
    return fabs(sum) / (2.0 * M_PI);
}

void rt_zstats_add(rt_zstats *z, double got, double se, double expect, double var1, int spp)
{
    double se_a = sqrt(var1 / spp), dev = fabs(got - expect) / se_a;
    z->worst_z = dev > z->worst_z ? dev : z->worst_z;
    z->dsum += got - expect;
    z->var_r += se * se;
    z->var_a += se_a * se_a;
    z->esum += expect;
    z->msum += got;
    z->n++;
}

void rt_zstats_check(rt_zstats *z, const char *what)
{
    z->zsum = z->dsum / sqrt(z->var_r);
    char label[256];
    snprintf(label, sizeof label, "%s: image-wide deviation (standard errors)", what);
    CHECK_NEAR(label, 0, z->zsum, 3.0, "3 of the renderer's standard errors of the sum");
    snprintf(label, sizeof label, "%s: worst pixel (analytic standard errors)", what);
    CHECK_AT_MOST(label, z->worst_z, 5.0, "~0.5 expected false alarms per million pixels");
    snprintf(label, sizeof label, "%s: renderer variance %.4g over the analytic %.4g", what,
             z->var_r, z->var_a);
    if (z->sobol)
        CHECK_AT_MOST(label, z->var_r / z->var_a, 1.05,
                      "Sobol: stratification does not exceed independent samples' variance on "
                      "smooth integrands (measured 0.04-0.25)");
    else
        CHECK_NEAR(label, 1, z->var_r / z->var_a, 0.05,
                   "the renderer estimates the same variance from thousands of pixels");
}

void rt_z_diff(const double *a_img, const double *a_var, const double *b_img, const double *b_var,
               int w, int h, int nb, double *zmean, double *zblock)
{
    *zmean = *zblock = 0.0;
    for (int c = 0; c < 3; c++) {
        size_t o = (size_t)c * (size_t)w * (size_t)h;
        double dm = 0.0, vm = 0.0;
        for (int by = 0; by < h; by += nb)
            for (int bx = 0; bx < w; bx += nb) {
                double d = 0.0, v = 0.0;
                for (int y = by; y < by + nb && y < h; y++)
                    for (int x = bx; x < bx + nb && x < w; x++) {
                        size_t i = o + (size_t)y * (size_t)w + (size_t)x;
                        d += a_img[i] - b_img[i];
                        v += a_var[i] + b_var[i];
                    }
                dm += d;
                vm += v;
                double z = v > 0.0 ? fabs(d) / sqrt(v) : (d != 0.0 ? INFINITY : 0.0);
                *zblock = z > *zblock ? z : *zblock;
            }
        double z = vm > 0.0 ? dm / sqrt(vm) : (dm != 0.0 ? INFINITY : 0.0);
        *zmean = fabs(z) > fabs(*zmean) ? z : *zmean;
    }
}
