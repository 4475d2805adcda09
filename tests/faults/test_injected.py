#!/usr/bin/env python3
"""Faults injected into a matrix run, each row's status and message checked:

- GPU memory exhausted: GIBENCH_GPU_BUDGET_BYTES (the ledger refuses an allocation that would
  pass it, as a driver's GL_OUT_OF_MEMORY would). With 2 MB, `direct` at shadow_res 512 and 1024
  cannot allocate its shadow map (6 and 25 MB): those rows are `out_of_memory` with a message
  naming the allocation, every other row renders as without the budget, the run exits 0
  (out_of_memory is a result, not a failure) and every row is there once.
- A shader that fails to compile: GIBENCH_INJECT_SHADER_ERROR=hbao puts a line the GLSL compiler
  rejects into hbao's shaders: hbao's rows are `shader_failed` with the driver's log in the
  message, the other techniques' rows are `ok` and equal to a clean run's, the run exits 1.
- Two runs of the same matrix into the same folder at once: the second refuses (a lock), the first
  finishes, every row once.
- A full disk (every file capped at 7,000 bytes): a clear error naming the file, the run stops,
  no temporary or truncated file is left, and the next run finishes with the clean run's rows."""
import csv
import os
import resource
import shutil
import signal
import subprocess
import sys
import time

from fault_checks import MATRIX, args, check, run_gibench, verdict

KEY = ("scene", "technique", "component", "params", "width", "height")


def run(gibench, matrix, out, cache, env_extra, images=False):
    env = dict(os.environ, **env_extra)
    p = run_gibench([gibench, "run", matrix, "--out", out, "--cache", cache, "--no-images"],
                     env=env)
    with open(os.path.join(out, "faults.csv"), newline="") as f:
        rows = list(csv.DictReader(f))
    return p.returncode, {tuple(r[k] for k in KEY): r for r in rows}, len(rows), p.stderr


def main():
    a = args()
    matrix = MATRIX
    cache = os.path.join(a.work, "cache")
    rc, clean, n, _ = run(a.gibench, matrix, os.path.join(a.work, "clean"), cache, {})
    check(rc == 0 and all(r["status"] == "ok" for r in clean.values()),
          f"clean run: exit {rc}, {n} rows, all ok")

    rc, oom, n, _ = run(a.gibench, matrix, os.path.join(a.work, "oom"), cache,
                        {"GIBENCH_GPU_BUDGET_BYTES": "2000000"})
    check(rc == 0, f"2 MB budget: exit {rc} (out_of_memory rows are results)")
    check(n == len(oom) == len(clean), f"2 MB budget: {n} rows, each once, as many as the clean run")
    big = [k for k in oom if k[1] == "direct" and "shadow_res=256" not in k[3]]
    check(big and all(oom[k]["status"] == "out_of_memory" and "out of memory: 'shadow.depth'"
                      in oom[k]["message"] and "budget of 2000000 bytes" in oom[k]["message"]
                      for k in big),
          f"direct at shadow_res 512 and 1024: {len(big)} rows out_of_memory naming shadow.depth "
          "and the budget")
    check(all(oom[k]["rmse"] == "" for k in big), "no metric in an out_of_memory row")
    fit = [k for k in oom if k[1] != "direct"]
    check(fit and all(oom[k]["status"] == "ok" and oom[k]["rmse"] == clean[k]["rmse"] for k in fit),
          f"hbao and ldm_ao under the budget: {len(fit)} rows ok, RMSE as the clean run's")

    rc, bad, n, err = run(a.gibench, matrix, os.path.join(a.work, "shader"), cache,
                          {"GIBENCH_INJECT_SHADER_ERROR": "hbao"})
    check(rc == 1, f"injected shader error: exit {rc} (rows not ok)")
    hb = [k for k in bad if k[1] == "hbao"]
    check(hb and all(bad[k]["status"] == "shader_failed" and "failed to compile" in bad[k]["message"]
                     and "error" in bad[k]["message"] for k in hb),
          f"hbao: {len(hb)} rows shader_failed with the compiler's log")
    other = [k for k in bad if k[1] != "hbao"]
    check(n == len(clean) and other and all(bad[k]["status"] == "ok" and bad[k]["rmse"] == clean[k]["rmse"]
                                            for k in other),
          f"the matrix goes on: {len(other)} other rows ok and equal to the clean run's")
    check("shader_failed" in err, "the failure is reported on stderr as it happens")
    # Two runs of the same matrix into the same folder at once: the second refuses at once (the
    # table's lock), the first finishes, every row is there once.
    two = os.path.join(a.work, "two")
    first = subprocess.Popen([a.gibench, "run", matrix, "--out", two, "--cache", cache, "--no-images"],
                             stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    while first.poll() is None and not os.path.exists(os.path.join(two, "faults.csv")):
        time.sleep(0.01)
    second = subprocess.run([a.gibench, "run", matrix, "--out", two, "--cache", cache, "--no-images"],
                            capture_output=True, text=True)
    first.communicate()
    check(first.returncode == 0, f"two runs at once: the first finishes (exit {first.returncode})")
    check(second.returncode == 1 and "another gibench run is writing" in second.stderr,
          f"two runs at once: the second refuses (exit {second.returncode}): "
          f"{second.stderr.strip().splitlines()[-1][:120] if second.stderr.strip() else ''}")
    with open(os.path.join(two, "faults.csv"), newline="") as f:
        keys = [tuple(r[k] for k in KEY) for r in csv.DictReader(f)]
    check(len(keys) == len(set(keys)) == len(clean), f"two runs at once: {len(keys)} rows, each once")

    # A full disk: every file limited to 7,000 bytes (RLIMIT_FSIZE, SIGXFSZ ignored, so a write past
    # it fails with EFBIG as a full disk fails with ENOSPC; no privileges needed, unlike a tiny
    # tmpfs). With an empty reference cache the first 9 kB reference entry cannot be written; with
    # the clean run's cache the technique images and then the table fill up.
    def limit():
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
        resource.setrlimit(resource.RLIMIT_FSIZE, (7000, 7000))
    for case, what in (("empty_cache", "writing reference cache entry"), ("filled_cache", "cannot write")):
        full_out, full_cache = os.path.join(a.work, case), os.path.join(a.work, case + "_cache")
        if case == "filled_cache":
            shutil.copytree(cache, full_cache)
        # Without the SQLite history, which a 7,000-byte cap would stop at its creation.
        p = subprocess.run([a.gibench, "run", matrix, "--out", full_out, "--cache", full_cache,
                            "--no-history"],
                           preexec_fn=limit, capture_output=True, text=True)
        print("     " + "\n     ".join(l for l in p.stderr.splitlines() if "stopping" in l))
        check(p.returncode == 1 and what in p.stderr and "stopping" in p.stderr,
              f"disk full, {case}: exit {p.returncode}, a message naming the file, the run stops")
        left = [os.path.join(d, f) for d, _, fs in os.walk(a.work) for f in fs if ".tmp" in f]
        check(not left, f"disk full, {case}: no temporary file left behind ({left[:3]})")
        pngs = [os.path.join(d, f) for d, _, fs in os.walk(full_out) for f in fs if f.endswith(".png")]
        cut = [f for f in pngs if b"IEND" not in open(f, "rb").read()[-12:]]
        check(not cut, f"disk full, {case}: every PNG there is complete ({len(pngs)}, {len(cut)} cut)")
        rc, resumed, n, err = run(a.gibench, matrix, full_out, full_cache, {}, images=True)
        check(rc == 0 and n == len(resumed) == len(clean), f"disk full, {case}: the next run on a "
              f"free disk finishes: exit {rc}, {n} rows, each once")
        same = all(resumed[k]["status"] == "ok" and resumed[k]["rmse"] == clean[k]["rmse"] for k in clean)
        check(same, f"disk full, {case}: its rows equal the clean run's (nothing half-written trusted)")
    return verdict()


if __name__ == "__main__":
    sys.exit(main())
