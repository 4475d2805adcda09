/* gibench — the cameras and KHR_lights_punctual lights of a glTF 2.0 file's nodes, placed by the
 * nodes' world transforms (FORMAT.md, "glTF scenes"; the mapping is stated in gltf_scene.c). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "gltf_file.h"

/* ------------------------------------------------------------------ node transforms */

/* Column-major 4x4 (glTF's layout): out = a b. */
static void mul4(const double a[16], const double b[16], double out[16])
{
    double r[16];
    for (int c = 0; c < 4; c++)
        for (int row = 0; row < 4; row++) {
            double s = 0;
            for (int k = 0; k < 4; k++)
                s += a[k * 4 + row] * b[c * 4 + k];
            r[c * 4 + row] = s;
        }
    memcpy(out, r, sizeof r);
}

static int local_matrix(const gfile *f, int node, int ni, double m[16], gib_error *err)
{
    static const double id[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    memcpy(m, id, sizeof id);
    if (gib_json_get(f->j, node, "matrix") >= 0) {
        if (nums(f, node, "matrix", m, 16))
            return gib_fail(err, "glTF '%s': node %d: 'matrix' is not 16 numbers", f->path, ni);
        return 0;
    }
    double t[3] = {0, 0, 0}, q[4] = {0, 0, 0, 1}, s[3] = {1, 1, 1};
    if (nums(f, node, "translation", t, 3) || nums(f, node, "rotation", q, 4) ||
        nums(f, node, "scale", s, 3))
        return gib_fail(err, "glTF '%s': node %d: translation, rotation or scale is not 3, 4 "
                             "and 3 numbers", f->path, ni);
    const double ql = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    if (ql > 0)
        for (int k = 0; k < 4; k++)
            q[k] /= ql;
    const double x = q[0], y = q[1], z = q[2], w = q[3];
    const double r[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)},
                            {2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)},
                            {2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)}};
    for (int c = 0; c < 3; c++)
        for (int row = 0; row < 3; row++)
            m[c * 4 + row] = r[row][c] * s[c];
    for (int row = 0; row < 3; row++)
        m[12 + row] = t[row];
    return 0;
}

/* World matrices of the nodes of the file's default scene (`scene`, else scene 0, else every
 * root): world[16 n..]; reached[n] = 1 for those in it. Nodes form trees (gib_gltf_bounds). */
static int world_matrices(const gfile *f, double **world, unsigned char **reached, int *nn,
                          gib_error *err)
{
    const int nodes = gib_json_get(f->j, 0, "nodes"), n = count(f, nodes);
    int *tok = calloc((size_t)n + 1, sizeof *tok), *parent = calloc((size_t)n + 1, sizeof *parent);
    int *stack = calloc((size_t)n + 1, sizeof *stack), sp = 0, rc = 0;
    *world = calloc((size_t)n * 16 + 1, sizeof **world);
    *reached = calloc((size_t)n + 1, 1);
    *nn = n;
    if (!tok || !parent || !stack || !*world || !*reached)
        rc = gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY, "glTF '%s': out of memory", f->path);
    int i = 0;
    for (int k = -1; rc == 0 && (k = gib_json_child(f->j, nodes, k)) >= 0; i++)
        tok[i] = k, parent[i] = -1;
    for (i = 0; rc == 0 && i < n; i++)
        for (int c = -1; (c = gib_json_child(f->j, gib_json_get(f->j, tok[i], "children"), c)) >= 0;) {
            double v;
            if (gib_json_num(f->j, c, &v) == 0 && v >= 0 && v < n)
                parent[(int)v] = i;
        }
    int sc = -1, scenes = gib_json_get(f->j, 0, "scenes");
    if (rc == 0 && index_of(f, 0, "scene", &sc))
        rc = gib_fail(err, "glTF '%s': 'scene' is not an index", f->path);
    if (sc < 0 && count(f, scenes) > 0)
        sc = 0;
    if (rc == 0 && sc >= 0) {
        int st = top(f, "scenes", sc);
        if (st < 0)
            rc = gib_fail(err, "glTF '%s': 'scene' %d does not exist", f->path, sc);
        for (int k = -1; rc == 0 && (k = gib_json_child(f->j, gib_json_get(f->j, st, "nodes"), k)) >= 0;) {
            double v;
            if (gib_json_num(f->j, k, &v) || v < 0 || v >= n || parent[(int)v] >= 0)
                continue;
            if (!(*reached)[(int)v])
                (*reached)[(int)v] = 1, stack[sp++] = (int)v;
        }
    } else {
        for (i = 0; rc == 0 && i < n; i++)
            if (parent[i] < 0)
                (*reached)[i] = 1, stack[sp++] = i;
    }
    /* roots first: their world matrix is their own; a child's is its parent's times its own */
    for (i = 0; rc == 0 && i < sp; i++)
        rc = local_matrix(f, tok[stack[i]], stack[i], *world + 16 * (size_t)stack[i], err);
    while (rc == 0 && sp > 0) {
        const int p = stack[--sp];
        for (int c = -1; rc == 0 && (c = gib_json_child(f->j, gib_json_get(f->j, tok[p], "children"), c)) >= 0;) {
            double v, m[16];
            if (gib_json_num(f->j, c, &v) || v < 0 || v >= n || (*reached)[(int)v])
                continue;
            const int ch = (int)v;
            if ((rc = local_matrix(f, tok[ch], ch, m, err)) == 0) {
                mul4(*world + 16 * (size_t)p, m, *world + 16 * (size_t)ch);
                (*reached)[ch] = 1;
                stack[sp++] = ch;
            }
        }
    }
    free(tok);
    free(parent);
    free(stack);
    return rc;
}

/* A node's world origin, -Z (forward) and +Y (up), the latter two unit length. */
static int node_frame(const double w[16], float pos[3], float fwd[3], float up[3])
{
    double fl = 0, ul = 0;
    for (int k = 0; k < 3; k++) {
        fl += w[8 + k] * w[8 + k];
        ul += w[4 + k] * w[4 + k];
    }
    fl = sqrt(fl);
    ul = sqrt(ul);
    for (int k = 0; k < 3; k++) {
        pos[k] = (float)w[12 + k];
        fwd[k] = fl > 0 ? (float)(-w[8 + k] / fl) : 0.0f;
        up[k] = ul > 0 ? (float)(w[4 + k] / ul) : 0.0f;
    }
    return fl > 0 && ul > 0 && isfinite(fl + ul) ? 0 : -1;
}

/* ------------------------------------------------------------------ cameras and lights */

static int read_camera(const gfile *f, int node, int ni, const double w[16], gib_gltf_info *out,
                       gib_error *err)
{
    int ci;
    if (index_of(f, node, "camera", &ci))
        return gib_fail(err, "glTF '%s': node %d: 'camera' is not an index", f->path, ni);
    int cam = top(f, "cameras", ci);
    if (cam < 0)
        return gib_fail(err, "glTF '%s': node %d: camera %d does not exist", f->path, ni, ci);
    if (!gib_json_streq(f->j, gib_json_get(f->j, cam, "type"), "perspective"))
        return gib_fail(err, "glTF '%s': camera %d is not perspective (orthographic cameras: "
                             "gibench's camera is a pinhole)", f->path, ci);
    double yfov = 0;
    if (num(f, gib_json_get(f->j, cam, "perspective"), "yfov", 0, &yfov) ||
        !(yfov > 0 && yfov < M_PI))
        return gib_fail(err, "glTF '%s': camera %d: 'perspective.yfov' must be in (0, pi) "
                             "radians", f->path, ci);
    gib_camera *c = &out->cameras[out->camera_count];
    char *alias = out->camera_alias[out->camera_count];
    memset(c, 0, sizeof *c);
    char cname[64] = "", nname[64] = "";
    gib_json_str(f->j, gib_json_get(f->j, cam, "name"), cname, sizeof cname);
    gib_json_str(f->j, gib_json_get(f->j, node, "name"), nname, sizeof nname);
    if (cname[0])
        snprintf(c->name, sizeof c->name, "%s", cname);
    else if (nname[0])
        snprintf(c->name, sizeof c->name, "%s", nname);
    else
        snprintf(c->name, sizeof c->name, "camera%d", ci);
    snprintf(alias, 64, "%s", nname);
    float fwd[3];
    if (node_frame(w, c->eye, fwd, c->up))
        return gib_fail(err, "glTF '%s': camera %d's node %d has a degenerate transform", f->path,
                        ci, ni);
    /* the target as far from the eye as the eye is from the origin, so that eye + d fwd keeps
     * fwd to float rounding in scenes far from the origin (Sponza's centimetres) */
    const float d = fmaxf(1.0f, 2.0f * fmaxf(fabsf(c->eye[0]), fmaxf(fabsf(c->eye[1]),
                                                                     fabsf(c->eye[2]))));
    for (int k = 0; k < 3; k++)
        c->target[k] = c->eye[k] + d * fwd[k];
    c->vfov_deg = (float)(yfov * 180.0 / M_PI);
    out->camera_count++;
    return 0;
}

/* extras.gibench of light l: gibench's exact intensity (W/sr, or W/m^2), spot exponent and outer
 * angle, which `gibench export` writes beside glTF's photometric values and smooth cone edge,
 * preferred to the mapping while the file's values (have: colour, intensity, inner and outer
 * cone angles) are the ones it recorded; else listed as ignored. */
static int light_extras(const gfile *f, int l, int li, const double have[6], gib_light *g,
                        char *ignored, size_t cap, gib_error *err)
{
    const int x = gib_json_get(f->j, gib_json_get(f->j, l, "extras"), "gibench");
    const int spot = g->type == GIB_LIGHT_SPOT;
    double in[3] = {0, 0, 0}, e = g->spot_exponent, o = g->spot_outer_deg;
    if (x < 0)
        return 0;
    if (!gib_gltf_extras_current(f, x, have, spot ? 6 : 4)) {
        note(ignored, cap, "gibench extras of lights edited since export (their glTF values "
                           "are used)");
        return 0;
    }
    if (gib_json_get(f->j, x, "intensity") < 0 || nums(f, x, "intensity", in, 3) ||
        !(in[0] >= 0 && in[1] >= 0 && in[2] >= 0) || num(f, x, "spot_exponent", e, &e) ||
        num(f, x, "spot_outer_deg", o, &o) || !(e >= 0) || !(o > 0 && o <= 180))
        return gib_fail(err, "glTF '%s': light %d: extras.gibench needs intensity (3 numbers >= "
                             "0) and may give spot_exponent (>= 0) and spot_outer_deg (in (0, "
                             "180])", f->path, li);
    for (int k = 0; k < 3; k++)
        g->intensity[k] = (float)in[k];
    if (spot) {
        g->spot_exponent = (float)e;
        g->spot_outer_deg = (float)o;
    }
    return 0;
}

static int read_light(const gfile *f, int node, int ni, int li, const double w[16],
                      gib_gltf_info *out, gib_error *err)
{
    int l = -1, arr = gib_json_get(f->j, gib_json_get(f->j, gib_json_get(f->j, 0, "extensions"),
                                                      "KHR_lights_punctual"), "lights");
    for (int k = -1, i = 0; (k = gib_json_child(f->j, arr, k)) >= 0 && l < 0; i++)
        l = i == li ? k : -1;
    if (l < 0)
        return gib_fail(err, "glTF '%s': node %d: KHR_lights_punctual light %d does not exist",
                        f->path, ni, li);
    char type[32] = "";
    gib_json_str(f->j, gib_json_get(f->j, l, "type"), type, sizeof type);
    const int t = strcmp(type, "point") == 0 ? GIB_LIGHT_POINT
                  : strcmp(type, "spot") == 0 ? GIB_LIGHT_SPOT
                  : strcmp(type, "directional") == 0 ? GIB_LIGHT_DIRECTIONAL : -1;
    if (t < 0)
        return gib_fail(err, "glTF '%s': KHR_lights_punctual light %d has type '%s'; gibench "
                             "takes point, spot and directional lights", f->path, li, type);
    double color[3] = {1, 1, 1}, intensity = 1, inner = 0, outer = M_PI / 4;
    const int spot = gib_json_get(f->j, l, "spot");
    if (nums(f, l, "color", color, 3) || num(f, l, "intensity", 1, &intensity) || intensity < 0 ||
        color[0] < 0 || color[1] < 0 || color[2] < 0)
        return gib_fail(err, "glTF '%s': light %d: 'color' (3 numbers >= 0) or 'intensity' "
                             "(>= 0) is invalid", f->path, li);
    if (t == GIB_LIGHT_SPOT &&
        (num(f, spot, "innerConeAngle", 0, &inner) ||
         num(f, spot, "outerConeAngle", M_PI / 4, &outer) || !(inner >= 0 && inner <= outer &&
                                                              outer > 0 && outer <= M_PI / 2 + 1e-9)))
        return gib_fail(err, "glTF '%s': spot light %d: cone angles must satisfy 0 <= inner <= "
                             "outer <= pi/2, outer > 0", f->path, li);
    if (gib_json_get(f->j, l, "range") >= 0)
        note(out->ignored, sizeof out->ignored, "light range (gibench lights reach everywhere)");
    gib_light *g = &out->lights[out->light_count];
    memset(g, 0, sizeof *g);
    char name[64] = "";
    if (gib_json_str(f->j, gib_json_get(f->j, l, "name"), name, sizeof name) || !name[0])
        if (gib_json_str(f->j, gib_json_get(f->j, node, "name"), name, sizeof name) || !name[0])
            snprintf(name, sizeof name, "light%d", li);
    snprintf(g->name, sizeof g->name, "%s", name);
    g->type = t;
    float up[3];
    if (node_frame(w, g->position, g->direction, up))
        return gib_fail(err, "glTF '%s': light %d's node %d has a degenerate transform", f->path,
                        li, ni);
    for (int k = 0; k < 3; k++)
        g->intensity[k] = (float)(color[k] * intensity / GIB_GLTF_LM_PER_W);
    if (t == GIB_LIGHT_DIRECTIONAL)
        g->position[0] = g->position[1] = g->position[2] = 0.0f;
    g->spot_exponent = t == GIB_LIGHT_SPOT ? gib_gltf_spot_exponent(inner, outer) : 1.0f;
    g->spot_outer_deg = t == GIB_LIGHT_SPOT ? (float)(outer * 180.0 / M_PI) : 90.0f;
    const double have[6] = {color[0], color[1], color[2], intensity, inner, outer};
    if (light_extras(f, l, li, have, g, out->ignored, sizeof out->ignored, err))
        return -1;
    out->light_count++;
    return 0;
}

int gib_gltf_read_nodes(const gfile *f, unsigned want, gib_gltf_info *out, gib_error *err)
{
    double *world = NULL;
    unsigned char *reached = NULL;
    int n = 0, rc = world_matrices(f, &world, &reached, &n, err);
    if (rc == 0) {
        out->cameras = calloc((size_t)n + 1, sizeof *out->cameras);
        out->camera_alias = calloc((size_t)n + 1, sizeof *out->camera_alias);
        out->lights = calloc((size_t)n + 1, sizeof *out->lights);
        if (!out->cameras || !out->camera_alias || !out->lights)
            rc = gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY, "glTF '%s': out of memory", f->path);
    }
    int cams = 0, lights = 0, i = 0;
    for (int k = -1; rc == 0 && (k = gib_json_child(f->j, gib_json_get(f->j, 0, "nodes"), k)) >= 0;
         i++) {
        if (!reached[i])
            continue;
        const double *w = world + 16 * (size_t)i;
        if (gib_json_get(f->j, k, "camera") >= 0) {
            cams++;
            if (want & GIB_GLTF_CAMERAS)
                rc = read_camera(f, k, i, w, out, err);
        }
        int lt = gib_json_get(f->j, gib_json_get(f->j, k, "extensions"), "KHR_lights_punctual");
        if (rc == 0 && lt >= 0) {
            int li;
            lights++;
            if (index_of(f, lt, "light", &li) || li < 0)
                rc = gib_fail(err, "glTF '%s': node %d: KHR_lights_punctual 'light' is not an "
                                   "index", f->path, i);
            else if (want & GIB_GLTF_LIGHTS)
                rc = read_light(f, k, i, li, w, out, err);
        }
    }
    if (rc == 0 && cams && !(want & GIB_GLTF_CAMERAS))
        note(out->ignored, sizeof out->ignored, "cameras (camera = gltf takes them)");
    if (rc == 0 && lights && !(want & GIB_GLTF_LIGHTS))
        note(out->ignored, sizeof out->ignored, "lights (lights = gltf takes them)");
    free(world);
    free(reached);
    return rc;
}

