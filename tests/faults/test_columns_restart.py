#!/usr/bin/env python3
"""A results table whose columns changed (its matrix names another parameter, the run CSV gained a
column) is moved aside to <matrix>.csv.old and started afresh, and its passes CSV with it: the old
passes rows belong to runs that are gone, and share their keys with the runs about to be redone, so
a passes table kept would hold the old revision's timings under the new rows (found in results/: the
VCT stages of Table 3 were the previous revision's). The test writes a run CSV with other columns
and a passes CSV holding a stale row under the key of a run of faults.matrix, runs the matrix, and
checks that both went aside, the new passes CSV has every run's passes once and none of the stale
times."""
import csv
import os
import subprocess
import sys

from fault_checks import MATRIX, args, check, verdict



def main():
    a = args()
    matrix = MATRIX
    out, cache = os.path.join(a.work, "out"), os.path.join(a.work, "cache")
    os.makedirs(out)
    # A first run gives the real passes CSV, whose header and first key we reuse.
    subprocess.run([a.gibench, "run", matrix, "--out", out, "--cache", cache, "--no-images"],
                   check=True, stdout=subprocess.DEVNULL)
    runs_path, passes_path = os.path.join(out, "faults.csv"), os.path.join(out, "faults_passes.csv")
    with open(passes_path, newline="") as f:
        rows = list(csv.reader(f))
    header, first = rows[0], rows[1]
    stale = list(first)
    stale[header.index("ms_median")] = "123456.789"
    with open(passes_path, "w", newline="") as f:
        csv.writer(f).writerows([header, stale])
    with open(runs_path, "w") as f:
        f.write("matrix,profile,an_old_column\nfaults,quick,1\n")
    r = subprocess.run([a.gibench, "run", matrix, "--out", out, "--cache", cache, "--no-images"],
                       stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    check(r.returncode == 0, f"the rerun succeeds (exit {r.returncode})")
    check(os.path.exists(runs_path + ".old"), "the run CSV with other columns went to faults.csv.old")
    check(os.path.exists(passes_path + ".old"), "its passes CSV went to faults_passes.csv.old")
    with open(passes_path, newline="") as f:
        new = list(csv.DictReader(f))
    check(not any(p["ms_median"] == "123456.789" for p in new),
          "no stale pass time in the new passes CSV")
    key = ("profile", "scene", "technique", "params", "width", "height", "time", "pass")
    keys = [tuple(p[k] for k in key) for p in new]
    check(len(keys) == len(set(keys)) and tuple(first[header.index(k)] for k in key) in set(keys),
          f"every run's passes once, the stale row's run among them ({len(keys)} rows)")
    return verdict("PASS: a restarted table restarts its passes")


if __name__ == "__main__":
    sys.exit(main())
