#!/usr/bin/env python3
"""The timing method's own benchmark: how far apart two runs of the same matrices land on one machine,
and how far a longer warm-up moves a median. Not a test: it measures, it asserts nothing.

usage: python3 -m reporting.bench_timing GIBENCH RESULTS_DIR [--matrices A,B,...] [--work DIR] [--long-warmup N]

Runs the matrices three times with the quick profile into WORK/{a,b,long} (no images, no history,
references from RESULTS_DIR/cache): a and b as the profile says, `long` with --warmup N (default
10). For every run (scene, technique, parameters, size, instant) and every pass it sets the three
medians side by side and writes
  RESULTS_DIR/bench_timing.csv        a row per run total and per pass: the medians, the IQR of a,
                                      the run-to-run difference |a - b| / mean(a, b), the shift of a
                                      longer warm-up (long - a) / a, and whether that shift is within
                                      the spread (|long - a| <= max(IQR of a, |a - b|))
  RESULTS_DIR/timing_resolution.csv   one row per kind (total, pass): the 50th, 90th and 95th
                                      percentiles of the run-to-run difference. The 95th is the
                                      smallest relative time difference this machine resolves: the
                                      report and the claims call two times closer than it a tie.
Only times of at least MIN_MS enter the percentiles (below it a timer query's own granularity and
the driver's scheduling dominate); those rows are still written.
"""
import argparse
import os
import subprocess
import sys

from reporting.schema import ROOT, read_csv, write_csv  # noqa: E402

DEFAULT_MATRICES = ["thesis_t41_ring", "direct_shadows", "ldm_fig11", "lrsm_stages"]
MIN_MS = 0.5
RUN_KEY = ("matrix", "scene", "technique", "params", "width", "height", "time")


def run(gibench, matrices, out, cache, extra):
    cmd = [gibench, "run", *matrices, "--profile", "quick", "--out", out, "--cache", cache,
           "--no-images", "--no-history", *extra]
    print("bench_timing:", " ".join(cmd), flush=True)
    rc = subprocess.call(cmd, stdout=subprocess.DEVNULL)
    if rc not in (0, 1):  # 1: some row not ok (out_of_memory rows are results)
        sys.exit(f"bench_timing: gibench run exited {rc}")


def table(folder, names, passes):
    """{(run key..., pass): (median, iqr, renderer)} over the matrices' CSVs in folder."""
    out = {}
    for n in names:
        for r in read_csv(os.path.join(folder, n + ("_passes.csv" if passes else ".csv"))):
            if not passes and r["status"] != "ok":
                continue
            key = tuple(r[k] for k in RUN_KEY) + ((r["pass"],) if passes else ("total",))
            med = r["ms_median"] if passes else r["gpu_ms_median"]
            iqr = r["ms_iqr"] if passes else r["gpu_ms_iqr"]
            out[key] = (float(med), float(iqr), r["renderer"])
    return out


def percentile(values, q):
    if not values:
        return ""
    s = sorted(values)
    h = q * (len(s) - 1)
    lo = int(h)
    return s[lo] if lo + 1 >= len(s) else s[lo] + (h - lo) * (s[lo + 1] - s[lo])


def compare(a, b, long):
    rows = []
    for key, (ma, iqr, renderer) in sorted(a.items()):
        if key not in b or key not in long:
            continue
        mb, ml = b[key][0], long[key][0]
        mean = 0.5 * (ma + mb)
        rel = abs(ma - mb) / mean if mean > 0 else 0.0
        shift = (ml - ma) / ma if ma > 0 else 0.0
        within = abs(ml - ma) <= max(iqr, abs(ma - mb))
        rows.append({**dict(zip(RUN_KEY, key[:-1])), "pass": key[-1], "ms_a": f"{ma:.6g}",
                     "ms_b": f"{mb:.6g}", "ms_long_warmup": f"{ml:.6g}", "iqr_a": f"{iqr:.6g}",
                     "run_to_run_rel": f"{rel:.4f}", "warmup_shift_rel": f"{shift:.4f}",
                     "shift_within_spread": "yes" if within else "no", "renderer": renderer,
                     "counted": "yes" if min(ma, mb) >= MIN_MS else "no"})
    return rows


def summary(rows, cores, long_warmup):
    out = []
    for kind in ("total", "pass"):
        sel = [r for r in rows if (r["pass"] == "total") == (kind == "total") and r["counted"] == "yes"]
        rel = [float(r["run_to_run_rel"]) for r in sel]
        shift = [abs(float(r["warmup_shift_rel"])) for r in sel]
        within = sum(r["shift_within_spread"] == "yes" for r in sel)
        out.append({"kind": kind, "renderer": sel[0]["renderer"] if sel else "", "cores": cores,
                    "times": len(sel), "min_ms": MIN_MS,
                    "run_to_run_p50": decimals4(percentile(rel, 0.5)), "run_to_run_p90": decimals4(percentile(rel, 0.9)),
                    "run_to_run_p95": decimals4(percentile(rel, 0.95)),
                    "resolution_rel": decimals4(percentile(rel, 0.95)),
                    "long_warmup": long_warmup, "warmup_shift_p50": decimals4(percentile(shift, 0.5)),
                    "warmup_shift_p95": decimals4(percentile(shift, 0.95)),
                    "warmup_shift_within_spread": f"{within}/{len(sel)}"})
    return out


def decimals4(x):
    """A relative difference to four decimals (this table's own style, apart from schema.fmt)."""
    return f"{x:.4f}" if isinstance(x, float) else str(x)


def write(path, rows):
    print("bench_timing: wrote", write_csv(path, rows, list(rows[0].keys())))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("gibench")
    ap.add_argument("results")
    ap.add_argument("--matrices", default=",".join(DEFAULT_MATRICES))
    ap.add_argument("--work", default=None)
    ap.add_argument("--long-warmup", type=int, default=10)
    args = ap.parse_args()
    root = ROOT
    names = [m for m in args.matrices.split(",") if m]
    paths = [os.path.join(root, "harness", "matrices", m + ".matrix") for m in names]
    work = args.work or os.path.join(args.results, "bench_timing_work")
    cache = os.path.join(args.results, "cache")
    for sub, extra in (("a", []), ("b", []), ("long", ["--warmup", str(args.long_warmup)])):
        d = os.path.join(work, sub)
        for n in names:  # afresh: gibench run resumes from what a folder holds
            for suffix in (".csv", "_passes.csv"):
                if os.path.exists(os.path.join(d, n + suffix)):
                    os.remove(os.path.join(d, n + suffix))
        run(args.gibench, paths, d, cache, extra)
    rows = []
    for passes in (False, True):
        a, b, lng = (table(os.path.join(work, s), names, passes) for s in ("a", "b", "long"))
        rows += compare(a, b, lng)
    if not rows:
        sys.exit("bench_timing: no run produced comparable times")
    write(os.path.join(args.results, "bench_timing.csv"), rows)
    write(os.path.join(args.results, "timing_resolution.csv"),
          summary(rows, os.cpu_count(), args.long_warmup))


if __name__ == "__main__":
    main()
