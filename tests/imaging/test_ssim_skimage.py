#!/usr/bin/python3
"""Checks gib_ssim_gray against scikit-image on the pairs ssim_dump writes (ARCHITECTURE.md "Metrics":
equal to structural_similarity(a, b, gaussian_weights=True, sigma=1.5,
use_sample_covariance=False, data_range=1) to 1e-4).

Usage: test_ssim_skimage.py SSIM_DUMP OUTDIR
A missing scikit-image is a failure, not a skip: the check is part of the contract."""
import os
import subprocess
import sys

TOL = 1e-4  # ARCHITECTURE.md's agreement bound; both sides use float64, so real gaps are ~1e-15
MIN_PAIRS = 5


def main():
    if len(sys.argv) != 3:
        print("usage: test_ssim_skimage.py SSIM_DUMP OUTDIR")
        return 2
    try:
        import numpy as np
        from skimage.metrics import structural_similarity
    except ImportError as e:
        print(f"FAIL: cannot import numpy/scikit-image ({e}); run `make deps` "
              "(Debian: python3-skimage python3-numpy) and use /usr/bin/python3")
        return 1

    exe, outdir = sys.argv[1], sys.argv[2]
    os.makedirs(outdir, exist_ok=True)
    subprocess.run([exe, outdir], check=True)

    failures = 0
    count = 0
    with open(os.path.join(outdir, "pairs.txt")) as f:
        for line in f:
            name, w, h, ours = line.split()
            w, h, ours = int(w), int(h), float(ours)
            a = np.fromfile(os.path.join(outdir, f"{name}_a.f32"), dtype="<f4")
            b = np.fromfile(os.path.join(outdir, f"{name}_b.f32"), dtype="<f4")
            a = a.reshape(h, w).astype(np.float64)
            b = b.reshape(h, w).astype(np.float64)
            ref = structural_similarity(a, b, gaussian_weights=True, sigma=1.5,
                                        use_sample_covariance=False, data_range=1)
            diff = abs(ours - ref)
            ok = diff <= TOL
            failures += not ok
            count += 1
            print(f"{'PASS' if ok else 'FAIL'} {name:22s} gib {ours:.10f} skimage {ref:.10f} "
                  f"|diff| {diff:.3e} tol {TOL:g}")
    if count < MIN_PAIRS:
        print(f"FAIL: only {count} pairs (need >= {MIN_PAIRS})")
        failures += 1
    print(f"{failures} failure(s) over {count} pairs")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
