"""What a row's numbers can and cannot tell apart, read from the result CSVs (no C code):

- an error's interval: the row's `rmse_lo` .. `rmse_hi` around `rmse_denoised` (the RMSE with the
  reference's noise taken out, metrics.h gib_rmse_interval), in RMSE or relative to the
  reference's mean; two rows whose intervals overlap are a tie, not a rank;
- the black image: `black_rmse`, what an all-black image scores against the same reference; a row
  with `rmse_over_black` above 1 is further from the reference than leaving the component out;
- a time's resolution: the smallest relative difference between two medians this machine resolves,
  from RESULTS_DIR/timing_resolution.csv (harness/reporting/bench_timing.py: the 95th percentile of the
  run-to-run difference of the same runs); two times closer than it are a tie;
- a memory figure: bytes do not depend on the machine, but a paper's figure may count what ours
  does not, or round: ours agrees with it within MEMORY_TOLERANCE, for every paper alike (claim.py
  states the tolerance of every kind of claim).
"""
import os

from reporting.schema import fnum, read_csv  # noqa: E402,F401  (fnum: a finite float or None)

from reporting.claim import MEMORY_TOLERANCE  # noqa: E402,F401  (a memory figure agrees within 25%)


def error_interval(r, relative=False):
    """(lo, estimate, hi) of the row's error with the reference's noise accounted for; the plain
    RMSE three times for a table written before the interval existed. Relative: divided by the
    reference's mean (rmse / rel_rmse). None where the row has no finite error."""
    rmse = fnum(r.get("rmse"))
    if rmse is None:
        return None
    lo, est, hi = (fnum(r.get(k)) for k in ("rmse_lo", "rmse_denoised", "rmse_hi"))
    if est is None or lo is None or hi is None:
        lo = est = hi = rmse
    if relative:
        rel = fnum(r.get("rel_rmse"))
        if rel is None or rel == 0 or rmse == 0:
            return None if rel is None else (0.0, 0.0, 0.0)
        mean = rmse / rel
        return lo / mean, est / mean, hi / mean
    return lo, est, hi


def over_black(r):
    """The row's RMSE over the black image's, or None where the table has no black column. A black
    reference (a view that should be dark, thin_wall_leak's) makes any light infinitely worse."""
    try:
        ratio = float(r.get("rmse_over_black"))
    except (TypeError, ValueError):
        ratio = None
    if ratio is not None and ratio == ratio:
        return ratio
    rmse, black = fnum(r.get("rmse")), fnum(r.get("black_rmse"))
    return rmse / black if rmse is not None and black else None


def worse_than_black(r):
    ratio = over_black(r)
    return ratio is not None and ratio > 1.0


def overlap(a, b):
    """Whether two (lo, estimate, hi) intervals overlap."""
    return a[0] <= b[2] and b[0] <= a[2]


def time_resolution(results, kind="total"):
    """The relative time resolution of the machine (timing_resolution.csv), or None when the timing
    benchmark has not been run (then no time difference is called a tie: say so where it matters)."""
    for row in read_csv(os.path.join(results, "timing_resolution.csv")):
        if row.get("kind") == kind:
            return fnum(row.get("resolution_rel"))
    return None


def time_interval(ms, resolution):
    """A median's interval at the machine's resolution: two medians tie when |a - b| <= r x mean."""
    half = 0.5 * (resolution or 0.0)
    return ms * (1 - half), ms, ms * (1 + half)


def compare_times(a, b, resolution):
    """'>' / '<' / 'tie' for two medians (ms) at the relative resolution (None: no tie is called)."""
    if resolution and overlap(time_interval(a, resolution), time_interval(b, resolution)):
        return "tie"
    return ">" if a > b else "<" if a < b else "tie"


def ranks(items):
    """Ranks with ties: items are (id, (lo, estimate, hi)); ordered by estimate, an item whose
    interval overlaps its predecessor's shares its rank. Returns {id: "1", "2=", ...}: '=' marks
    a rank shared with another item."""
    order = sorted(items, key=lambda kv: kv[1][1])
    rank, out, prev = {}, {}, None
    for i, (key, iv) in enumerate(order):
        rank[key] = rank[prev[0]] if prev is not None and overlap(prev[1], iv) else i + 1
        prev = (key, iv)
    counts = {}
    for v in rank.values():
        counts[v] = counts.get(v, 0) + 1
    for key, v in rank.items():
        out[key] = f"{v}=" if counts[v] > 1 else str(v)
    return out
