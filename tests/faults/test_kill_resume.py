#!/usr/bin/env python3
"""A matrix run killed with SIGKILL at random points, ten times, then resumed.

faults.matrix runs once uninterrupted (the expected table). Then, into a fresh output folder and
reference cache, `gibench run` is started and killed with SIGKILL at a random point (once it has
written 0 or 1 more rows, after a further random 0-0.3 s: inside a reference render, a technique's
frames, between a run's rows) ten times in a row, each start resuming what the killed ones left;
a last start finishes. The CSVs must then parse (every line has the header's field count), hold every expected
row exactly once (identity key: profile, scene, camera, technique, component, params, size,
instant), equal the uninterrupted run's rows but for times, timestamps and the reference's
git revision, and the passes CSV must hold each run's passes exactly once. The random points come
from a fixed seed."""
import csv
import os
import random
import shutil
import signal
import subprocess
import sys
import time

from fault_checks import MATRIX, args, check, verdict

KEY = ("profile", "scene", "camera", "technique", "component", "params", "width", "height", "time")
PASS_KEY = ("profile", "scene", "technique", "params", "width", "height", "time", "pass")
TIMES = {"gpu_ms_median", "gpu_ms_min", "gpu_ms_max", "gpu_ms_iqr", "cpu_ms", "cpu_ms_iqr", "first_frame_ms",
         "first_frame_gpu_ms", "timestamp", "driver_mem_bytes"}
KILLS = 10


def read_strict(path):
    """Rows of a CSV, failing on any line whose field count differs from the header's."""
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    header, body = rows[0], rows[1:]
    bad = [i + 2 for i, r in enumerate(body) if len(r) != len(header)]
    check(not bad, f"{os.path.basename(path)} parses: {len(body)} rows of {len(header)} fields"
                   + (f" (bad lines {bad[:5]})" if bad else ""))
    return [dict(zip(header, r)) for r in body if len(r) == len(header)]


def count_lines(path):
    """Complete data lines of a CSV that may end in an unfinished one (0 if absent)."""
    if not os.path.exists(path):
        return 0
    with open(path, "rb") as f:
        return max(0, f.read().count(b"\n") - 1)


def run(gibench, matrix, out, cache):
    return subprocess.Popen([gibench, "run", matrix, "--out", out, "--cache", cache, "--no-images"],
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)


def main():
    a = args()
    matrix = MATRIX
    gold, out = os.path.join(a.work, "gold"), os.path.join(a.work, "killed")
    t0 = time.monotonic()
    p = run(a.gibench, matrix, gold, os.path.join(a.work, "gold_cache"))
    _, err = p.communicate()
    full = time.monotonic() - t0
    if p.returncode != 0:
        sys.stderr.write(err[-3000:])
        raise SystemExit(f"the uninterrupted run failed (exit {p.returncode})")
    print(f"uninterrupted run: {full:.1f} s")
    rng = random.Random(19)
    cache = os.path.join(a.work, "killed_cache")
    killed = 0
    total = len(read_strict(os.path.join(gold, "faults.csv")))
    for i in range(KILLS):
        # Each start is killed once it has written 0 or 1 more rows, after a further random
        # delay: the kills land in reference renders, frames, between a run's rows and passes,
        # and the matrix cannot finish before the tenth.
        before = count_lines(os.path.join(out, "faults.csv"))
        more, extra = rng.randint(0, 1), rng.uniform(0.0, 0.3)
        p = run(a.gibench, matrix, out, cache)
        while p.poll() is None and count_lines(os.path.join(out, "faults.csv")) < before + more:
            time.sleep(0.005)
        time.sleep(extra)
        if p.poll() is not None:
            print(f"start {i + 1}: finished before its kill")
            continue
        p.send_signal(signal.SIGKILL)
        p.wait()
        killed += 1
        print(f"start {i + 1}: SIGKILL after {more} more rows and {extra:.2f} s "
              f"({count_lines(os.path.join(out, 'faults.csv'))} of {total} rows written)")
    # Load on a shared machine can make a start finish sooner than its delay: most must be killed.
    check(killed >= KILLS - 2, f"{killed} of {KILLS} starts were killed mid-run")
    p = run(a.gibench, matrix, out, cache)
    _, err = p.communicate()
    check(p.returncode == 0, f"the last start finishes the matrix (exit {p.returncode})")
    if p.returncode != 0:
        sys.stderr.write(err[-3000:])
    name = "faults"
    want = read_strict(os.path.join(gold, name + ".csv"))
    got = read_strict(os.path.join(out, name + ".csv"))
    keys = [tuple(r[k] for k in KEY) for r in got]
    dup = len(keys) - len(set(keys))
    check(dup == 0, f"every row once: {dup} duplicated")
    want_by = {tuple(r[k] for k in KEY): r for r in want}
    got_by = {tuple(r[k] for k in KEY): r for r in got}
    check(set(got_by) == set(want_by), f"the same {len(want_by)} rows as the uninterrupted run "
          f"({len(set(want_by) - set(got_by))} missing, {len(set(got_by) - set(want_by))} extra)")
    diffs = [f"{k[1]} {k[3]} {k[4]} {k[6]}x{k[7]} {c}: {want_by[k][c]!r} vs {got_by[k][c]!r}"
             for k in want_by if k in got_by for c in want_by[k]
             if c not in TIMES and c != "git_revision" and want_by[k][c] != got_by[k][c]]
    for d in diffs[:8]:
        print("     " + d)
    check(not diffs, f"rows equal to the uninterrupted run's but for times ({len(diffs)} differences)")
    pw = read_strict(os.path.join(gold, name + "_passes.csv"))
    pg = read_strict(os.path.join(out, name + "_passes.csv"))
    pkeys = [tuple(r[k] for k in PASS_KEY) for r in pg]
    check(len(pkeys) == len(set(pkeys)), f"every pass row once: {len(pkeys) - len(set(pkeys))} duplicated")
    check(set(pkeys) == {tuple(r[k] for k in PASS_KEY) for r in pw},
          f"the same {len(pw)} pass rows as the uninterrupted run")
    leftovers = [f for f in os.listdir(cache) if not f.endswith(".exr")]
    check(not leftovers, f"no unfinished reference left in the cache ({leftovers[:3]})")
    # A write cut short (what SIGKILL during write(2), or a full disk, leaves): the finished table
    # with its last row replaced by a first part of that row, no newline: half of it, and all of
    # it but the newline (every field there: such a row was once counted present and then cut
    # off, so it was never written again). The next run must cut the line off, redo that run and
    # leave every row once.
    for what, keep in (("half", lambda n: n // 2), ("all but its newline", lambda n: n)):
        cut = os.path.join(a.work, "cut_" + str(keep(100)))
        shutil.copytree(gold, cut)
        path = os.path.join(cut, name + ".csv")
        with open(path, "rb") as f:
            lines = f.read().split(b"\n")[:-1]
        with open(path, "wb") as f:
            f.write(b"\n".join(lines[:-1]) + b"\n" + lines[-1][: keep(len(lines[-1]))])
        p = run(a.gibench, matrix, cut, os.path.join(a.work, "gold_cache"))
        _, err = p.communicate()
        check(p.returncode == 0 and "cut off an unfinished last line" in err,
              f"a last row cut to {what} is cut off and its run redone (exit {p.returncode})")
        rows = read_strict(path)
        ck = [tuple(r[k] for k in KEY) for r in rows]
        check(len(ck) == len(set(ck)) and set(ck) == set(want_by),
              f"then every row once ({len(ck)} rows, {len(want_by)} expected)")
    return verdict()


if __name__ == "__main__":
    sys.exit(main())
