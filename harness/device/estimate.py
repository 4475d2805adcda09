#!/usr/bin/env python3
"""How long the device run of all three papers (harness/device/time_all_papers.sh) will take, from
the rows of an earlier run: before a lent GPU's minutes are spent, whether the run fits its budget.

    python3 harness/device/estimate.py FOLDER [--frames F] [--warmup W] [--speedup S] [--budget B]

FOLDER holds an earlier run's runs tables (results/gpu/<gpu>/ of a device run, or a folder of a dry
run on llvmpipe: harness/device/time_all_papers.sh with GIB_DEVICE_PROFILE and GIB_DEVICE_TMP set).
A run's wall time is its cold first frame (create and compiles included: first_frame_ms) plus its
warm-up and timed frames at its median wall time a frame (cpu_ms: glFinish waits for the GPU), and
each matrix adds LOAD_S for loading its scenes. --frames and --warmup are the counts to predict for
(default: the rows' own); --speedup divides every time (a dry run on a slower renderer: its times
over the target's, e.g. measured on a matrix both ran). Prints each matrix's estimate in the
script's order and whether the sum fits the budget (default 480 s, the script's)."""
import csv
import glob
import os
import sys

LOAD_S = 2.0  # a matrix's scene loads and GL set-up, seconds (measured: 1-2 s on the H200 machine)
HERE = os.path.dirname(os.path.abspath(__file__))


def order():
    """The matrices in time_all_papers.sh's order."""
    text = open(os.path.join(HERE, "time_all_papers.sh")).read()
    body = text.split('order="', 1)[1].split('"', 1)[0]
    return body.split()


def runs(path):
    """{run identity: one of its rows} of a runs table (a run writes a row per component)."""
    out = {}
    with open(path, newline="") as f:
        for r in csv.DictReader(f):
            out[(r["scene"], r["technique"], r["params"], r["width"], r["height"], r["time"])] = r
    return out


def number(v, default=0.0):
    try:
        return float(v)
    except (TypeError, ValueError):
        return default


def estimate(folder, frames=None, warmup=None, speedup=1.0):
    """[(matrix, runs, seconds or None when the folder lacks it)] in the script's order."""
    out = []
    for name in order():
        path = os.path.join(folder, name + ".csv")
        if not os.path.exists(path):
            out.append((name, 0, None))
            continue
        rs = runs(path)
        s = LOAD_S
        for r in rs.values():
            n = (number(r["warmup"]) if warmup is None else warmup) + \
                (number(r["frames"]) if frames is None else frames)
            s += (number(r["first_frame_ms"]) + n * number(r["cpu_ms"])) / 1e3 / speedup
        out.append((name, len(rs), s))
    return out


def main(argv):
    if len(argv) < 2:
        sys.exit(__doc__)
    opts = {k: float(argv[argv.index(k) + 1]) for k in ("--frames", "--warmup", "--speedup", "--budget")
            if k in argv}
    rows = estimate(argv[1], opts.get("--frames"), opts.get("--warmup"), opts.get("--speedup", 1.0))
    budget = opts.get("--budget", 480.0)
    total, missing = 0.0, []
    print("matrix,runs,estimated_s,cumulative_s")
    for name, n, s in rows:
        if s is None:
            missing.append(name)
            continue
        total += s
        print(f"{name},{n},{s:.1f},{total:.1f}")
    print(f"# total {total:.0f} s against a budget of {budget:.0f} s: "
          f"{'fits' if total <= budget else 'does not fit'}"
          + (f"; no rows for {', '.join(missing)}" if missing else ""))
    return 0 if total <= budget and not missing else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
