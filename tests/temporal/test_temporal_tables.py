#!/usr/bin/env python3
"""harness/reporting/temporal_tables.py on constructed rows with known answers (no GL):
- flicker: a steady error (temporal error 0) scores 0; an error drawn anew each frame, temporal
  error sqrt(2) x the frame error, scores 1; over_frozen is the temporal error over the frozen scale;
- steady: yes within both thresholds, no past either, empty where the references' noise hides the
  temporal error (sqrt(2) x noise over half the temporal RMSE);
- the LRSM claim: reproduced when every lrsm component is steady, not reproduced when one is not,
  not measurable without rows; rows of lrsm with rebuild = 0 are not the paper's and do not count;
- the thesis claim: reproduced when reuse is lower than redraw by more than the seeds' spread at
  every mask level, not reproduced when the difference is within the spread at one level;
- the sequence table is written with the temporal columns from a runs table with the sequence
  columns, and tables without them are left out.
"""
import csv
import math
import os
import shutil
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "harness"))
from reporting import temporal_tables as tt  # noqa: E402
from reporting.claim import MACHINE_INDEPENDENT, Claim  # noqa: E402
from reporting.schema import columns  # noqa: E402

FAILS = []


def check(ok, what):
    print(("ok    " if ok else "FAIL  ") + what)
    if not ok:
        FAILS.append(what)


def seq_row(t, e, frozen, noise=0.0, **kw):
    r = {"status": "ok", "temporal_rmse": str(math.sqrt(t * t + 2 * noise * noise)),
         "temporal_rmse_denoised": str(t), "seq_rmse_denoised_mean": str(e),
         "temporal_frozen": str(frozen), "seq_ref_noise_rmse": str(noise)}
    r.update(kw)
    return r


def write_table(results, name, rows, seq=True):
    base = columns("runs")
    cols = base + ([c for c in tt.COLUMNS if c.startswith(("seq", "temporal")) or c == "sequence"]
                   if seq else []) + ["rebuild", "redraw", "mask_level", "seed"]
    with open(os.path.join(results, name + ".csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=cols, extrasaction="ignore")
        w.writeheader()
        for r in rows:
            full = {c: "" for c in cols}
            full.update(matrix=name, profile="quick", scene="s", camera="0", params="", width="64",
                        height="64", time="1", dt="0.1", sequence="8", renderer="r", image="")
            full.update(r)
            w.writerow(full)


def ratios():
    check(tt.flicker(seq_row(0, 0.1, 1)) == 0, "a steady error scores flicker 0")
    check(abs(tt.flicker(seq_row(math.sqrt(2) * 0.1, 0.1, 1)) - 1) < 1e-12,
          "an error drawn anew each frame scores flicker 1")
    check(abs(tt.over_frozen(seq_row(0.05, 0.1, 0.2)) - 0.25) < 1e-12, "over_frozen = 0.05 / 0.2")
    check(tt.steady(seq_row(0.05, 0.1, 0.2)) == "yes", "flicker 0.35, over frozen 0.25: steady")
    check(tt.steady(seq_row(0.1, 0.1, 0.2)) == "no", "flicker 0.71: not steady")
    check(tt.steady(seq_row(0.05, 0.1, 0.04)) == "no", "over the frozen scale: not steady")
    check(tt.steady(seq_row(0.05, 0.1, 0.2, noise=0.05)) == "", "noise hiding it: not judged")
    check(tt.steady(seq_row(0.05, 0.1, 0.2, noise=0.015)) == "yes", "noise small enough: judged")


def lrsm_rows(glossy_t):
    return [seq_row(0.05, 0.1, 0.2, technique="lrsm", component="direct", rebuild="1"),
            seq_row(glossy_t, 0.1, 0.2, technique="lrsm", component="glossy", rebuild="1"),
            seq_row(0.3, 0.1, 0.2, technique="lrsm", component="glossy", rebuild="0")]


def water_rows(level2_redraw):
    out = []
    for level, reuse, redraw in (("1", 0.030, 0.034), ("2", 0.050, level2_redraw)):
        for seed, d in (("1", 0.0), ("2", 0.0004), ("3", -0.0003)):
            out.append(seq_row(reuse + d, 0.05, 0.08, technique="ispm_caustics", component="caustic",
                               mask_level=level, redraw="0", seed=seed))
            out.append(seq_row(redraw + d, 0.05, 0.08, technique="ispm_caustics",
                               component="caustic", mask_level=level, redraw="1", seed=seed))
    return out


def claims(work):
    results = os.path.join(work, "r")
    os.makedirs(results)
    check(tt.claims(results)[0].verdict == tt.NOT_MEASURABLE, "no rows: not measurable")
    write_table(results, "temporal_lrsm_dragon", lrsm_rows(0.05))
    write_table(results, "temporal_thesis_water", water_rows(0.056))
    write_table(results, "plain", [{"technique": "direct", "component": "direct"}], seq=False)
    c = tt.claims(results)
    check([x.verdict for x in c] == [tt.REPRODUCED, tt.REPRODUCED],
          f"steady lrsm and reuse lower beyond the spread: both reproduced ({[x.verdict for x in c]})")
    check(all(isinstance(x, Claim) and x.kind == MACHINE_INDEPENDENT for x in c),
          "claims are Claims, of the machine-independent kind")
    write_table(results, "temporal_lrsm_dragon", lrsm_rows(0.1))
    write_table(results, "temporal_thesis_water", water_rows(0.0505))
    c = tt.claims(results)
    check([x.verdict for x in c] == [tt.NOT_REPRODUCED, tt.NOT_REPRODUCED],
          f"flickering glossy, and reuse within the spread at level 2: not reproduced ({[x.verdict for x in c]})")
    check("glossy" in c[0].reason, "the LRSM reason names the failing component")
    path, rows = tt.write(results)
    check(len(rows) == 3 + 12, f"the sequence table: the sequence tables' rows only ({len(rows)})")
    with open(path) as f:
        head = f.readline().strip().split(",")
    check({"temporal_rmse", "flicker", "steady", "animation"} <= set(head), "its temporal columns")


def main():
    work = tempfile.mkdtemp()
    try:
        ratios()
        claims(work)
    finally:
        shutil.rmtree(work)
    print("FAILED: %d checks" % len(FAILS) if FAILS else "all checks passed")
    return 1 if FAILS else 0


if __name__ == "__main__":
    sys.exit(main())
