#!/usr/bin/env python3
"""A timing-only run (`gibench run --timing-only --warmup auto`), as the device script makes it:
rows that are timed but not scored (no reference rendered, no image written, the metric columns
empty, the message saying so), a warm-up that stopped once the frame time settled (its count in the
row), each row's technique hash equal to the sources' (harness/reporting/source_hash.py), and per pass the
pipeline statistics and the kind they imply: the G-buffer is raster work, multires_ir's splitting
has compute work, and the counts of two runs are equal (they count work, not time)."""
import csv
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "harness"))
sys.path.insert(0, os.path.join(ROOT, "tests", "common"))
from reporting import source_hash  # noqa: E402
from script_checks import args, check, run as run_checked, verdict  # noqa: E402



def run(gibench, out, cache):
    p = run_checked([gibench, "run", os.path.join(HERE, "tiny_timing.matrix"), "--timing-only",
                     "--warmup", "auto", "--out", out, "--cache", cache, "--no-history"])
    if p.returncode != 0:
        sys.exit(f"FAIL: gibench run exited {p.returncode}: {p.stderr[-2000:]}")
    with open(os.path.join(out, "tiny_timing.csv"), newline="") as f:
        rows = list(csv.DictReader(f))
    with open(os.path.join(out, "tiny_timing_passes.csv"), newline="") as f:
        passes = list(csv.DictReader(f))
    return rows, passes


def main():
    a = args()
    cache = os.path.join(a.work, "cache")
    rows, passes = run(a.gibench, os.path.join(a.work, "one"), cache)
    check(len(rows) == 2 and all(r["status"] == "ok" for r in rows), f"two ok rows ({len(rows)})")
    check(all(r["message"] == "timing only: not scored" for r in rows), "each row says it is not scored")
    check(all(not r[k] for r in rows for k in ("rmse", "ssim", "flip", "ref_spp", "image")),
          "the metric and image columns are empty")
    check(all(float(r["gpu_ms_median"]) > 0 for r in rows), "each row has a time")
    check(not os.path.exists(os.path.join(a.work, "one", "images")), "no image written")
    check(not os.path.exists(cache) or not os.listdir(cache), "no reference rendered")
    # At least three frames after the counting one agree within 5% (or 2 s passed): 4 to 60.
    check(all(4 <= int(r["warmup"]) <= 60 for r in rows),
          "the auto warm-up's count is in the row: " + ", ".join(r["warmup"] for r in rows))
    tree = source_hash.Tree()
    check(all(r["technique_hash"] == source_hash.technique_hash(tree, r["technique"]) for r in rows),
          "each row's technique hash is its sources' (source_hash.py)")
    kinds = {(p["technique"], p["pass"]): p for p in passes}
    g = kinds.get(("direct", "gbuffer"))
    check(g is not None and g["kind"] == "raster" and int(g["fragment_invocations"]) >= 32 * 32 // 2
          and int(g["primitives"]) > 0 and int(g["compute_invocations"]) == 0,
          "the G-buffer pass is raster work: primitives, and fragments for at least half the pixels")
    s = kinds.get(("multires_ir", "splitting"))
    check(s is not None and s["kind"] in ("compute", "both") and int(s["compute_invocations"]) > 0,
          "multires_ir's splitting runs compute work")
    check(all(p["kind"] in ("raster", "compute", "both", "none") for p in passes), "every pass has a kind")
    _, again = run(a.gibench, os.path.join(a.work, "two"), cache)
    cols = ("vertices", "primitives", "fragment_invocations", "compute_invocations")
    first = {(p["technique"], p["pass"]): tuple(p[c] for c in cols) for p in passes}
    second = {(p["technique"], p["pass"]): tuple(p[c] for c in cols) for p in again}
    check(first == second, "two runs count the same work in every pass")
    return verdict("PASS: timing-only rows, auto warm-up, work counts")


if __name__ == "__main__":
    sys.exit(main())
