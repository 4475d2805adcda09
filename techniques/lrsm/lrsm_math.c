/* gibench technique `lrsm` — the CPU mirror of lrsm_common.glsl (lrsm_math.h says what each does). */
#include "techniques/lrsm/lrsm_math.h"

#include <math.h>

double lrsm_erf(double x)
{
    /* Abramowitz and Stegun 7.1.26 for x >= 0, odd extension. */
    double s = x < 0 ? -1.0 : 1.0, a = fabs(x);
    double t = 1.0 / (1.0 + 0.3275911 * a);
    double y = ((((1.061405429 * t - 1.453152027) * t + 1.421413741) * t - 0.284496736) * t +
                0.254829592) * t;
    return s * (1.0 - y * exp(-a * a));
}

double lrsm_phi(double x)
{
    return 0.5 * (1.0 + lrsm_erf(x * 0.70710678118654752));
}

double lrsm_visibility(double zc, double rc, double mu, double sigma2)
{
    double sigma = sqrt(sigma2 > LRSM_MIN_VARIANCE ? sigma2 : LRSM_MIN_VARIANCE);
    return lrsm_phi((zc + rc - mu) / sigma) - lrsm_phi((zc - rc - mu) / sigma);
}

double lrsm_smooth(double t)
{
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    return t * t * (3.0 - 2.0 * t);
}

void lrsm_layer_range(const lrsm_partition *p, int d, double *zmin, double *zmax)
{
    double w = (p->z1 - p->z0) / p->parts, delta = p->overlap * w;
    *zmin = p->z0 + d * w - 0.5 * delta;
    *zmax = p->z0 + (d + 1) * w + 0.5 * delta;
}

int lrsm_in_depth_layer(const lrsm_partition *p, int d, double z)
{
    double lo, hi;
    lrsm_layer_range(p, d, &lo, &hi);
    return (d == 0 || z >= lo) && (d == p->parts - 1 || z <= hi);
}

int lrsm_layer_overlaps(const lrsm_partition *p, int d, double a, double b)
{
    double lo, hi;
    lrsm_layer_range(p, d, &lo, &hi);
    return (d == 0 || b >= lo) && (d == p->parts - 1 || a <= hi);
}

double lrsm_decay(const lrsm_partition *p, int d, double zc)
{
    if (!lrsm_in_depth_layer(p, d, zc))
        return 0.0;
    double lo, hi;
    lrsm_layer_range(p, d, &lo, &hi);
    double delta = p->overlap * (p->z1 - p->z0) / p->parts;
    if (delta <= 0)
        return 1.0;
    if (d > 0 && zc < lo + delta)
        return lrsm_smooth((zc - lo) / delta);
    if (d < p->parts - 1 && zc > hi - delta)
        return lrsm_smooth((hi - zc) / delta);
    return 1.0;
}

int lrsm_normal_part(double cosnl, int parts)
{
    if (!(cosnl > 0))
        return -1;
    int k = (int)(cosnl * parts);
    return k < parts ? k : parts - 1;
}

void lrsm_build_block(const lrsm_partition *p, int normal_parts, const lrsm_texel block[4],
                      lrsm_layer_texel *out)
{
    for (int d = 0; d < p->parts; d++) {
        double lo, hi;
        lrsm_layer_range(p, d, &lo, &hi);
        for (int k = 0; k < normal_parts; k++) {
            lrsm_layer_texel *o = &out[d * normal_parts + k];
            double r[3] = {0, 0, 0}, n[3] = {0, 0, 0}, z = 0, z2 = 0, count = 0, area = 0;
            for (int i = 0; i < 4; i++) {
                const lrsm_texel *t = &block[i];
                if (!t->valid || !lrsm_in_depth_layer(p, d, t->z) ||
                    lrsm_normal_part(t->cosnl, normal_parts) != k)
                    continue;
                double zw = (t->z - lo) / (hi - lo);
                zw = zw < 0 ? 0 : zw > 1 ? 1 : zw;
                for (int c = 0; c < 3; c++) {
                    r[c] += t->radiance[c] * t->area;
                    n[c] += t->n[c];
                }
                area += t->area;
                z += zw;
                z2 += zw * zw;
                count += 1;
            }
            for (int c = 0; c < 3; c++) {
                o->radiance[c] = r[c] / 4;
                o->normal[c] = n[c] / 4;
            }
            o->radiance[3] = area / 4;
            o->normal[3] = count / 4;
            o->depth[0] = z / 4;
            o->depth[1] = z2 / 4;
            o->depth[2] = count / 4;
        }
    }
}

double lrsm_area_weight(int kind, double z, double zfar, double cos_face, double cosnl)
{
    double tilt = cosnl > LRSM_JACOBIAN_COS ? LRSM_JACOBIAN_COS / cosnl : 1;
    if (kind == GIB_LV_KIND_ORTHO)
        return tilt;
    double r = z / zfar;
    return r * r * cos_face * cos_face * cos_face * tilt;
}

double lrsm_mip(double diameter_texels, double clamp)
{
    double m = log2(diameter_texels > 1e-30 ? diameter_texels : 1e-30);
    return m > clamp ? m : clamp;
}

double lrsm_cap_cosine(double cos_axis, double sin_axis, double sin_half)
{
    double a = cos_axis, b = sin_half * sin_axis;
    if (b < 1e-9)
        return a > 0 ? a : 0.0;
    double u = -a / b;
    if (u <= -1)
        return a;
    if (u >= 1)
        return 0.0;
    double w = sqrt(1 - u * u);
    return (2 / M_PI) * (a * (M_PI / 4 - 0.5 * (u * w + asin(u))) + b * w * w * w / 3);
}

double lrsm_plane_hits(double delta, double E, double rc, double step, double sigma2_delta)
{
    double h = step * rc * E;
    double S = sqrt(0.25 * rc * rc * fmax(1 - E * E, 0) + sigma2_delta + 1e-8 * rc * rc);
    return lrsm_phi((h - delta) / S) - lrsm_phi((-h - delta) / S);
}

double lrsm_plane_spread(double var, double cos_nl, double rc)
{
    double s2 = var * cos_nl * cos_nl - rc * rc * (1 - cos_nl * cos_nl) / 3;
    return s2 > 0 ? s2 : 0.0;
}
