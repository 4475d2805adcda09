/* Fuzz target: an EXR as the project reads one (harness/imaging/exr.c through OpenEXR's C core):
 * header attributes, channels, pixels; then, as the reference cache does with an entry, the seal
 * over pixels and header (gib_ref_seal_ok). A reference cache entry is exactly such a file. */
#include <stdlib.h>

#include "harness/app/app.h"
#include "harness/imaging/image.h"
#include "tests/fuzz/fuzz_common.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const char *path = fuzz_temp_file(data, size, "exr");
    if (!path)
        return 0;
    gib_image img;
    gib_kv *attrs = NULL;
    int n = 0;
    gib_error err;
    if (gib_exr_read(path, &img, &attrs, &n, &err) == 0) {
        static const gib_kv want[] = {{"component", "indirect"}, {"spp", "64"}};
        gib_ref_seal_ok(&img, want, 2, attrs, n);
        gib_image_free(&img);
    }
    free(attrs);
    return 0;
}
