#!/usr/bin/env python3
"""harness/reporting/uncertainty.py on constructed rows: ranks with ties (overlapping intervals share a rank),
time ties at the machine's resolution, the black image's ratio, the interval read from a row (and
the plain RMSE for a table without one)."""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "harness"))
from reporting.uncertainty import compare_times, error_interval, over_black, ranks, worse_than_black  # noqa: E402

failures = 0


def check(cond, what):
    global failures
    print(("PASS " if cond else "FAIL ") + what)
    failures += not cond


r = ranks([("a", (0.9, 1.0, 1.1)), ("b", (1.05, 1.2, 1.3)), ("c", (2.0, 2.1, 2.2)), ("d", (0.1, 0.2, 0.3))])
check(r == {"d": "1", "a": "2=", "b": "2=", "c": "4"}, f"overlapping a, b share rank 2, c is 4th: {r}")
check(compare_times(10.0, 10.4, 0.05) == "tie", "10.0 vs 10.4 ms at 5% resolution: a tie")
check(compare_times(10.0, 11.0, 0.05) == "<", "10.0 vs 11.0 ms at 5%: ordered")
check(compare_times(10.0, 10.4, None) == "<", "no resolution measured: no tie called")
row = {"rmse": "0.2", "rel_rmse": "2", "rmse_lo": "0.18", "rmse_denoised": "0.19", "rmse_hi": "0.2",
       "black_rmse": "0.1", "rmse_over_black": "2"}
check(error_interval(row) == (0.18, 0.19, 0.2), f"interval read: {error_interval(row)}")
lo, est, hi = error_interval(row, relative=True)
check(abs(est - 1.9) < 1e-12 and abs(lo - 1.8) < 1e-12, f"relative to the mean 0.1: {est}")
check(worse_than_black(row) and over_black(row) == 2.0, "twice the black image's error: worse than black")
check(worse_than_black({"rmse": "0.1", "rel_rmse": "inf", "black_rmse": "0", "rmse_over_black": "inf"}),
      "light where the reference is black: worse than black")
old = {"rmse": "0.3", "rel_rmse": "1"}
check(error_interval(old) == (0.3, 0.3, 0.3) and over_black(old) is None,
      "a table from before the interval: the plain RMSE, no black ratio")
print(f"{'FAIL' if failures else 'PASS'}: {failures} failures")
sys.exit(1 if failures else 0)
