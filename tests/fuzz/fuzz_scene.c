/* Fuzz target: a scene file (scenes/FORMAT.md), parsed, checked and built as `gibench` loads one:
 * every section and key, the procedural generators and their keys, motion, lights and cameras.
 * Mesh and texture paths resolve under GIBENCH_SCENES, which the target points at an empty folder
 * so that a path in the input cannot read the machine's files. */
#include <stdlib.h>

#include "scenes/scene.h"
#include "tests/fuzz/fuzz_common.h"

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    static char dir[] = "/tmp/gibench-fuzz-scenes-XXXXXX"; /* left behind: empty */
    if (mkdtemp(dir))
        setenv("GIBENCH_SCENES", dir, 1);
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
