#!/usr/bin/env python3
"""Quality-regression check: renders tests/quality/quality.matrix and compares each row's RMSE and
SSIM with tests/quality/baselines.csv (the last accepted run).

A row fails when:
  - its status is not `ok` (NaN/Inf, shader failure, overflow...), or it is missing;
  - RMSE rose by more than RMSE_REL_TOL of the baseline (plus RMSE_ABS_TOL for near-zero errors);
  - SSIM fell by more than SSIM_TOL.
Tolerances: the runs are deterministic on one build and renderer (llvmpipe gives bit-identical
images run to run), so any change comes from code; 2% of RMSE and 0.002 of SSIM let a different
rasteriser (a GPU, another Mesa) pass while a real regression — a shadow-map bias change that
leaks light, a wrong falloff — moves RMSE by tens of percent.

`--update FILE` writes the current numbers as the new baselines (make baselines): deliberate, never
automatic.
"""
import argparse
import csv
import os
import subprocess
import sys

RMSE_REL_TOL = 0.02
RMSE_ABS_TOL = 1e-6
SSIM_TOL = 0.002
KEY = ("scene", "technique", "component", "params", "width", "height")
HERE = os.path.dirname(os.path.abspath(__file__))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--gibench", required=True)
    ap.add_argument("--work", required=True)
    ap.add_argument("--baselines", default=os.path.join(HERE, "baselines.csv"))
    ap.add_argument("--update", metavar="FILE")
    a = ap.parse_args()
    out = os.path.join(a.work, "results")
    csv_path = os.path.join(out, "quality.csv")
    if os.path.exists(csv_path):
        os.remove(csv_path)  # always a fresh run: this is a check, not a resumable benchmark
    cmd = [a.gibench, "run", os.path.join(HERE, "quality.matrix"), "--profile", "quick", "--out", out,
           "--cache", os.path.join(a.work, "cache"), "--no-images"]
    print("check_quality:", " ".join(cmd), flush=True)
    rc = subprocess.run(cmd).returncode  # 1 when a row is not ok: the rows are judged below
    if not os.path.exists(csv_path):
        sys.exit(f"check_quality: gibench run exited {rc} and wrote no {csv_path}")
    with open(csv_path, newline="") as f:
        rows = {tuple(r[k] for k in KEY): r for r in csv.DictReader(f)}
    if a.update:
        with open(a.update, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(KEY + ("rmse", "ssim", "renderer", "git_revision"))
            for k, r in sorted(rows.items()):
                if r["status"] != "ok":
                    sys.exit(f"check_quality: not accepting a baseline from a row with status {r['status']}: {k}")
                w.writerow(k + (r["rmse"], r["ssim"], r["renderer"], r["git_revision"]))
        print(f"check_quality: wrote {len(rows)} baselines to {a.update}")
        return
    if not os.path.exists(a.baselines):
        sys.exit(f"check_quality: no baselines at {a.baselines}: run `make baselines` once and commit it")
    fails = passes = 0
    with open(a.baselines, newline="") as f:
        for b in csv.DictReader(f):
            k = tuple(b[x] for x in KEY)
            r = rows.get(k)
            name = " ".join(k)
            if r is None:
                print(f"FAIL {name}: no row in this run")
                fails += 1
                continue
            if r["status"] != "ok":
                print(f"FAIL {name}: status {r['status']}: {r['message']}")
                fails += 1
                continue
            rmse, ssim = float(r["rmse"]), float(r["ssim"])
            brmse, bssim = float(b["rmse"]), float(b["ssim"])
            limit = brmse * (1 + RMSE_REL_TOL) + RMSE_ABS_TOL
            ok = rmse <= limit and ssim >= bssim - SSIM_TOL
            print(f"{'PASS' if ok else 'FAIL'} {name}: rmse {rmse:.6g} (baseline {brmse:.6g}, limit {limit:.6g}), "
                  f"ssim {ssim:.5f} (baseline {bssim:.5f}, limit {bssim - SSIM_TOL:.5f})")
            fails += not ok
            passes += ok
    print(f"{passes} passed, {fails} failed")
    sys.exit(1 if fails or not passes else 0)


if __name__ == "__main__":
    main()
