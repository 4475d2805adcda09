/* Fuzz target: a scene file (scenes/FORMAT.md), parsed, checked and built as `gibench` loads one:
 * every section and key, the procedural generators and their keys, motion, lights and cameras.
 * Mesh and texture paths resolve under GIBENCH_SCENES, which the target points at an empty folder
 * so that a path in the input cannot read the machine's files. */
#include <stdlib.h>
#include <unistd.h>

#include "scenes/scene.h"
#include "tests/fuzz/fuzz_common.h"

static char empty_root[] = "/tmp/gibench-fuzz-scenes-XXXXXX";

static void remove_empty_root(void)
{
    rmdir(empty_root);
}

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    if (mkdtemp(empty_root)) {
        setenv("GIBENCH_SCENES", empty_root, 1);
        atexit(remove_empty_root);
    }
    return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const char *path = fuzz_temp_file(data, size, "scene");
    if (!path)
        return 0;
    gib_scene scene;
    gib_error err;
    if (gib_scene_load(path, &scene, &err) == 0)
        gib_scene_free(&scene);
    return 0;
}
