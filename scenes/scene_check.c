/* gibench — checks on a parsed .scene file that need the whole file (required keys, directions,
 * cameras), and whether the shared data it needs is present. Every message names file:line. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "scene_internal.h"

int gib_scene_fail_at(const gib_scene_spec *s, int line, gib_error *err, const char *fmt, ...)
{
    char msg[1536];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    return gib_fail(err, "%s:%d: %s", s->path, line, msg);
}

static float len3(const float v[3])
{
    return sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

/* A mesh's motion keys (FORMAT.md, "Motion"): keyframes need times and one value per time;
 * waves belong to a `water` mesh, which needs them and takes no keyframes. */
static int check_motion(const gib_scene_spec *s, gib_mesh_spec *m, gib_error *err)
{
    const int water = strcmp(m->procedural, "water") == 0;
    const int any_key = m->keys_line || m->key_rotate_line || m->key_translate_line ||
                        m->pivot_line || m->loop_line;
    if (m->waves_line && !water)
        return gib_scene_fail_at(s, m->waves_line, err,
                                 "mesh '%s': 'waves' applies only to 'procedural = water'",
                                 m->name);
    if (water && !m->waves_line)
        return gib_scene_fail_at(s, m->procedural_line, err,
                                 "mesh '%s': a water surface needs 'waves = amplitude wavelength "
                                 "direction_deg speed' (one to %d waves)",
                                 m->name, GIB_MOTION_MAX_WAVES);
    if (!any_key)
        return 0;
    const int first = m->keys_line ? m->keys_line
                      : m->key_rotate_line ? m->key_rotate_line
                      : m->key_translate_line ? m->key_translate_line
                      : m->pivot_line ? m->pivot_line
                                      : m->loop_line;
    if (water)
        return gib_scene_fail_at(s, first, err,
                                 "mesh '%s': a water surface moves by its waves; keyframes apply "
                                 "to other meshes",
                                 m->name);
    if (!m->keys_line)
        return gib_scene_fail_at(s, first, err,
                                 "mesh '%s': keyframes need 'keys = t0 t1 ...' (times in seconds)",
                                 m->name);
    if (!m->key_rotate_line && !m->key_translate_line)
        return gib_scene_fail_at(s, m->keys_line, err,
                                 "mesh '%s': 'keys' needs 'key_rotate' and/or 'key_translate' "
                                 "(3 numbers per key)",
                                 m->name);
    for (int k = 0; k < 2; k++) {
        const int line = k ? m->key_translate_line : m->key_rotate_line;
        const int n = k ? m->key_translate_n : m->key_rotate_n;
        if (line && n != 3 * m->key_count)
            return gib_scene_fail_at(s, line, err,
                                     "mesh '%s': '%s' has %d numbers; 'keys' gives %d times, so "
                                     "%d are needed (3 per key)",
                                     m->name, k ? "key_translate" : "key_rotate", n, m->key_count,
                                     3 * m->key_count);
    }
    if (m->loop && m->key_count < 2)
        return gib_scene_fail_at(s, m->loop_line, err,
                                 "mesh '%s': 'loop = 1' needs at least 2 keys", m->name);
    if (!m->pivot_line)
        memcpy(m->pivot, m->translate, sizeof m->pivot); /* about the mesh's own origin */
    return 0;
}

/* A mesh's source: a file or a known generator (not both), and generator keys only on a
 * generator, as that generator takes them. */
static int check_mesh(const gib_scene_spec *s, gib_mesh_spec *m, gib_error *err)
{
    if (!m->file[0] && !m->procedural[0])
        return gib_scene_fail_at(s, m->line, err, "mesh '%s' needs 'file' or 'procedural'",
                                 m->name);
    if (m->file[0] && m->procedural[0])
        return gib_scene_fail_at(s, m->procedural_line, err,
                                 "mesh '%s' has both 'file' and "
                                 "'procedural'; use one [mesh.NAME] section for each",
                                 m->name);
    if (m->procedural[0] && !gib_procedural_known(m->procedural))
        return gib_scene_fail_at(s, m->procedural_line, err,
                                 "mesh '%s': unknown procedural generator "
                                 "'%s' (known: %s)",
                                 m->name, m->procedural, gib_procedural_names());
    if (m->params.set) {
        char msg[768];
        int key = -1;
        if (!m->procedural[0]) {
            for (key = 0; !(m->params.set & (1u << key)); key++)
                ;
            snprintf(msg, sizeof msg, "'%s' applies only to procedural meshes, not to 'file'",
                     gib_proc_key_get(key)->name);
            return gib_scene_fail_at(s, m->params.line[key], err, "mesh '%s': %s", m->name, msg);
        }
        if (gib_procedural_check(m->procedural, &m->params, &key, msg, sizeof msg))
            return gib_scene_fail_at(s, key >= 0 ? m->params.line[key] : m->procedural_line, err,
                                     "mesh '%s': %s", m->name, msg);
    }
    return 0;
}

/* A light's required keys; its direction (from 'direction' or 'target') made unit length. */
static int check_light(const gib_scene_spec *s, gib_light_spec *l, gib_error *err)
{
    gib_light *L = &l->l;
    if (!l->type_set)
        return gib_scene_fail_at(s, l->line, err,
                                 "light '%s' needs 'type = point | spot | "
                                 "directional'",
                                 L->name);
    if (!l->intensity_set)
        return gib_scene_fail_at(s, l->line, err,
                                 "light '%s' needs 'intensity = r g b' (W/sr for "
                                 "point and spot lights, W/m^2 for directional)",
                                 L->name);
    if (L->type != GIB_LIGHT_DIRECTIONAL && !l->position_set)
        return gib_scene_fail_at(s, l->line, err, "light '%s' needs 'position = x y z'", L->name);
    if (L->type == GIB_LIGHT_POINT) {
        /* Unused by a point light, but scene.h promises a unit vector. */
        float n = len3(L->direction);
        for (int k = 0; k < 3; k++)
            L->direction[k] = n > 0.0f ? L->direction[k] / n : (k == 1 ? -1.0f : 0.0f);
        return 0;
    }
    if (l->direction_set && l->target_set)
        return gib_scene_fail_at(s, l->target_line, err,
                                 "light '%s': give 'direction' or 'target', "
                                 "not both",
                                 L->name);
    if (l->target_set) {
        if (L->type == GIB_LIGHT_DIRECTIONAL)
            return gib_scene_fail_at(s, l->target_line, err,
                                     "light '%s': a directional light takes "
                                     "'direction', not 'target'",
                                     L->name);
        for (int k = 0; k < 3; k++)
            L->direction[k] = l->target[k] - L->position[k];
    } else if (!l->direction_set) {
        return gib_scene_fail_at(s, l->line, err, "light '%s' needs 'direction = x y z'%s",
                                 L->name, L->type == GIB_LIGHT_SPOT ? " or 'target = x y z'" : "");
    }
    float n = len3(L->direction);
    if (!(n > 0.0f))
        return gib_scene_fail_at(s, l->target_set ? l->target_line : l->direction_line, err,
                                 "light '%s': the direction has zero length", L->name);
    for (int k = 0; k < 3; k++)
        L->direction[k] /= n;
    return 0;
}

/* A camera's eye and target, apart, with an 'up' not along the view. */
static int check_camera(const gib_scene_spec *s, const gib_camera_spec *cs, gib_error *err)
{
    const gib_camera *C = &cs->c;
    if (!cs->eye_set || !cs->target_set)
        return gib_scene_fail_at(s, cs->line, err,
                                 "camera '%s' needs 'eye = x y z' and "
                                 "'target = x y z'",
                                 C->name);
    const float f[3] = {C->target[0] - C->eye[0], C->target[1] - C->eye[1],
                        C->target[2] - C->eye[2]};
    const float x[3] = {f[1] * C->up[2] - f[2] * C->up[1], f[2] * C->up[0] - f[0] * C->up[2],
                        f[0] * C->up[1] - f[1] * C->up[0]};
    if (!(len3(f) > 0.0f))
        return gib_scene_fail_at(s, cs->line, err, "camera '%s': eye and target coincide",
                                 C->name);
    if (!(len3(x) > 1e-6f * len3(f) * len3(C->up)))
        return gib_scene_fail_at(s, cs->line, err,
                                 "camera '%s': 'up' is parallel to the view "
                                 "direction (or zero)",
                                 C->name);
    return 0;
}

/* [scene] gltf = FILE (FORMAT.md, "glTF scenes"): its meshes become the mesh 'gltf', found under
 * the data root like every mesh file; camera, lights and materials = gltf need the key. */
static int gltf_mesh(gib_scene_spec *s, gib_error *err)
{
    const int line = s->camera_line ? s->camera_line : s->lights_line ? s->lights_line
                                                                      : s->materials_line;
    if (!s->gltf[0]) {
        if (line)
            return gib_scene_fail_at(s, line, err,
                                     "[scene]: camera, lights or materials = gltf need "
                                     "'gltf = FILE' (a glTF 2.0 .gltf or .glb under the data "
                                     "root)");
        return 0;
    }
    char fmt[8];
    int gz = 0;
    if (gib_mesh_format(s->gltf, fmt, &gz, err) || gz ||
        (strcmp(fmt, "gltf") != 0 && strcmp(fmt, "glb") != 0)) {
        return gib_scene_fail_at(s, s->gltf_line, err,
                                 "[scene]: 'gltf' names '%s'; it takes a .gltf or .glb file "
                                 "(glTF 2.0, not gzipped)", s->gltf);
    }
    for (int i = 0; i < s->mesh_count; i++)
        if (strcmp(s->meshes[i].name, "gltf") == 0)
            return gib_scene_fail_at(s, s->meshes[i].line, err,
                                     "[mesh.gltf]: the name 'gltf' is the [scene] gltf file's "
                                     "mesh; name this mesh otherwise");
    gib_mesh_spec *m = gib_realloc_array(s->meshes, (size_t)s->mesh_count + 1, sizeof *m, err);
    if (!m)
        return -1;
    s->meshes = m;
    m = &s->meshes[s->mesh_count++];
    memset(m, 0, sizeof *m);
    snprintf(m->name, sizeof m->name, "gltf");
    snprintf(m->file, sizeof m->file, "%s", s->gltf);
    m->line = m->file_line = s->gltf_line;
    m->scale[0] = m->scale[1] = m->scale[2] = 1.0f;
    m->smooth_angle_deg = 60.0f;
    m->gltf_materials = s->gltf_materials;
    return 0;
}

int gib_scene_validate(gib_scene_spec *s, gib_error *err)
{
    if (!s->scene_line)
        return gib_scene_fail_at(s, 1, err,
                                 "no [scene] section (every scene file starts with one)");
    if (gltf_mesh(s, err))
        return -1;
    for (int i = 0; i < s->mesh_count; i++)
        if (check_mesh(s, &s->meshes[i], err))
            return -1;
    for (int i = 0; i < s->mesh_count; i++)
        if (check_motion(s, &s->meshes[i], err))
            return -1;
    if (s->mesh_count == 0)
        return gib_scene_fail_at(s, s->scene_line, err, "the scene has no [mesh.NAME] section");
    for (int i = 0; i < s->material_count; i++) {
        gib_material_spec *m = &s->materials[i];
        if (m->mirror && !(m->set & GIB_MS_SPECULAR))
            return gib_scene_fail_at(s, m->key_line[3], err,
                                     "material '%s': 'mirror = 1' needs "
                                     "'specular = r g b' (the mirror's reflectance)",
                                     m->name);
        /* rho_d + rho_s <= 1 is checked in scene_build, once overrides are merged with what the
         * mesh file said. */
    }
    for (int i = 0; i < s->light_count; i++)
        if (check_light(s, &s->lights[i], err))
            return -1;
    for (int i = 0; i < s->camera_count; i++)
        if (check_camera(s, &s->cameras[i], err))
            return -1;
    if (s->camera_count == 0 && !s->gltf_camera)
        return gib_scene_fail_at(s, s->scene_line, err,
                                 "the scene has no [camera.NAME] section (the first "
                                 "one is the default view) and no 'camera = gltf'");
    return 0;
}

/* ------------------------------------------------------------------ shared data */

static const char *const where_to_get =
    "Download it from Morgan McGuire's Computer Graphics Archive "
    "(https://casual-effects.com/data/; Sponza, Sibenik) or, for the bunny and the dragon, the "
    "Stanford 3D Scanning Repository (https://graphics.stanford.edu/data/3Dscanrep/), unpack it "
    "so that the folder exists under one data root, and set GIBENCH_SCENES to that root (default: "
    "../shared/scenes beside the project). The procedural scenes (cornell, plane_box) need no "
    "data.";

int gib_scene_check_data(const gib_scene_spec *spec, gib_error *err)
{
    int needs_files = spec->data[0] != '\0';
    int first_line = spec->data_line;
    for (int i = 0; i < spec->mesh_count; i++)
        if (spec->meshes[i].file[0]) {
            if (!needs_files)
                first_line = spec->meshes[i].file_line;
            needs_files = 1;
        }
    if (!needs_files)
        return 0;
    const char *root = gib_scene_data_root();
    if (!root) {
        gib_scene_fail_at(
            spec, first_line, err,
            "scene '%s' needs shared data%s%s%s, and there is no data "
            "root: GIBENCH_SCENES is not set and ../shared/scenes beside the project does "
            "not exist. %s",
            spec->name, spec->data[0] ? " (folder '" : "", spec->data, spec->data[0] ? "')" : "",
            where_to_get);
        return GIB_SCENE_UNAVAILABLE;
    }
    if (spec->data[0]) {
        char dir[GIB_PATH_MAX], resolved[GIB_PATH_MAX];
        if (gib_path_join(root, spec->data, dir, sizeof dir) ||
            gib_path_resolve_ci(dir, resolved, sizeof resolved) || !gib_path_is_dir(resolved)) {
            gib_scene_fail_at(spec, spec->data_line, err,
                              "scene '%s' needs the shared data folder '%s', "
                              "which is not in the data root '%s'. %s",
                              spec->name, spec->data, root, where_to_get);
            return GIB_SCENE_UNAVAILABLE;
        }
    }
    return 0;
}
