/* Reference renderer: the early exits on a ray's first hit (ref_may_hit_mirror and
 * ref_may_hit_specular, ref_world.c). Every path the light tracer follows starts at a mirror, and
 * caustic's camera paths continue only from a vertex with a specular lobe, so a ray that meets no
 * such triangle in a scene of them alone ends without a trace through the whole scene. The images
 * stay the same bits only if no ray whose closest hit in the whole scene is such a triangle is
 * ever told "none".
 *
 * Checked on rays from every light in all directions and from points spread over the scene's
 * bounds (so that the triangles are met from both sides, at grazing angles and at shared edges),
 * for each kind (mirror, specular):
 *   - no ray whose first hit is of the kind is ever told 0 (the property the images rest on);
 *   - the exit does cull: a fair share of the rays that hit something else are told 0, or it is
 *     dead code (a negative control on the check above);
 *   - a scene without mirrors answers 0; a mirror with a cut-out mask (no separate scene) 1.
 * Scenes: the mixed scene of ref_determinism (a mirror wall, an alpha-masked Phong board), the same
 * with the board unmasked (a Phong surface in the specular scene, not in the mirrors'), and the
 * procedural water room and ring (mirror water, a mirror ring). */
#include <math.h>
#include <string.h>

#include "reference/ref_internal.h"
#include "ref_test_util.h"
#include "scenes/scene.h"

enum { RAYS_PER_ORIGIN = 4096, ORIGINS = 48 };

typedef struct fh_count {
    long first, told_no_but_first, other, culled;
} fh_count;

static int fh_is_specular(const gib_material *m)
{
    return m->spec_type != GIB_SPEC_NONE &&
           (m->specular[0] > 0.0f || m->specular[1] > 0.0f || m->specular[2] > 0.0f);
}

static int fh_is_mirror(const gib_material *m)
{
    return fh_is_specular(m) && m->spec_type == GIB_SPEC_MIRROR;
}

static void fh_tally(fh_count *c, int first_is, int may)
{
    if (first_is) {
        c->first++;
        c->told_no_but_first += !may;
    } else {
        c->other++;
        c->culled += !may;
    }
}

/* Uniform directions from o (a fixed generator: the same rays every run). c[0] mirrors, c[1]
 * specular. */
static void fh_origin(const ref_world *w, const float o[3], uint64_t seed, fh_count c[2])
{
    ref_pcg32 rng;
    ref_pcg32_seed_sample(&rng, seed, 0, 1, 0);
    for (int i = 0; i < RAYS_PER_ORIGIN; i++) {
        float z = 1.0f - 2.0f * ref_pcg32_float(&rng), phi = 6.2831853f * ref_pcg32_float(&rng);
        float r = sqrtf(fmaxf(0.0f, 1.0f - z * z));
        float d[3] = {r * cosf(phi), r * sinf(phi), z};
        ref_hit h;
        int hit = ref_trace(w, o, d, &h);
        fh_tally(&c[0], hit && fh_is_mirror(h.mat), ref_may_hit_mirror(w, o, d));
        fh_tally(&c[1], hit && fh_is_specular(h.mat), ref_may_hit_specular(w, o, d));
    }
}

static void fh_check(const char *scene, const char *kind, const fh_count *c, int expect_cull)
{
    printf("%-14s %-8s first %6ld (told no: %ld)  other %6ld: culled %6ld\n", scene, kind,
           c->first, c->told_no_but_first, c->other, c->culled);
    CHECK(c->told_no_but_first == 0, "%s: %ld rays with a %s first were told none", scene,
          c->told_no_but_first, kind);
    CHECK(c->first > 100, "%s: only %ld rays hit a %s first: the check has no power", scene,
          c->first, kind);
    if (expect_cull) /* most of the other rays never meet one */
        CHECK(c->culled > c->other / 4, "%s: only %ld of %ld rays culled (%s)", scene, c->culled,
              c->other, kind);
}

/* expect: bit 0 the mirrors' exit culls, bit 1 the specular one's. */
static void fh_scene(const gib_scene *s, int expect)
{
    ref_world w;
    gib_error err;
    if (ref_world_build(&w, s, &err) < 0) {
        CHECK(0, "%s: %s", s->name, err.msg);
        return;
    }
    fh_count c[2] = {{0}};
    for (uint32_t l = 0; l < w.gs->light_count; l++)
        if (w.gs->lights[l].type != GIB_LIGHT_DIRECTIONAL)
            fh_origin(&w, w.gs->lights[l].position, 1000 + l, c);
    ref_pcg32 rng;
    ref_pcg32_seed_sample(&rng, 7, 0, 1, 0);
    for (int k = 0; k < ORIGINS; k++) { /* points within the bounding sphere */
        float o[3];
        for (int j = 0; j < 3; j++)
            o[j] = w.bcentre[j] +
                   w.bradius * 0.8f * (2.0f * ref_pcg32_float(&rng) - 1.0f) / 1.7320508f;
        fh_origin(&w, o, 2000 + (uint64_t)k, c);
    }
    fh_check(s->name, "mirror", &c[0], expect & 1);
    fh_check(s->name, "specular", &c[1], expect & 2);
    ref_world_free(&w);
}

/* A mirror with a cut-out mask: no separate scene, every ray may hit one. A scene without
 * mirrors: no ray can. */
static void fh_fallbacks(void)
{
    gib_scene s;
    rt_scene_mixed(&s); /* its board's mask is texture 0: the mirror takes it too */
    CHECK(s.texture_count > 0, "the mixed scene has no texture to mask the mirror with");
    for (uint32_t m = 0; m < s.material_count; m++)
        if (fh_is_mirror(&s.materials[m]))
            s.materials[m].alpha_tex = 0;
    ref_world w;
    gib_error err;
    CHECK(ref_world_build(&w, &s, &err) == 0, "%s", err.msg);
    const float o[3] = {0.0f, 5.0f, 0.0f}, d[3] = {0.0f, 1.0f, 0.0f}; /* toward nothing */
    CHECK(ref_may_hit_mirror(&w, o, d) == 1 && !w.mirrors,
          "a masked mirror: every ray must take the whole trace");
    ref_world_free(&w);
    for (uint32_t m = 0; m < s.material_count; m++)
        s.materials[m].spec_type = GIB_SPEC_NONE;
    CHECK(ref_world_build(&w, &s, &err) == 0, "%s", err.msg);
    const float down[3] = {0.0f, -1.0f, 0.0f};
    CHECK(ref_may_hit_mirror(&w, o, down) == 0 && ref_may_hit_specular(&w, o, down) == 0,
          "no specular lobe in the scene: no ray may meet one");
    ref_world_free(&w);
    rt_scene_free(&s);
}

int main(void)
{
    gib_scene s;
    rt_scene_mixed(&s);
    fh_scene(&s, 1); /* the masked Phong board: no specular scene */
    for (uint32_t m = 0; m < s.material_count; m++)
        s.materials[m].alpha_tex = -1;
    s.name[0] = 'M'; /* the board unmasked: a Phong surface among the specular triangles */
    fh_scene(&s, 3);
    rt_scene_free(&s);
    const char *builtin[] = {"water_room", "ring"}; /* procedural: no shared data needed */
    for (int i = 0; i < 2; i++) {
        gib_error err;
        if (gib_scene_load(builtin[i], &s, &err) < 0) {
            CHECK(0, "%s: %s", builtin[i], err.msg);
            continue;
        }
        fh_scene(&s, 3);
        gib_scene_free(&s);
    }
    fh_fallbacks();
    return failures != 0;
}
