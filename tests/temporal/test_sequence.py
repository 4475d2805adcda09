#!/usr/bin/env python3
"""Sequences in `gibench run` (harness/app/runner.h, matrix.h `sequence`, schema.h GIB_SEQ_COLUMNS).

`direct` on cornell_moving (a cube turning and travelling; its shadow moves), 64x64, 6 frames 0.1 s
apart ending at t = 0.5, checked:
- the row has the sequence columns; the per-frame mean lies between the best and the worst frame
  (the worst at least the mean), and the last frame's RMSE is the row's own;
- `direct` is deterministic (shadow map, no noise), so its frame-to-frame changes differ from the
  reference's only by the change of its per-frame error: temporal_rmse is at most sqrt(2) times the
  worst frame's RMSE (what two independent errors of that size give) and under half the frozen scale
  (a sequence that stood still), its perceptual version under 0.01;
- each frame's technique, reference and error previews are written (images/<matrix>/seq/);
- single-frame runs are unchanged: the same matrix without `sequence` writes the base columns alone
  and the same image metrics (rmse, ssim, flip, ...) as the sequence's row, whose last frame is the
  same image (its preview is byte for byte the row's).
"""
import csv
import math
import os
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from script_checks import args, check, verdict, run as run_gibench  # noqa: E402

MATRIX = """[matrix]
description = sequence test: direct on the moving Cornell box
scenes = cornell_moving
techniques = direct
sizes = 64x64
frames = 3
warmup = 1
times = 0.5
dt = 0.1
{sequence}
ref_spp_direct = 16
[profile.quick]
"""



def run(gibench, work, name, sequence):
    path = os.path.join(work, name + ".matrix")
    with open(path, "w") as f:
        f.write(MATRIX.format(sequence=sequence))
    out = os.path.join(work, "out")
    p = run_gibench([gibench, "run", path, "--out", out, "--cache", os.path.join(work, "cache"),
                      "--no-history"])
    if p.returncode:
        sys.exit("gibench run failed:\n" + p.stdout + p.stderr)
    with open(os.path.join(out, name + ".csv")) as f:
        rows = list(csv.DictReader(f))
    with open(os.path.join(out, name + ".csv")) as f:
        head = f.readline().rstrip("\n").split(",")
    return rows[0], head, os.path.join(out, "images", name)


def base_columns(gibench):
    import json
    p = subprocess.run([gibench, "schema"], capture_output=True, text=True, check=True)
    s = json.loads(p.stdout)
    return [c["name"] for c in s["runs"]["columns"]], [c["name"] for c in s["sequence"]["columns"]]


def main():
    a = args()
    os.makedirs(a.work)
    base, seq_cols = base_columns(a.gibench)
    r, head, images = run(a.gibench, a.work, "seq", "sequence = 6")
    check(head[:len(base) + len(seq_cols)] == base + seq_cols, "a sequence table: base columns, "
          "then the sequence columns")
    f = {k: float(r[k]) for k in seq_cols + ["rmse"] if k not in ("sequence", "seq_worst_frame")}
    check(r["status"] == "ok" and r["sequence"] == "6", "the row is ok with 6 frames")
    check(0 < f["seq_rmse_mean"] <= f["seq_rmse_worst"], "mean %.4g <= worst %.4g"
          % (f["seq_rmse_mean"], f["seq_rmse_worst"]))
    check(f["rmse"] <= f["seq_rmse_worst"] + 1e-12, "the last frame's rmse %.4g within the worst"
          % f["rmse"])
    bound = math.sqrt(2) * f["seq_rmse_worst"]
    check(f["temporal_rmse"] <= bound, "temporal_rmse %.4g <= sqrt(2) x worst frame %.4g"
          % (f["temporal_rmse"], bound))
    check(f["temporal_rmse"] < 0.5 * f["temporal_frozen"], "temporal_rmse under half the frozen "
          "scale %.4g" % f["temporal_frozen"])
    check(f["temporal_flip"] < 0.01, "temporal_flip %.4g < 0.01" % f["temporal_flip"])
    seq_dir = os.path.join(images, "seq")
    for k in range(6):
        for suffix in ("", "_ref", "_error"):
            name = "%s_f%02d%s.png" % (r["image"], k, suffix)
            if not os.path.exists(os.path.join(seq_dir, name)):
                check(False, "frame image %s written" % name)
    with open(os.path.join(seq_dir, r["image"] + "_f05.png"), "rb") as a5, \
            open(os.path.join(images, r["image"] + ".png"), "rb") as last:
        check(a5.read() == last.read(), "the sequence's last frame is the row's image")
    s, shead, _ = run(a.gibench, a.work, "single", "")
    check(shead == base, "a single-frame table has the base columns alone")
    for k in ("rmse", "rel_rmse", "mean_ratio", "psnr", "ssim", "flip", "hdrflip", "black_rmse"):
        check(s[k] == r[k], "single-frame %s %s equals the sequence row's" % (k, s[k]))
    return verdict("all checks passed")


if __name__ == "__main__":
    sys.exit(main())
