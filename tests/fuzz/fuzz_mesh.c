/* Fuzz target: a mesh file as gibench drives assimp (scenes/mesh_import.c): the first byte picks
 * the kind (byte % 8: OBJ, PLY, gzipped PLY, OFF, STL, glTF, GLB, gzipped OFF: every format
 * gibench reads, so the checks of scenes/mesh_bounds.c and gltf_bounds.c and assimp's importers
 * behind them are all reached), the rest is the file. A glTF's buffer uri resolves in $TMPDIR. A bad mesh must be a clear error: a
 * crash, leak or sanitizer report in our code (the import, the gzip reader, the conversion to the
 * scene's arrays) is a bug. An OBJ's `mtllib` resolves beside the file, in $TMPDIR. */
#include <string.h>

#include "scenes/scene_internal.h"
#include "tests/fuzz/fuzz_common.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1)
        return 0;
    static const char *const kinds[] = {"obj", "ply", "ply.gz", "off", "stl", "gltf", "glb", "off.gz"};
    const char *path = fuzz_temp_file(data + 1, size - 1, kinds[data[0] % 8]);
    if (!path)
        return 0;
    gib_geom g;
    memset(&g, 0, sizeof g);
    uint64_t hash = 0;
    gib_error err;
    gib_mesh_import(path, 60.0f, &g, &hash, &err);
    gib_geom_free(&g);
    return 0;
}
