/* Fuzz target: a matrix file (harness/matrices, README "Matrices"), expanded and validated for
 * both profiles as `gibench run` does before rendering anything: sections, techniques, parameter
 * lists and their values, sizes, profiles and their overrides. */
#include "harness/app/matrix.h"
#include "tests/fuzz/fuzz_common.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const char *path = fuzz_temp_file(data, size, "matrix");
    if (!path)
        return 0;
    static const char *const profiles[] = {"quick", "paper"};
    for (int i = 0; i < 2; i++) {
        gib_matrix m;
        gib_error err;
        if (gib_matrix_load(path, profiles[i], &m, &err) == 0)
            gib_matrix_free(&m);
    }
    return 0;
}
