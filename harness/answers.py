"""Which technique to use: for each component and scene that two or more techniques estimate, the
rows no other row beats on both error and cost (the Pareto set), with ties called and rows worse
than a black image set apart.

A row's error is its RMSE interval (uncertainty.error_interval: the reference's noise taken out,
lo..hi; absolute, as every row of a group is scored against the same reference image);
its time is the warm median at the machine's resolution (uncertainty.time_interval: two medians
closer than the timing benchmark's run-to-run spread tie); its memory is the ledger's bytes, exact,
so equal bytes tie and nothing else does. Row a beats row b when a is no worse on both axes (lower
or tied) and clearly better on one (lower and not tied). A row that beats nothing and is beaten by
nothing is on the front; a front row whose error interval overlaps another front row's ties with it.

A group is (component, scene, camera, image size, renderer): times from two renderers or two image
sizes are not one axis. Rows further from the reference than a black image (rmse_over_black > 1)
never enter the front; they are listed as such. Rows whose status is not `ok` are left out. A
group whose reference is black (black_rmse 0: a component the scene does not have, or a view that
should be dark) ranks nothing: any error there is light that should not be, which the leak claims
judge, so it is not a question of this table.
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from uncertainty import error_interval, fnum, overlap, time_interval, worse_than_black  # noqa: E402

GROUP = ("component", "scene", "camera", "width", "height", "renderer")


def group_key(r):
    return tuple(r.get(k, "") for k in GROUP)


def time_cost(r, resolution):
    ms = fnum(r.get("gpu_ms_median"))
    return None if ms is None else time_interval(ms, resolution)


def memory_cost(r, _resolution=None):
    b = fnum(r.get("mem_bytes"))
    return None if b is None else (b, b, b)


def compare(a, b):
    """-1 when interval a is clearly below b, 1 when clearly above, 0 when they overlap (a tie)."""
    if overlap(a, b):
        return 0
    return -1 if a[1] < b[1] else 1


def beats(a, b):
    """Whether candidate a beats candidate b: no worse on error and cost, clearly better on one.
    A candidate is (row, error interval, cost interval)."""
    e, c = compare(a[1], b[1]), compare(a[2], b[2])
    return e <= 0 and c <= 0 and (e < 0 or c < 0)


def distinct(rows):
    """One row per technique and parameters: the same setting run by two matrices (a figure's and a
    sweep's) is one candidate, the first met (the tables are read in name order), not two that tie
    with each other."""
    seen, out = set(), []
    for r in rows:
        key = (r.get("technique"), r.get("params"))
        if key not in seen:
            seen.add(key)
            out.append(r)
    return out


def candidates(rows, cost, resolution):
    """(usable candidates, rows worse than black) of one group."""
    usable, black = [], []
    for r in distinct(rows):
        if r.get("status") != "ok":
            continue
        err, cst = error_interval(r), cost(r, resolution)
        if err is None or cst is None:
            continue
        (black if worse_than_black(r) else usable).append((r, err, cst))
    return usable, black


def front(cands):
    """The candidates no other candidate beats, ordered by cost."""
    out = [a for a in cands if not any(beats(b, a) for b in cands if b is not a)]
    return sorted(out, key=lambda c: (c[2][1], c[1][1]))


def error_ties(fr):
    """{index in fr: indices of the other front rows whose error interval overlaps its own}."""
    return {i: [j for j, b in enumerate(fr) if j != i and overlap(a[1], b[1])]
            for i, a in enumerate(fr)}


def answer(rows, cost=time_cost, resolution=None):
    """One group's answer: {"front": [(row, err, cost), ...] cheapest first, "ties": error_ties,
    "black": [rows worse than black], "techniques": techniques with a usable or black row,
    "least_error": the technique of the front's lowest error estimate}."""
    usable, black = candidates(rows, cost, resolution)
    fr = front(usable)
    techniques = sorted({c[0]["technique"] for c in usable} | {c[0]["technique"] for c in black})
    best = min(fr, key=lambda c: c[1][1])[0]["technique"] if fr else None
    return {"front": fr, "ties": error_ties(fr), "black": [c[0] for c in black],
            "techniques": techniques, "least_error": best}


def by_technique(fr):
    """The front grouped by technique, cheapest first: [(technique, [candidates])]. A technique
    whose settings tie one another appears once, with all of them."""
    out = {}
    for c in fr:
        out.setdefault(c[0]["technique"], []).append(c)
    return list(out.items())


def reference_black(rows):
    return all(fnum(r.get("black_rmse")) == 0 for r in rows if fnum(r.get("black_rmse")) is not None)


def groups(rows):
    """{group key: rows} for the groups that two or more techniques estimate with a usable row
    (status ok, an error, a time) against a reference that is not black."""
    by = {}
    for r in rows:
        by.setdefault(group_key(r), []).append(r)
    out = {}
    for key, grp in by.items():
        usable, black = candidates(grp, time_cost, None)
        if len({c[0]["technique"] for c in usable + black}) >= 2 and not reference_black(grp):
            out[key] = grp
    return out


def answers(rows, resolution=None):
    """[(group key, time answer, memory answer)] for every group two or more techniques estimate,
    ordered by component then scene."""
    order = {c: i for i, c in enumerate(("ao", "direct", "indirect", "glossy", "caustic"))}
    out = []
    for key, grp in groups(rows).items():
        out.append((key, answer(grp, time_cost, resolution), answer(grp, memory_cost)))
    return sorted(out, key=lambda a: (order.get(a[0][0], 9), a[0][1:]))
