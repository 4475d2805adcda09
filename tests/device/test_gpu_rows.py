#!/usr/bin/env python3
"""Which device-run rows the report may use (harness/reporting/gpu_rows.py), on a constructed run: a row timed
while nvidia-smi named a reason other than idle is held down; a row whose window saw the clock drop
is used only when its timed frames agree (IQR within 5% of the median); a row of a technique whose
sources changed since is stale; the newest valid row of a run wins. Then the GPU-timed copies the
answers rank (a group is timed on the GPU only when every row of it has a GPU row), and the time a
device run is estimated to take (harness/device/estimate.py). No GL."""
import csv
import os
import shutil
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "harness"))
sys.path.insert(0, os.path.join(ROOT, "tests", "common"))
sys.path.insert(0, os.path.join(ROOT, "harness", "device"))
import estimate  # noqa: E402
from reporting import gpu_rows  # noqa: E402
from reporting import pass_work  # noqa: E402
from script_checks import check, verdict  # noqa: E402

COLS = ["matrix", "profile", "scene", "camera", "technique", "component", "params", "width", "height",
        "time", "warmup", "frames", "gpu_ms_median", "gpu_ms_iqr", "gpu_ms_min", "gpu_ms_max", "cpu_ms",
        "first_frame_ms", "status", "renderer", "git_revision", "technique_hash", "timestamp",
        "rel_rmse", "rmse"]


def write(path, cols, rows):
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, cols, lineterminator="\n")
        w.writeheader()
        for r in rows:
            w.writerow({c: r.get(c, "") for c in cols})


def gpu_row(tech, params, ts, ms="10", iqr="0.05", hashes=None, width="128"):
    return {"matrix": "m", "profile": "gpu", "scene": "cornell", "camera": "0", "technique": tech,
            "component": "indirect", "params": params, "width": width, "height": width, "time": "0",
            "warmup": "4", "frames": "5", "gpu_ms_median": ms, "gpu_ms_iqr": iqr, "cpu_ms": "12",
            "first_frame_ms": "100", "status": "ok", "renderer": "NVIDIA H200/PCIe/SSE2",
            "git_revision": "abc", "technique_hash": hashes.current(tech) if hashes else "000000000000",
            "timestamp": f"2026-11-27T17:00:{ts:02d}Z"}


def main():
    work = tempfile.mkdtemp()
    try:
        return run(work)
    finally:
        shutil.rmtree(work)


def run(work):
    hashes = gpu_rows.Hashes()
    folder = os.path.join(work, "gpu", "fakegpu")
    os.makedirs(folder)
    rows = [gpu_row("rsm_gather", "a=1", 10, hashes=hashes),             # steady: valid
            gpu_row("rsm_gather", "a=2", 20, hashes=hashes),             # power cap: held down
            gpu_row("rsm_gather", "a=3", 30, iqr="1.0", hashes=hashes),  # clock drop, 10% spread
            gpu_row("rsm_gather", "a=4", 40, iqr="0.1", hashes=hashes),  # clock drop, 1% spread: used
            gpu_row("multires_ir", "a=5", 50)]                           # another hash: stale
    write(os.path.join(folder, "m.csv"), COLS, rows)
    samples = [("2026/11/27 17:00:%02d.000" % s, 1980, "0x0000000000000001") for s in range(0, 60)]
    samples[15] = (samples[15][0], 1980, "0x0000000000000004")   # SW power cap in row 2's window
    samples[25] = (samples[25][0], 345, "0x0000000000000001")    # the clock idled in row 3's
    samples[35] = (samples[35][0], 345, "0x0000000000000001")    # and in row 4's
    with open(os.path.join(folder, "gpu_samples.csv"), "w") as f:
        f.write("timestamp,clocks.sm,clocks.mem,clocks.max.sm,power.draw,temperature.gpu,pstate,"
                "utilization.gpu,clocks_event_reasons.active\n")
        for t, sm, why in samples:
            f.write(f"{t}, {sm}, 3201, 1980, 130.0, 43, P0, 50, {why}\n")
    loaded = gpu_rows.load(work, hashes)
    by = {r["params"]: r for r in loaded}
    check(by["a=1"]["_valid"], "a steady, current row is valid")
    check(by["a=2"]["_held_down"] and not by["a=2"]["_valid"], "a row timed under a power cap is held down")
    check(by["a=3"]["_clock_moved"] and not by["a=3"]["_valid"],
          "a clock drop in the window with a 10% spread leaves the row out")
    check(by["a=4"]["_clock_moved"] and by["a=4"]["_valid"],
          "a clock drop in the window with a 1% spread keeps it (the frames agree)")
    check(not by["a=5"]["_current"] and not by["a=5"]["_valid"] and "stale" in by["a=5"]["_why"],
          "a row whose technique's sources changed is stale")
    # An older run of the same rows under older/: the newest valid row of each run wins.
    older = os.path.join(folder, "older", "0ld")
    os.makedirs(older)
    write(os.path.join(older, "m.csv"), COLS, [gpu_row("rsm_gather", "a=1", 10, ms="99", hashes=hashes)])
    v = gpu_rows.valid(gpu_rows.load(work, hashes))
    a1 = [r for r in v.values() if r["params"] == "a=1"]
    check(len(a1) == 1 and a1[0]["gpu_ms_median"] == "10", "the newest run's row wins over an older one")
    copies_case(work, hashes)
    work_case()
    est = estimate.estimate(folder, frames=10, warmup=4)
    # estimate reads the script's matrix names; the constructed table is named m: none of them.
    check(all(s is None for _, _, s in est), "estimate: the script's matrices absent here are reported absent")
    write(os.path.join(folder, "lrsm_stages.csv"), COLS, rows[:2])
    est = dict((n, s) for n, _, s in estimate.estimate(folder, frames=10, warmup=4))
    want = estimate.LOAD_S + 2 * (100 + 14 * 12) / 1e3
    check(abs(est["lrsm_stages"] - want) < 1e-9,
          f"estimate: cold frame + (warm-up + frames) x frame wall time, plus the loads: {est['lrsm_stages']:.3f} s")
    return verdict("PASS: device rows judged, GPU-timed copies, run estimate")


def work_case():
    """The work-and-time table: invocations summed over fragment and compute, a pass with no counts
    (a table from before the columns) said so, the largest image kept."""
    base = {"technique": "vct", "scene": "s", "params": "voxel_res=256", "ms_median": "2.5"}
    passes = [dict(base, width="64", height="64", kind="both", fragment_invocations="10",
                   compute_invocations="5", **{"pass": "voxelization"}),
              dict(base, width="128", height="128", kind="both", fragment_invocations="40",
                   compute_invocations="20", **{"pass": "voxelization"}),
              dict(base, width="128", height="128", kind="", **{"pass": "cones"})]
    rows = pass_work.machine_rows(passes, "m")
    check([r[6] for r in rows] == ["60", ""] and rows[1][3] == "not counted" and
          all(r[5] == "128x128" for r in rows),
          "work table: fragment + compute invocations, uncounted passes said so, the largest image")


def copies_case(work, hashes):
    """Paper-profile rows of two techniques at 32x32 and the GPU's at 128x128."""
    llvm = []
    for tech, params in (("rsm_gather", "a=1"), ("rsm_gather", "a=4")):
        r = gpu_row(tech, params, 0, width="32", hashes=hashes)
        llvm.append(dict(r, profile="paper", renderer="llvmpipe", gpu_ms_median="500", rel_rmse="0.5"))
    copies = gpu_rows.timed_copies(llvm, work, gpu_rows.load(work, hashes))
    check(len(copies) == 2 and all(c["renderer"].startswith("NVIDIA") for c in copies),
          "each paper-profile row of a fully timed group gets a GPU-timed copy")
    check(all(c["rel_rmse"] == "0.5" and c["width"] == "32" for c in copies),
          "a copy keeps the llvmpipe row's error and size (the time's size is in time_source)")
    check({c["gpu_ms_median"] for c in copies} == {"10"} and "128x128" in copies[0]["time_source"],
          "its time is the GPU's at the paired size")
    llvm.append(dict(llvm[0], params="a=2"))  # its GPU row is held down: the group has a gap
    check(gpu_rows.timed_copies(llvm, work, gpu_rows.load(work, hashes)) == [],
          "a group with a row the GPU cannot time gets no copies (one machine or none)")


if __name__ == "__main__":
    sys.exit(main())
