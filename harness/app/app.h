/* gibench — the command-line application: subcommands and what they share. */
#ifndef GIB_APP_H
#define GIB_APP_H

#include "reference/reference.h"
#include "scenes/scene.h"
#include "techniques/technique.h"
#include "harness/gl/context.h"
#include "harness/imaging/metrics.h"
#include "harness/imaging/score.h"

int gib_cmd_list(int argc, char **argv);
int gib_cmd_render(int argc, char **argv);
int gib_cmd_reference(int argc, char **argv);
int gib_cmd_compare(int argc, char **argv);
int gib_cmd_export(int argc, char **argv);
int gib_cmd_run(int argc, char **argv);
int gib_cmd_bench(int argc, char **argv);
int gib_cmd_merge(int argc, char **argv);
int gib_cmd_history(int argc, char **argv);
int gib_cmd_check(int argc, char **argv);

/* Technique plugins (plugins.c): loads the shared library at path and registers its techniques; 0,
 * or -1 with err naming the file (a contract version mismatch names both versions). */
int gib_plugin_load(const char *path, gib_error *err);
/* Loads $GIBENCH_PLUGINS (paths joined by ':'), then every `--plugin PATH` / `--plugin=PATH` of
 * argv, which it removes from argv (argc updated): 0, or -1 with err set. */
int gib_plugins_from_args(int *argc, char **argv, gib_error *err);

/* "256x256" → w, h; errors name the option. */
int gib_parse_size(const char *opt, const char *s, int *w, int *h, gib_error *err);
/* Integer / float option values with range checks; errors name the option. */
int gib_parse_int(const char *opt, const char *s, long min, long max, long *out, gib_error *err);
int gib_parse_float(const char *opt, const char *s, double min, double max, double *out,
                    gib_error *err);
/* Loads a scene for command `cmd` and checks that it has camera `camera`. Returns 0, or the exit
 * status to return after printing the error: 3 when the scene's shared data is absent, 1 when the
 * scene cannot be loaded, 2 for a camera it lacks. */
int gib_cli_load_scene(const char *cmd, const char *name, long camera, gib_scene *scene);
/* Makes a directory and its parents. */
int gib_mkdirs(const char *path, gib_error *err);
/* The folder a file path names: "." without a slash, "/" for a file in the root. */
void gib_path_folder(const char *path, char *out, size_t size);
/* Refuses, before any work is done, an output file that could not be written at the end: a path
 * that is a directory, a folder that is missing or not writable, a read-only file, or (ext not
 * NULL) a name that does not end in ext. Errors name the option. */
int gib_check_output(const char *opt, const char *path, const char *ext, gib_error *err);
/* The git revision the binary was built from: GIB_REVISION when the build names it (a bundle, built
 * to run away from its checkout), else asked of git ("unknown" outside a checkout). */
const char *gib_git_revision(void);
/* The hash of technique NAME's sources when the binary was built (harness/reporting/source_hash.py, generated
 * at build time), "" for a name it does not know. */
const char *gib_technique_source_hash(const char *name);

/* Reference images, from the cache or rendered and cached (harness/app/refcache.c). */
typedef struct gib_ref_request {
    const gib_scene *scene;
    int camera;
    int width, height;
    float time;          /* seconds: the instant of a moving scene (ignored for a static one) */
    int component;       /* enum gib_component */
    int spp;
    float dmax;          /* ao */
    /* The component's other parameters (reference.h, gib_ref_params); 0 = the renderer's
     * default, so a request that does not name them keeps working. */
    int obscurance;      /* ao: Zhukov's obscurance with the technique's dmax */
    int max_depth;       /* full, higher */
    int min_depth;       /* full, higher: Russian roulette from this depth */
    int max_specular;    /* caustic, higher */
    int cone;            /* indirect: k >= 1 only diffuse cone k - 1 (reference.h) */
    float cone_aperture; /* with cone: degrees */
    double target_noise; /* > 0: sample until noise_rmse / mean <= this ... */
    int max_spp;         /* ... or this many samples per pixel */
    const char *cache_dir;
    int force;           /* render even when a valid entry exists */
    int quiet;           /* no progress output */
    int threads;         /* 0: all cores (the image does not depend on it) */
    gib_ref_interrupt *interrupt; /* NULL, or stop early on request (reference.h): the rounds done
                                   * are not stored as the entry (they missed its target) but
                                   * written beside it, and gib_reference_get fails naming that
                                   * file */
} gib_ref_request;

typedef struct gib_ref_result {
    gib_image image;
    int spp;             /* samples per pixel actually taken */
    double noise_rmse, seconds;
    int from_cache;
    int interrupted;     /* the request's interrupt stopped it: no entry, see the error */
    char path[1024];
} gib_ref_result;

/* 0, or -1 with err set; GIB_REF_WRITE_FAILED (< 0 too) when the reference rendered but its cache
 * entry could not be written (a full disk): nothing of it is left behind. */
#define GIB_REF_WRITE_FAILED (-2)
int gib_reference_get(const gib_ref_request *rq, gib_ref_result *out, gib_error *err);
/* n requests of one scene at one instant: each found in the cache as
 * gib_reference_get finds it; those missing are rendered together (gib_reference_render_set, each
 * the pixels its render alone gives) and each stored as its own entry under its own key. The
 * requests' interrupts are not heard. out[i] as gib_reference_get's; on error none holds an
 * image. */
int gib_reference_get_set(const gib_ref_request *rq, int n, gib_ref_result *out, gib_error *err);

/* Sets the reference settings of output `output` (a GIB_OUT_* bit) from the technique's declared
 * bindings (technique.h, gib_ref_binding), so the reference models what the technique estimates;
 * a setting no binding names keeps its default (dmax unbounded, visibility not obscurance). */
void gib_ref_request_match(gib_ref_request *rq, const gib_technique *t, const gib_params *p,
                           unsigned output);
/* A reference setting's (enum gib_ref_setting) name and its default where no binding names it. */
const char *gib_ref_setting_name(int setting);
double gib_ref_setting_default(int setting);
/* The renderer parameters of a request (seed 1). */
gib_ref_params gib_ref_request_params(const gib_ref_request *rq);
/* The seal of a reference EXR: appends a "content_hash" attribute (when max allows) that hashes
 * the pixels and every other attribute, so that an image or header changed after writing is
 * detected (FNV-1a: edits and corruption, not forgery). Returns the new count. */
int gib_ref_seal(const gib_image *img, gib_kv *attrs, int n, int max);
/* 1 when the header got (as read back) carries the seal of img and of the values of the
 * attributes named in want (the keys written: a header may hold others), 0 otherwise. */
int gib_ref_seal_ok(const gib_image *img, const gib_kv *want, int nwant, const gib_kv *got,
                    int ngot);

/* Returned by gib_score_and_save when the metrics are computed but an image cannot be written
 * (a full disk): the caller stops rather than record a row. */
#define GIB_IMAGE_WRITE_FAILED GIB_SCORE_WRITE_FAILED

/* Scores a technique image against a reference and writes the images: DIR/NAME.exr, NAME.png
 * (preview at the scene's exposure), NAME_error.png and NAME_flip.png (the LDR-FLIP error map in
 * the magma colours of FLIP's reference tool; LDR-FLIP compares the images the previews show,
 * HDR-FLIP the linear radiance: gib_flip_pair_on in flip.h). gib_score_pair (harness/imaging/
 * score.h): every metric once, over the scoring threads, the images written meanwhile. */
int gib_score_and_save(const gib_image *ref, const gib_image *img, float exposure, const char *dir,
                       const char *name, gib_metrics *m, gib_error *err);

/* What every command reports of an image against a reference: the metrics and FLIP means
 * (gib_score_and_save, the images written where dir is set) and the RMSE's 95% interval with the
 * reference's noise (its RMSE against the truth, 0 for an exact image) taken out. `gibench run`,
 * `render` and `compare` score through it. Returns as gib_score_and_save. */
typedef struct gib_score {
    gib_metrics m;
    gib_rmse_bounds rmse; /* metrics.h, gib_rmse_interval */
} gib_score;
int gib_score_image(const gib_image *ref, double ref_noise_rmse, const gib_image *img,
                    float exposure, const char *dir, const char *name, gib_score *s,
                    gib_error *err);

#endif
