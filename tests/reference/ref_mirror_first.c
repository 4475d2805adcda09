/* Reference renderer: the light tracer's early exit (ref_may_hit_mirror, ref_world.c). Every path
 * the light tracer follows starts at a mirror, so a particle whose first ray meets no mirror
 * triangle ends without a trace through the whole scene. The images stay the same bits only if
 * the test never says "no mirror" for a ray whose closest hit in the whole scene is a mirror.
 *
 * Checked on rays from every light in all directions and from points spread over the scene's
 * bounds (so that mirrors are met from both sides, at grazing angles and at shared edges):
 *   - no ray whose first hit is a mirror is ever told 0 (the property the images rest on);
 *   - the test does cull: a fair share of the rays that hit something else are told 0, or the
 *     early exit is dead code (a negative control on the check above);
 *   - rays that meet a mirror behind another surface are told 1: the test is "meets a mirror",
 *     not "first hit": those rays still take the whole trace;
 *   - a scene without mirrors answers 0, a mirror with a cut-out mask (no separate scene) 1.
 * Scenes: the mixed scene of ref_determinism (a mirror wall, an alpha-masked board), and the
 * built-in water room, ring and bunnies in a ring (mirror water, a mirror ring). */
#include <math.h>
#include <string.h>

#include "reference/ref_internal.h"
#include "ref_test_util.h"
#include "scenes/scene.h"

enum { RAYS_PER_ORIGIN = 4096, ORIGINS = 48 };

typedef struct mf_count {
    long mirror_first, told_no_but_mirror, other_first, culled, met_behind;
} mf_count;

static int mf_is_mirror(const gib_material *m)
{
    return m->spec_type == GIB_SPEC_MIRROR &&
           (m->specular[0] > 0.0f || m->specular[1] > 0.0f || m->specular[2] > 0.0f);
}

static void mf_ray(const ref_world *w, const float o[3], const float d[3], mf_count *c)
{
    ref_hit h;
    int hit = ref_trace(w, o, d, &h), may = ref_may_hit_mirror(w, o, d);
    if (hit && mf_is_mirror(h.mat)) {
        c->mirror_first++;
        c->told_no_but_mirror += !may;
    } else {
        c->other_first++;
        c->culled += !may;
        c->met_behind += may;
    }
}

/* Uniform directions from o (a fixed generator: the same rays every run). */
static void mf_origin(const ref_world *w, const float o[3], uint64_t seed, mf_count *c)
{
    ref_pcg32 rng;
    ref_pcg32_seed_sample(&rng, seed, 0, 1, 0);
    for (int i = 0; i < RAYS_PER_ORIGIN; i++) {
        float z = 1.0f - 2.0f * ref_pcg32_float(&rng), phi = 6.2831853f * ref_pcg32_float(&rng);
        float r = sqrtf(fmaxf(0.0f, 1.0f - z * z));
        float d[3] = {r * cosf(phi), r * sinf(phi), z};
        mf_ray(w, o, d, c);
    }
}

static void mf_scene(const gib_scene *s, int expect_cull)
{
    ref_world w;
    gib_error err;
    if (ref_world_build(&w, s, &err) < 0) {
        CHECK(0, "%s: %s", s->name, err.msg);
        return;
    }
    mf_count c = {0};
    for (uint32_t l = 0; l < w.gs->light_count; l++)
        if (w.gs->lights[l].type != GIB_LIGHT_DIRECTIONAL)
            mf_origin(&w, w.gs->lights[l].position, 1000 + l, &c);
    ref_pcg32 rng;
    ref_pcg32_seed_sample(&rng, 7, 0, 1, 0);
    for (int k = 0; k < ORIGINS; k++) { /* points within the bounding sphere */
        float o[3];
        for (int j = 0; j < 3; j++)
            o[j] = w.bcentre[j] + w.bradius * 0.8f * (2.0f * ref_pcg32_float(&rng) - 1.0f) / 1.7320508f;
        mf_origin(&w, o, 2000 + (uint64_t)k, &c);
    }
    printf("%-14s mirror first %6ld (told no: %ld)  other %6ld: culled %6ld, mirror behind %ld\n",
           s->name, c.mirror_first, c.told_no_but_mirror, c.other_first, c.culled, c.met_behind);
    CHECK(c.told_no_but_mirror == 0, "%s: %ld rays with a mirror first were told no mirror",
              s->name, c.told_no_but_mirror);
    CHECK(c.mirror_first > 100, "%s: only %ld rays hit a mirror first: the check has no power",
              s->name, c.mirror_first);
    if (expect_cull) /* most of the other rays never meet a mirror */
        CHECK(c.culled > c.other_first / 4, "%s: only %ld of %ld rays culled", s->name,
                  c.culled, c.other_first);
    ref_world_free(&w);
}

/* A mirror with a cut-out mask: no separate scene, every ray may hit one. A scene without
 * mirrors: no ray can. */
static void mf_fallbacks(void)
{
    gib_scene s;
    rt_scene_mixed(&s); /* its board's mask is texture 0: the mirror takes it too */
    CHECK(s.texture_count > 0, "the mixed scene has no texture to mask the mirror with");
    for (uint32_t m = 0; m < s.material_count; m++)
        if (mf_is_mirror(&s.materials[m]))
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
    CHECK(ref_may_hit_mirror(&w, o, down) == 0, "no mirror in the scene: no ray may meet one");
    ref_world_free(&w);
    rt_scene_free(&s);
}

int main(void)
{
    gib_scene s;
    rt_scene_mixed(&s);
    mf_scene(&s, 1);
    rt_scene_free(&s);
    const char *builtin[] = {"water_room", "ring", "bunnies_ring"};
    for (int i = 0; i < 3; i++) {
        gib_error err;
        if (gib_scene_load(builtin[i], &s, &err) < 0) {
            CHECK(0, "%s: %s", builtin[i], err.msg);
            continue;
        }
        mf_scene(&s, 1);
        gib_scene_free(&s);
    }
    mf_fallbacks();
    return failures != 0;
}
