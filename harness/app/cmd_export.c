/* gibench export — a scene as an external renderer's row gets it (external_job.c: scene.gltf,
 * scene.bin, job.json), without a matrix: for a renderer outside gibench to read, or to read back
 * through a .scene's `gltf =` (scenes/FORMAT.md, "glTF scenes"). */
#include <ctype.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app.h"
#include "external.h"
#include "options.h"

typedef struct export_opts {
    const char *scene_name, *dir, *camera, *size, *components;
    double time;
    int w, h;
} export_opts;

static const gib_command_doc doc = {
    "export", "SCENE DIR [--camera NAME|INDEX] [--time T] [--size WxH] [--components LIST]",
    "Writes scene SCENE (a name from gibench list, or a .scene path) into DIR as an external\n"
    "renderer's row gets it: scene.gltf + scene.bin (glTF 2.0: the geometry posed at --time, the\n"
    "materials, the camera, the lights as KHR_lights_punctual; gibench's exact values in extras)\n"
    "and job.json (examples/external_renderer/README.md), its outputs named DIR/<component>.exr.\n"
    "It then prints a .scene that reads the glTF back (scenes/FORMAT.md, \"glTF scenes\"); its\n"
    "other lines are comments, so `gibench export S DIR > DIR/back.scene` keeps it.\n"};

static int parse_args(int argc, char **argv, export_opts *o)
{
    const char *pos[2];
    int npos = 0;
    const gib_option opts[] = {
        GIB_OPTION_TEXT("--camera", &o->camera, "NAME|INDEX",
                        "the scene's camera, by name or index (default 0)"),
        GIB_OPTION_FLOAT("--time", &o->time, -1e6, 1e6, "T",
                         "the instant a moving scene is posed at, seconds (default 0)"),
        GIB_OPTION_TEXT("--size", &o->size, "WxH", "the image size job.json asks for (256x256)"),
        GIB_OPTION_TEXT("--components", &o->components, "LIST",
                        "what job.json asks for: ao, direct, indirect, glossy, caustic (direct)"),
        {0}};
    int rc = gib_options_parse(&doc, opts, argc, argv, pos, &npos, 2);
    if (rc != GIB_OPTIONS_PROCEED)
        return rc;
    if (npos != 2) {
        fprintf(stderr, "gibench export: needs SCENE and DIR (got %d argument%s)\n", npos,
                npos == 1 ? "" : "s");
        gib_options_usage(stderr, &doc, opts);
        return 2;
    }
    o->scene_name = pos[0];
    o->dir = pos[1];
    gib_error err = {0};
    if (gib_parse_size("--size", o->size, &o->w, &o->h, &err) < 0) {
        fprintf(stderr, "gibench export: %s\n", err.msg);
        return 2;
    }
    return GIB_OPTIONS_PROCEED;
}

/* --camera as an index or a name of the scene's cameras: its index, or -1 after the error. */
static int find_camera(const gib_scene *s, const char *want)
{
    if (!want)
        return 0;
    char *end;
    const long i = strtol(want, &end, 10);
    if (isdigit((unsigned char)want[0]) && !*end && i >= 0 && i < (long)s->camera_count)
        return (int)i;
    for (uint32_t c = 0; c < s->camera_count; c++)
        if (!strcmp(s->cameras[c].name, want))
            return (int)c;
    fprintf(stderr, "gibench export: --camera '%s': scene '%s' has no camera of that name or "
                    "index; its cameras:", want, s->name);
    for (uint32_t c = 0; c < s->camera_count; c++)
        fprintf(stderr, " %u %s%s", c, s->cameras[c].name, c + 1 < s->camera_count ? "," : "\n");
    return -1;
}

/* The external the job names: `gibench export`, asking for --components. 0, or 2 after the
 * error. */
static int export_external(const export_opts *o, gib_external *x, gib_params *p)
{
    gib_error err = {0};
    memset(x, 0, sizeof *x);
    snprintf(x->name, sizeof x->name, "export");
    if (gib_external_set(x, "command", "gibench export", &err) < 0 ||
        gib_external_set(x, "components", o->components, &err) < 0 ||
        gib_external_finish(x, ".", &err) < 0) {
        fprintf(stderr, "gibench export: --%s\n", err.msg);
        return 2;
    }
    gib_params_default(&x->technique, p);
    return 0;
}

/* A .scene that reads the export back (stdout as a whole is one: the other lines are comments):
 * the glTF's camera, lights and materials, and what glTF does not hold (sky, exposure, closed),
 * which the glTF's scene extras also record. */
static void print_scene(const gib_scene *s, const char *scene_name, const char *dir)
{
    printf("; a .scene that reads it back (a data root must exist: $GIBENCH_SCENES)\n"
           "[scene]\ndescription = %s, exported by gibench export\ngltf = %s/scene.gltf\n"
           "camera = gltf\nlights = gltf\nmaterials = gltf\nexposure = %.9g\n", scene_name,
           dir, s->exposure);
    if (s->features & GIB_FEAT_SKY)
        printf("sky = %.9g %.9g %.9g\n", s->sky[0], s->sky[1], s->sky[2]);
    if (s->features & GIB_FEAT_CLOSED)
        printf("closed = 1\n");
}

static int write_export(const export_opts *o, const gib_scene *scene, int camera)
{
    gib_external x;
    gib_params p;
    gib_error err = {0};
    char dir[PATH_MAX];
    int rc = export_external(o, &x, &p);
    if (rc)
        return rc;
    if (gib_mkdirs(o->dir, &err) < 0 || !realpath(o->dir, dir)) {
        fprintf(stderr, "gibench export: DIR '%s': %s\n", o->dir,
                err.msg[0] ? err.msg : "cannot resolve it");
        return 1;
    }
    gib_scene posed;
    if (gib_scene_posed(scene, o->time, &posed, &err) < 0) {
        fprintf(stderr, "gibench export: --time %g: %s\n", o->time, err.msg);
        return 1;
    }
    const gib_external_request rq = {.x = &x, .scene = &posed, .scene_name = o->scene_name,
                                     .params = &p, .camera = camera, .width = o->w,
                                     .height = o->h, .warmup = 0, .frames = 1, .time = o->time};
    rc = gib_external_write_job(&rq, dir, &err);
    if (rc < 0)
        fprintf(stderr, "gibench export: %s\n", err.msg);
    else
        printf("; wrote %s/scene.gltf, scene.bin and job.json: scene %s, camera %d '%s', "
               "%dx%d, t = %g s\n", dir, scene->name, camera, scene->cameras[camera].name, o->w,
               o->h, o->time);
    if (rc == 0)
        print_scene(&posed, scene->name, dir);
    gib_scene_posed_free(&posed);
    return rc < 0 ? 1 : 0;
}

int gib_cmd_export(int argc, char **argv)
{
    export_opts o = {.size = "256x256", .components = "direct"};
    int rc = parse_args(argc, argv, &o);
    if (rc != GIB_OPTIONS_PROCEED)
        return rc;
    gib_scene scene;
    if ((rc = gib_cli_load_scene("export", o.scene_name, 0, &scene)) != 0)
        return rc;
    const int camera = find_camera(&scene, o.camera);
    rc = camera < 0 ? 2 : write_export(&o, &scene, camera);
    gib_scene_free(&scene);
    return rc;
}
