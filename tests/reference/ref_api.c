/* Reference renderer, interface: component names, EXR attributes, parameter normalisation and
 * hashing, parameter errors, an empty scene and a scene with a bad index. Exact string and value
 * comparisons: no tolerance is involved. */
#include <math.h>
#include <string.h>

#include "ref_test_util.h"

static const char *rt_get(const gib_kv *kv, int n, const char *key)
{
    for (int i = 0; i < n; i++)
        if (strcmp(kv[i].key, key) == 0)
            return kv[i].value;
    return NULL;
}

int main(void)
{
    /* names */
    CHECK(strcmp(gib_component_name(GIB_COMP_AO), "ao") == 0, "name of ao");
    CHECK(strcmp(gib_component_name(GIB_COMP_DIRECT), "direct") == 0, "name of direct");
    CHECK(gib_component_parse("ao") == GIB_COMP_AO, "parse ao");
    CHECK(gib_component_parse("direct") == GIB_COMP_DIRECT, "parse direct");
    static const char *const names[GIB_COMP_COUNT] = {
        "ao", "direct", "indirect", "glossy", "caustic", "full", "higher", "albedo", "normal",
        "depth"};
    for (int i = 0; i < GIB_COMP_COUNT; i++)
        CHECK(gib_component_parse(names[i]) == i && !strcmp(gib_component_name(i), names[i]),
              "component %d round trip '%s'", i, names[i]);
    CHECK(gib_component_parse("bogus") == -1 && gib_component_parse(NULL) == -1,
          "unknown names parse to -1");
    CHECK(strcmp(gib_component_name(99), "unknown") == 0, "out-of-range name");

    /* an empty scene: every pixel misses, so everything is 0 */
    gib_scene s;
    rt_scene_init(&s, "empty");
    const float eye[3] = {0, 0, 5}, tgt[3] = {0, 0, 0}, up[3] = {0, 1, 0};
    rt_camera(&s, eye, tgt, up, 45.0f);
    gib_ref_params p = rt_params(GIB_COMP_AO, 8, 6, 4);
    gib_image img, sd;
    gib_ref_stats st;
    rt_render(&s, &p, &img, &sd, &st);
    int nonzero = 0;
    for (int i = 0; i < 8 * 6 * 3; i++)
        nonzero += img.px[i] != 0.0f || sd.px[i] != 0.0f;
    CHECK(nonzero == 0 && st.mean == 0.0 && st.rays == 48, "empty scene: %d nonzero, rays %lld",
          nonzero, st.rays);
    CHECK(img.width == 8 && img.height == 6 && img.channels == 3, "image shape %dx%dx%d",
          img.width, img.height, img.channels);
    gib_image_free(&img);
    gib_image_free(&sd);

    /* attributes */
    st.seconds = 1.25;
    st.noise_rmse = 0.0123;
    st.mean = 0.5;
    p.seed = 42;
    p.dmax = 0.0f;
    gib_kv kv[GIB_REF_ATTR_COUNT + 4];
    int n = gib_reference_attrs(&s, &p, &st, kv, GIB_REF_ATTR_COUNT + 4);
    /* Every attribute but `time`, which only a moving scene's header carries, and `cone`, which
     * only one diffuse cone's indirect carries. */
    CHECK(n == GIB_REF_ATTR_COUNT - 2, "attribute count %d, expected %d", n,
          GIB_REF_ATTR_COUNT - 2);
    struct {
        const char *key, *value;
    } want[] = {{"component", "ao"},      {"spp", "4"},
                {"scene_hash", "0123456789abcdef"}, {"renderer_version", GIB_REFERENCE_VERSION},
                {"width", "8"},           {"height", "6"},
                {"dmax", "inf"},          {"seed", "42"},
                {"camera", "0"},          {"seconds", "1.250"},
                {"noise_rmse", "0.0123"}, {"mean", "0.5"},
                {"obscurance", "0"},      {"max_depth", "0"},
                {"estimator", "random"},  {"footprint", "centre"},
                {"missing", "none"},      {"rounds", "1"},
                {"sky", "0 0 0"},         {"stop", "spp"}};
    for (unsigned i = 0; i < sizeof want / sizeof want[0]; i++) {
        const char *v = rt_get(kv, n, want[i].key);
        CHECK(v && strcmp(v, want[i].value) == 0, "attribute %s = '%s', expected '%s'",
              want[i].key, v ? v : "(missing)", want[i].value);
    }
    p.dmax = INFINITY;
    n = gib_reference_attrs(&s, &p, &st, kv, GIB_REF_ATTR_COUNT);
    CHECK(strcmp(rt_get(kv, n, "dmax"), "inf") == 0, "dmax inf is written 'inf'");
    p.dmax = 0.25f;
    n = gib_reference_attrs(&s, &p, &st, kv, GIB_REF_ATTR_COUNT);
    CHECK(strcmp(rt_get(kv, n, "dmax"), "0.25") == 0, "dmax 0.25 is written '0.25'");
    CHECK(gib_reference_attrs(&s, &p, &st, kv, 3) == 3, "max_attrs bounds the count");

    /* normalisation and the cache key: parameters a component ignores do not change its key,
     * parameters it uses do, and defaults hash like their explicit values */
    {
        gib_ref_params a = rt_params(GIB_COMP_DIRECT, 8, 6, 1), b = a;
        b.dmax = 3.0f, b.max_depth = 5, b.spp = 64, b.threads = 3, b.obscurance = 1;
        CHECK(gib_reference_cache_key(&s, &a) == gib_reference_cache_key(&s, &b),
              "direct: dmax, max_depth, spp (deterministic), threads must not change the key");
        a = rt_params(GIB_COMP_AO, 8, 6, 4), b = a;
        b.dmax = 0.0f;
        a.dmax = INFINITY;
        CHECK(gib_reference_cache_key(&s, &a) == gib_reference_cache_key(&s, &b),
              "ao: dmax 0 and inf are the same image");
        b.dmax = 2.0f;
        CHECK(gib_reference_cache_key(&s, &a) != gib_reference_cache_key(&s, &b),
              "ao: dmax changes the key");
        a.dmax = 2.0f, a.obscurance = 1;
        CHECK(gib_reference_cache_key(&s, &a) != gib_reference_cache_key(&s, &b),
              "ao: obscurance changes the key");
        a = rt_params(GIB_COMP_FULL, 8, 6, 4), b = a;
        b.max_depth = GIB_REF_DEFAULT_MAX_DEPTH, b.min_depth = GIB_REF_DEFAULT_MIN_DEPTH;
        CHECK(gib_reference_cache_key(&s, &a) == gib_reference_cache_key(&s, &b),
              "full: defaults hash like their explicit values");
        const int fields = 6;
        for (int f = 0; f < fields; f++) {
            gib_ref_params c = a;
            if (f == 0) c.max_depth = 3;
            if (f == 1) c.min_depth = 1;
            if (f == 2) c.spp = 5;
            if (f == 3) c.seed = 2;
            if (f == 4) c.target_noise = 0.01;
            if (f == 5) c.width = 9;
            CHECK(gib_reference_cache_key(&s, &a) != gib_reference_cache_key(&s, &c),
                  "full: field %d must change the key", f);
        }
        gib_ref_params c = a;
        c.max_specular = 4; /* full ignores it; higher and caustic use it */
        CHECK(gib_reference_cache_key(&s, &a) == gib_reference_cache_key(&s, &c),
              "full: max_specular must not change the key");
        a.component = c.component = GIB_COMP_HIGHER;
        CHECK(gib_reference_cache_key(&s, &a) != gib_reference_cache_key(&s, &c),
              "higher: max_specular changes the key");
        gib_scene s2 = s;
        s2.content_hash ^= 1;
        CHECK(gib_reference_cache_key(&s, &a) != gib_reference_cache_key(&s2, &a),
              "the scene's content hash changes the key");
        s2.content_hash = s.content_hash;
        gib_camera cam2 = s.cameras[0];
        cam2.vfov_deg += 1.0f;
        s2.cameras = &cam2;
        CHECK(gib_reference_cache_key(&s, &a) != gib_reference_cache_key(&s2, &a),
              "the camera changes the key");
        CHECK(gib_component_deterministic(&s, GIB_COMP_DIRECT) &&
                  gib_component_deterministic(&s, GIB_COMP_GLOSSY) &&
                  !gib_component_deterministic(&s, GIB_COMP_INDIRECT),
              "deterministic: direct and (no specular) glossy, not indirect");
    }

    /* parameter errors name the parameter */
    struct {
        gib_ref_params p;
        const char *needle;
    } bad[7];
    for (int i = 0; i < 7; i++)
        bad[i].p = rt_params(GIB_COMP_AO, 8, 8, 2);
    bad[0].p.spp = 0, bad[0].needle = "spp";
    bad[1].p.camera = 3, bad[1].needle = "camera";
    bad[2].p.component = 99, bad[2].needle = "component";
    bad[3].p.width = 0, bad[3].needle = "size";
    /* a random estimator with one sample: its variance, hence its noise, would be unknown */
    bad[4].p.spp = 1, bad[4].needle = "at least 2";
    bad[5].p.obscurance = 1, bad[5].needle = "obscurance"; /* needs a finite dmax */
    bad[6].p.target_noise = -1.0, bad[6].needle = "target_noise";
    for (int i = 0; i < 7; i++) {
        gib_error err = {0};
        int rc = gib_reference_render(&s, &bad[i].p, &img, NULL, NULL, &err);
        CHECK(rc < 0 && strstr(err.msg, bad[i].needle), "bad %s: rc %d, message '%s'",
              bad[i].needle, rc, err.msg);
    }

    /* a triangle indexing a vertex that does not exist is refused, not traced */
    int m = rt_material(&s, 0.5f, 0.5f, 0.5f);
    rt_floor(&s, 0.0f, -1, 1, -1, 1, m);
    s.indices[4] = 99;
    {
        gib_error err = {0};
        gib_ref_params q = rt_params(GIB_COMP_AO, 8, 8, 2);
        int rc = gib_reference_render(&s, &q, &img, NULL, NULL, &err);
        CHECK(rc < 0 && strstr(err.msg, "vertex 99"), "bad index: rc %d, message '%s'", rc,
              err.msg);
        printf("bad index refused: %s\n", err.msg);
    }
    rt_scene_free(&s);
    printf("names, attributes, parameter errors and the empty scene: %s\n",
           failures ? "FAILED" : "ok");
    return failures ? 1 : 0;
}
