/* gibench — the public entry points of scene.h: load a scene by name or path, list the scene
 * files, free a scene. */
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene_internal.h"

static int ends_with(const char *s, const char *suffix)
{
    size_t n = strlen(s), k = strlen(suffix);
    return n >= k && strcmp(s + n - k, suffix) == 0;
}

/* "cornell" -> <scene dir>/cornell.scene; a path (with '/' or ending in .scene) as given. */
static int scene_path(const char *name_or_path, char *out, size_t out_len, gib_error *err)
{
    if (!name_or_path || !name_or_path[0])
        return gib_fail(err, "no scene name given");
    int n;
    if (strchr(name_or_path, '/') || ends_with(name_or_path, ".scene"))
        n = snprintf(out, out_len, "%s", name_or_path);
    else
        n = snprintf(out, out_len, "%s/%s.scene", gib_scene_dir(), name_or_path);
    if (n < 0 || (size_t)n >= out_len)
        return gib_fail(err, "scene path too long: '%s'", name_or_path);
    if (!gib_path_is_file(out)) {
        if (strchr(name_or_path, '/') || ends_with(name_or_path, ".scene"))
            return gib_fail(err, "scene file '%s' not found", out);
        return gib_fail(err,
                        "no scene named '%s': '%s' does not exist (`gibench list` shows the "
                        "scenes)",
                        name_or_path, out);
    }
    return 0;
}

int gib_scene_load(const char *name_or_path, gib_scene *scene, gib_error *err)
{
    memset(scene, 0, sizeof *scene);
    char path[GIB_PATH_MAX];
    if (scene_path(name_or_path, path, sizeof path, err))
        return -1;
    gib_scene_spec spec;
    if (gib_scene_parse(path, &spec, err))
        return -1;
    int rc = gib_scene_check_data(&spec, err);
    if (rc == 0)
        rc = gib_scene_build(&spec, scene, err) ? -1 : 0;
    if (rc == 0 && scene->ignored[0]) /* FORMAT.md, "glTF scenes": never dropped silently */
        fprintf(stderr, "gibench: warning: %s: ignored: %s\n", path, scene->ignored);
    gib_scene_spec_free(&spec);
    return rc;
}

void gib_scene_free(gib_scene *scene)
{
    if (!scene)
        return;
    free(scene->positions);
    free(scene->normals);
    free(scene->uvs);
    free(scene->indices);
    free(scene->tri_material);
    free(scene->ranges);
    free(scene->materials);
    if (scene->textures)
        for (uint32_t i = 0; i < scene->texture_count; i++)
            free(scene->textures[i].rgba);
    free(scene->textures);
    free(scene->lights);
    free(scene->cameras);
    gib_scene_free_motion(scene);
    memset(scene, 0, sizeof *scene);
}

static int cmp_str(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

int gib_scene_list(gib_scene_info **out, int *count, gib_error *err)
{
    *out = NULL;
    *count = 0;
    const char *dir = gib_scene_dir();
    DIR *d = opendir(dir);
    if (!d)
        return gib_fail(err, "cannot open the scene folder '%s'", dir);
    char **names = NULL;
    int n = 0, rc = 0;
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        if (!ends_with(e->d_name, ".scene") || e->d_name[0] == '.')
            continue;
        char **nn = gib_realloc_array(names, (size_t)n + 1, sizeof *names, err);
        if (!nn) {
            rc = -1;
            break;
        }
        names = nn;
        if (!(names[n] = gib_strdup(e->d_name))) {
            rc = gib_fail_code(err, GIB_ERR_OUT_OF_MEMORY, "out of memory listing scenes");
            break;
        }
        n++;
    }
    closedir(d);
    gib_scene_info *info = NULL;
    if (rc == 0) {
        qsort(names, (size_t)n, sizeof *names, cmp_str);
        info = gib_calloc((size_t)n + 1, sizeof *info, err);
        if (!info)
            rc = -1;
    }
    for (int i = 0; i < n && rc == 0; i++) {
        gib_scene_info *si = &info[i];
        snprintf(si->name, sizeof si->name, "%.*s", (int)(strlen(names[i]) - 6), names[i]);
        char path[GIB_PATH_MAX];
        snprintf(path, sizeof path, "%s/%s", dir, names[i]);
        gib_scene_spec spec;
        gib_error e2;
        /* A scene file with an error is listed as unavailable, with the error as the reason, so
         * that one broken file does not hide the others. */
        if (gib_scene_parse(path, &spec, &e2)) {
            si->available = 0;
            snprintf(si->why_unavailable, sizeof si->why_unavailable, "%.*s",
                     (int)sizeof si->why_unavailable - 1, e2.msg);
            continue;
        }
        snprintf(si->description, sizeof si->description, "%s", spec.description);
        si->available = gib_scene_check_data(&spec, &e2) == 0;
        if (!si->available)
            snprintf(si->why_unavailable, sizeof si->why_unavailable, "%.*s",
                     (int)sizeof si->why_unavailable - 1, e2.msg);
        gib_scene_spec_free(&spec);
    }
    for (int i = 0; i < n; i++)
        free(names[i]);
    free(names);
    if (rc) {
        free(info);
        return -1;
    }
    *out = info;
    *count = n;
    return 0;
}
