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

A group is (component, scene, camera, image size, renderer, time, the reference's parameters): times
from two renderers or two image sizes are not one axis, and rows scored against two different
reference images (two instants of an animation, ambient occlusion at two dmax) estimate different
things. Rows further from the reference than a black image (rmse_over_black > 1)
never enter the front; they are listed as such. Rows whose status is not `ok` are left out. A
group whose reference is black (black_rmse 0: a component the scene does not have, or a view that
should be dark) ranks nothing: any error there is light that should not be, which the leak claims
judge, so it is not a question of this table.
"""
import math

from reporting import claims  # noqa: E402
from reporting import external  # noqa: E402
from reporting import schema  # noqa: E402
from reporting.schema import param  # noqa: E402
from reporting.uncertainty import error_interval, fnum, overlap, time_interval, worse_than_black  # noqa: E402

GROUP = ("component", "scene", "camera", "width", "height", "renderer")
# The technique parameters that change a component's reference image, with the reference's own
# value where a technique lacks one (the techniques' gib_ref_binding, as gibench exports them: ao
# at a dmax, as obscurance or not). Rows at two settings of these estimate two different images:
# not one group.
REFERENCE_PARAMS = schema.reference_params()


def reference_text(r):
    """'dmax=20' for a row whose component's reference has parameters (those at the reference's
    own default left out), else ''."""
    out = []
    for name, default in REFERENCE_PARAMS.get(r.get("component"), ()):
        v = param(r, name, default)
        if v != default:
            out.append(f"{name}={v:g}")
    return " ".join(out)


def group_key(r):
    """(component, scene, camera, width, height, renderer, time, reference parameters): the rows
    that estimate one image on one renderer. The first six are GROUP, in its order; an external
    renderer's row ranks on the renderer of its table's built-in rows, the machine it ran on
    (external.group_renderer)."""
    t = fnum(r.get("time")) or 0.0
    return tuple(external.group_renderer(r) if k == "renderer" else r.get(k, "") for k in GROUP) + \
        (f"{t:g}", reference_text(r))


def time_cost(r, resolution):
    """A row's time interval: at the machine's resolution, or at the row's own where it carries one
    (a GPU-timed copy, gpu_rows.timed_copies)."""
    ms = fnum(r.get("gpu_ms_median"))
    return None if ms is None else time_interval(ms, fnum(r.get("time_resolution")) or resolution)


def memory_cost(r, _resolution=None):
    """A row's memory, exact: the ledger's bytes; an external renderer's as its program reported
    them, none where it reported none (its row holds 0)."""
    b = fnum(r.get("mem_bytes"))
    if b is None or (not b and external.is_external(r)):
        return None
    return (b, b, b)


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
    "least_error": the technique of the front's lowest error estimate, "rows": the group's rows}."""
    usable, black = candidates(rows, cost, resolution)
    fr = front(usable)
    techniques = sorted({c[0]["technique"] for c in usable} | {c[0]["technique"] for c in black})
    best = min(fr, key=lambda c: c[1][1])[0]["technique"] if fr else None
    return {"front": fr, "ties": error_ties(fr), "black": [c[0] for c in black],
            "techniques": techniques, "least_error": best, "rows": rows}


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


def segments(fr):
    """The front cut where the technique changes, cheapest first: [(technique, [candidates])]. A
    technique whose neighbouring settings make several front points shows as one segment (its
    cheapest to its least error), so a front of ten lrsm settings reads as one step, not ten."""
    out = []
    for c in fr:
        if out and out[-1][0] == c[0]["technique"]:
            out[-1][1].append(c)
        else:
            out.append((c[0]["technique"], [c]))
    return out


def answers_rows(ans):
    return usable_rows(ans["rows"])


def usable_rows(rows):
    """The candidates of a group that any question of it may rank: distinct settings, status ok,
    with an error and a time."""
    usable, black = candidates(rows, time_cost, None)
    return [c[0] for c in usable + black]


def gpu_timed(t):
    """Whether an answer's times come from a GPU (every row a GPU-timed copy)."""
    return bool(t["rows"]) and all(r.get("time_source") for r in t["rows"])


# Where a paper made its point, per component: a predicate on a group's key. The LDM paper's Fig. 8
# point is AO at dmax >= 1280 (Sponza's units), where HBAO falls far behind; a group there heads
# the component's row on the first screen before any other of its scene.
PAPER_POINT = {"ao": lambda key: any(w.startswith("dmax=") and float(w[5:]) >= 1280
                                     for w in key[7].split())}


def paper_point(key):
    """Whether a group's key is where a paper made its point for its component (PAPER_POINT)."""
    test = PAPER_POINT.get(key[0])
    return bool(test and test(key))


def headline(ans_list):
    """One answer per (component, scene): a group where a paper made its point (PAPER_POINT), then
    one timed on a GPU where there is one (its error from the paper profile's rows), then a group
    of the papers'-settings rows (profile paper), then the group the most techniques estimate (then
    the largest image, then the most settings, then the fewest worse than black): [(key, time
    answer, memory answer, [keys of the other groups of that component and scene: other sizes,
    cameras and renderers])], in the order of ans_list."""
    by = {}
    for a in ans_list:
        key = a[0]
        by.setdefault((key[0], key[1]), []).append(a)

    def weight(a):
        key, t, _ = a
        return (paper_point(key), gpu_timed(t), profile_of(t["rows"]) == "paper", len(t["techniques"]),
                int(key[3]) * int(key[4]), len(answers_rows(t)), -len(t["black"]))

    out = []
    for a in ans_list:
        peers = by[(a[0][0], a[0][1])]
        best = max(peers, key=weight)
        if a is best:
            out.append((a[0], a[1], a[2], [p[0] for p in peers if p is not a]))
    return out


def profile_of(rows):
    """The profile a group's rows ran ('paper', 'quick', ...; profiles joined by '+' where they
    mix): a reader is told which rows an answer stands on."""
    return "+".join(sorted({r.get("profile", "") for r in rows})) or "?"


def at_common_cost(rows):
    """Each technique's row nearest the group's median time (on a log scale: 10 ms is as far from
    20 ms as 40 ms is), so a gallery compares techniques at about the same cost: [(row, ...)] in the
    order of time. Rows are the group's usable ones (worse than black included: the reader sees why)."""
    usable = [r for r in usable_rows(rows) if fnum(r.get("gpu_ms_median")) and fnum(r["gpu_ms_median"]) > 0]
    if not usable:
        return []
    times = sorted(fnum(r["gpu_ms_median"]) for r in usable)
    median = times[len(times) // 2]
    best = {}
    for r in usable:
        d = abs(math.log(fnum(r["gpu_ms_median"]) / median))
        t = r["technique"]
        if t not in best or d < best[t][0]:
            best[t] = (d, r)
    return sorted((v[1] for v in best.values()), key=lambda r: fnum(r["gpu_ms_median"]))


# ---- the papers' claims (claims.csv, harness/reporting/claims.py) --------------------------------------------

from reporting.claim import (ABSOLUTE_TIME, MACHINE_INDEPENDENT, NOT_MEASURABLE, NOT_REPRODUCED,  # noqa: E402,F401
                             REPRODUCED, TIME_ORDER)


def claim_kind(c):
    """A claim's `kind` column where claims.csv has one; else absolute_time for a claim not
    measurable here because the paper timed its own GPU (the reason says the absolute time is not
    comparable, or the claim is a table's frame time), machine_independent otherwise (memory, error,
    orders of stage times, leaks: what this machine measures as the paper's would)."""
    if c.get("kind"):
        return c["kind"]
    if c.get("verdict") != NOT_MEASURABLE:
        return MACHINE_INDEPENDENT
    reason, claim = c.get("reason", "").lower(), c.get("claim", "").lower()
    if "absolute" in reason or claim.endswith("frame time"):
        return ABSOLUTE_TIME
    return MACHINE_INDEPENDENT


stem = claims.stem  # a claim's words before its settings


def first_clause(text, keep=110, clauses=1):
    """The first clauses (;-separated) of a reason, cut at `keep` characters."""
    t = ";".join(text.split(";")[:clauses]).strip()
    return t if len(t) <= keep else t[:keep].rstrip() + "…"


def what_would_measure(c):
    """Why a claim is not measurable here: (what it is, what would measure it)."""
    r = c.get("reason", "").lower()
    if r.startswith("not run here"):
        return "not run here", "a run at the paper's setting, which our matrices lack"
    if claim_kind(c) == ABSOLUTE_TIME:
        return "absolute GPU times", "a GPU: the papers timed theirs"
    if schema.status("out_of_memory") in r or "out of memory" in r:
        return "out of memory here", "a machine with more memory"
    if "profile" in r or "settings" in r:
        return "not at the paper's settings", "make reproduce PROFILE=paper"
    return "no run of ours matches", first_clause(c.get("reason", ""), 80)


def by_stem(claims):
    """[(stem, [claims])] in first-met order."""
    out = {}
    for c in claims:
        out.setdefault(stem(c["claim"]), []).append(c)
    return list(out.items())


def findings(claims):
    """Per paper, what its claims came to, from claims.csv alone: [{"paper", "counts": {verdict: n},
    "not_reproduced": [(stem, n, paper value, our value, first clause of the reason)],
    "unmeasured": [(what they are, what would measure them, n)]}], papers in first-met order."""
    papers = {}
    for c in claims:
        papers.setdefault(c["paper"], []).append(c)
    out = []
    for paper, cs in papers.items():
        counts = {v: sum(1 for c in cs if c["verdict"] == v) for v in (REPRODUCED, NOT_REPRODUCED, NOT_MEASURABLE)}
        failed = [(s, len(g), g[0]["paper_value"], g[0]["our_value"], first_clause(g[0]["reason"], 140, 2))
                  for s, g in by_stem([c for c in cs if c["verdict"] == NOT_REPRODUCED])]
        need = {}
        for c in cs:
            if c["verdict"] == NOT_MEASURABLE:
                w = what_would_measure(c)
                need[w] = need.get(w, 0) + 1
        need = [(what, by, n) for (what, by), n in need.items()]
        out.append({"paper": paper, "counts": counts, "not_reproduced": failed,
                    "unmeasured": sorted(need, key=lambda x: -x[2])})
    return out


def plot_name(key):
    """The file name (no extension) of a group's speed-against-error plot (plot.py writes it, the
    report links it): answer_<component>_<scene>_cam<camera>_<W>x<H>[_t<time>][_<reference
    parameters>]_<renderer's first word>."""
    component, scene, camera, w, h, renderer, t, ref = key
    word = "".join(ch for ch in (renderer.split() or ["unknown"])[0].lower() if ch.isalnum()) or "unknown"
    extra = (f"_t{t}" if t != "0" else "") + ("_" + ref.replace(" ", "_").replace("=", "-") if ref else "")
    return f"answer_{component}_{scene}_cam{camera}_{w}x{h}{extra}_{word}"


def relative_error(r):
    """The row's error as the report shows it: the de-noised RMSE over the reference's mean
    (lo, estimate, hi), the plain RMSE interval where the relative one is undefined."""
    return error_interval(r, relative=True) or error_interval(r)
