// Prints the reference implementation's FLIP means for the pairs `test_flip --dump DIR` writes,
// the source of test_flip.c's expected values. Not built by CMake (it needs NVIDIA's FLIP.h,
// BSD-3-Clause, github.com/NVlabs/flip src/cpp/FLIP.h, which is not part of this repository):
//   c++ -O2 -std=c++17 -I PATH/TO/flip/src/cpp tests/imaging/flip_ref_driver.cpp -o flip_ref_driver
//   build/tests/imaging/test_flip --dump /tmp/pairs && ./flip_ref_driver /tmp/pairs/*.f32
// File format: int32 width, height, hdr flag; then width*height*3 floats reference, same test.
#include "FLIP.h"

#include <cstdio>
#include <vector>

int main(int argc, char** argv)
{
    for (int a = 1; a < argc; a++) {
        FILE* f = std::fopen(argv[a], "rb");
        int dims[3];
        if (!f || std::fread(dims, sizeof dims, 1, f) != 1) {
            std::fprintf(stderr, "cannot read %s\n", argv[a]);
            return 1;
        }
        size_t n = size_t(dims[0]) * dims[1] * 3;
        std::vector<float> ref(n), test(n);
        if (std::fread(ref.data(), 4, n, f) != n || std::fread(test.data(), 4, n, f) != n) {
            std::fprintf(stderr, "short file %s\n", argv[a]);
            return 1;
        }
        std::fclose(f);
        FLIP::Parameters p;
        float mean = -1, *map = nullptr;
        FLIP::evaluate(ref.data(), test.data(), dims[0], dims[1], dims[2] != 0, p, false, true, mean, &map);
        // FLIP.h sums the mean in float; over millions of pixels that drifts by ~1e-5, so the
        // mean of its map summed in double is printed too.
        double sum = 0;
        for (size_t i = 0; i < n / 3; i++)
            sum += map[i];
        std::printf("%s %s mean %.7f (double sum %.7f) ppd %.7f start %.7f stop %.7f exposures %d\n",
                    argv[a], dims[2] ? "HDR" : "LDR", mean, sum / double(n / 3), p.PPD,
                    p.startExposure, p.stopExposure, p.numExposures);
        delete[] map;
    }
    return 0;
}
