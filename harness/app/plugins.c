/* gibench — techniques from plugins (docs/adding-a-technique.md, "As a plugin"): shared libraries
 * named by `--plugin PATH` (a global option of every command, repeatable) and by $GIBENCH_PLUGINS
 * (paths joined by ':'), opened with dlopen before the command runs. Each exports GIB_PLUGIN_ENTRY
 * (techniques/technique.h); its contract version must be this binary's, and its techniques join
 * the registry (gib_technique_register), where `list`, matrices, `render` and `check-technique`
 * find them as they find the built-in ones. The functions a plugin calls are this executable's,
 * which exports its symbols (cmake/gl.cmake: ENABLE_EXPORTS). */
#include <dlfcn.h>
#include <stdlib.h>
#include <string.h>

#include "app.h"

int gib_plugin_load(const char *path, gib_error *err)
{
    /* The path is kept for the process's life: the registry names it as the technique's origin. */
    char *file = strdup(path);
    if (!file)
        return gib_fail(err, "plugin %s: out of memory", path);
    void *lib = dlopen(file, RTLD_NOW | RTLD_LOCAL);
    if (!lib) {
        const char *why = dlerror();
        gib_fail(err, "plugin %s cannot be loaded: %s", path, why ? why : "dlopen failed");
        free(file);
        return -1;
    }
    gib_plugin_entry_fn entry;
    *(void **)&entry = dlsym(lib, GIB_PLUGIN_ENTRY);
    if (!entry) {
        gib_fail(err, "plugin %s exports no '%s' (docs/adding-a-technique.md, \"As a plugin\")",
                 path, GIB_PLUGIN_ENTRY);
        dlclose(lib);
        free(file);
        return -1;
    }
    int count = 0, version = -1;
    const gib_technique *const *list = entry(&count, &version);
    if (version != GIB_CONTRACT_VERSION) {
        gib_fail(err, "plugin %s was built against technique contract version %d, this gibench "
                 "implements version %d (GIB_CONTRACT_VERSION): rebuild it against this gibench's "
                 "headers", path, version, GIB_CONTRACT_VERSION);
        dlclose(lib);
        free(file);
        return -1;
    }
    if (!list || count <= 0) {
        gib_fail(err, "plugin %s: %s returned no technique", path, GIB_PLUGIN_ENTRY);
        dlclose(lib);
        free(file);
        return -1;
    }
    /* The library stays open: the registry holds its descriptors until the process ends. */
    for (int i = 0; i < count; i++)
        if (gib_technique_register(list[i], file, err) < 0)
            return -1;
    return 0;
}

int gib_plugins_from_args(int *argc, char **argv, gib_error *err)
{
    const char *env = getenv("GIBENCH_PLUGINS");
    if (env && env[0]) {
        char *paths = strdup(env), *save = NULL;
        if (!paths)
            return gib_fail(err, "GIBENCH_PLUGINS: out of memory");
        int rc = 0;
        for (char *p = strtok_r(paths, ":", &save); p && rc == 0; p = strtok_r(NULL, ":", &save))
            rc = gib_plugin_load(p, err);
        free(paths);
        if (rc < 0)
            return gib_error_prefix(err, "GIBENCH_PLUGINS");
    }
    int out = 1;
    for (int i = 1; i < *argc; i++) {
        const char *path = NULL;
        if (!strcmp(argv[i], "--plugin")) {
            if (i + 1 >= *argc)
                return gib_fail(err, "--plugin needs a value (PATH: a technique plugin)");
            path = argv[++i];
        } else if (!strncmp(argv[i], "--plugin=", 9)) {
            path = argv[i] + 9;
        } else {
            argv[out++] = argv[i];
            continue;
        }
        if (gib_plugin_load(path, err) < 0)
            return -1;
    }
    argv[out] = NULL;
    *argc = out;
    return 0;
}
