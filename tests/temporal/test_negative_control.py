#!/usr/bin/env python3
"""The temporal error's negative control: `lrsm` with its structures frozen at the first frame
(rebuild = 0: voxels, light views and layers kept) against the same technique rebuilding them every
frame as the LRSM paper does (rebuild = 1), on cornell_moving (a 12 cm cube turning and travelling
a loop in the spot light), 96x96, 128^3 voxels, 8 frames 0.5 s apart ending at t = 3.5 s.

The frozen run still draws the cube where it is (its G-buffer is every frame's), but its shadow
cones read the first frame's voxels: the cube's shadow stays where it was and no shadow follows it.
So its `direct` changes between frames unlike the reference's, where the live run's shadow moves
with the cube. Measured (llvmpipe): temporal_rmse 0.0226 frozen against 0.0158 live (1.43x; the
frozen scale is 0.0311), temporal_flip 0.0169 against 0.0053 (3.2x). The checks leave room below
those: frozen >= 1.25x live in temporal_rmse and >= 2x in temporal_flip, and the live run under
the frozen scale. A metric that did not see motion (or a runner that read one frame N times) would
score the two alike and fail.
"""
import csv
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from script_checks import args, check, verdict, run as run_gibench  # noqa: E402

MATRIX = """[matrix]
description = negative control: lrsm with its structures rebuilt or kept from the first frame
scenes = cornell_moving
techniques = lrsm
sizes = 96x96
frames = 3
warmup = 1
times = 3.5
dt = 0.5
sequence = 8
ref_spp_direct = 16
ref_spp_indirect = 64
ref_spp_glossy = 16
[params.lrsm]
voxel_res = 128
rsm_res = 512
rebuild = 1, 0
[profile.quick]
"""



def main():
    a = args()
    os.makedirs(a.work)
    path = os.path.join(a.work, "control.matrix")
    with open(path, "w") as f:
        f.write(MATRIX)
    out = os.path.join(a.work, "out")
    p = run_gibench([a.gibench, "run", path, "--out", out, "--cache",
                      os.path.join(a.work, "cache"), "--no-history", "--no-images"])
    if p.returncode:
        sys.exit("gibench run failed:\n" + p.stdout + p.stderr)
    with open(os.path.join(out, "control.csv")) as f:
        rows = {(r["rebuild"], r["component"]): r for r in csv.DictReader(f)}
    live, frozen = rows[("1", "direct")], rows[("0", "direct")]
    lr, fr = float(live["temporal_rmse"]), float(frozen["temporal_rmse"])
    lf, ff = float(live["temporal_flip"]), float(frozen["temporal_flip"])
    scale = float(live["temporal_frozen"])
    print("direct: temporal_rmse live %.4g, frozen structures %.4g (%.2fx); temporal_flip %.4g, "
          "%.4g (%.2fx); frozen scale %.4g" % (lr, fr, fr / lr, lf, ff, ff / lf, scale))
    check(fr >= 1.25 * lr, "frozen structures' temporal_rmse >= 1.25x the live one's")
    check(ff >= 2.0 * lf, "frozen structures' temporal_flip >= 2x the live one's")
    check(lr < scale, "the live run changes more like the reference than standing still")
    return verdict("all checks passed")


if __name__ == "__main__":
    sys.exit(main())
