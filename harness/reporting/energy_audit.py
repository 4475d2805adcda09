"""The energy audit: for every technique, named reading (preset), scene and component, the image's
mean over the reference's and its RMSE over a black image's, over the rows that ran there.

A cell is read from the papers'-settings rows (profile `paper`) where it has any, else from the
quick profile, and says which. A cell whose mean ratio leaves 0.85-1.15 needs a cause: either a
fix, or a measured control that shows where the gap comes from; the causes are written by hand in
harness/energy_causes.csv (technique, preset, scene, component, cause, control), and a cell outside
the band with none is listed as unexplained. A cause's `verdict` is `explained` (the control
accounts for the gap), `partly` (a part fixed or accounted for, the rest open) or `open`; its scene
or component may be `*` (every scene or component of that technique and preset without a cause of
its own). An external renderer's cells (external.py) are named as the report names it, with its
program and version (`ext:x (external, render.py 1.0)`), its rows of a version its table supersedes
left out (external.superseded). Writes RESULTS/energy_audit.csv.
"""
import csv
import html
import os

from reporting import external  # noqa: E402
from reporting.schema import fnum, matrices, preset, read_csv

HERE = os.path.dirname(os.path.abspath(__file__))
BAND = (0.85, 1.15)
COMPONENTS = ("direct", "indirect", "glossy", "caustic", "ao")
COLUMNS = ["technique", "preset", "scene", "component", "profile", "rows", "mean_ratio_min",
           "mean_ratio_max", "rmse_over_black_min", "rmse_over_black_max", "worse_than_black",
           "outside_band", "verdict", "cause", "control", "matrices"]
INTRO = ("Each technique's image energy on each scene and component: its mean over the reference's "
         f"(in {BAND[0]}-{BAND[1]} it carries about the reference's light) and its RMSE over a black "
         "image's (above 1 the image is further from the reference than leaving the component out), "
         "the least and the most over the rows that ran there. The papers'-settings rows (profile "
         "paper) are read where a matrix has them, else the quick profile's, which the cell names. "
         "A cell outside the band gives its cause with the measured control that shows it.")


def causes():
    """{(technique, preset, scene, component): row} of harness/energy_causes.csv."""
    out = {}
    for r in read_csv(os.path.join(HERE, "energy_causes.csv")):
        out[(r["technique"], r["preset"], r["scene"], r["component"])] = r
    return out


def cause_of(known, technique, preset_name, scene, component):
    """The cause written for a cell: its own, else its technique and preset's for every scene, for
    every component, or for both ({} where there is none)."""
    for key in ((scene, component), ("*", component), (scene, "*"), ("*", "*")):
        if (technique, preset_name) + key in known:
            return known[(technique, preset_name) + key]
    return {}


def chosen_rows(mats):
    """The rows each cell is read from: the paper profile's where the cell (technique, preset,
    scene, component) has any ok row of it in any matrix, else the quick profile's. A parameter
    study run only at the quick profile (lrsm_sweeps_cones, _layers: apertures and layer counts
    away from the paper's) then speaks for a cell only where no row at the papers' settings does.
    A row whose reference is black (a leak test, a component the view lacks) has no energy to
    audit: the leak claims judge it."""
    old = {k for rows in mats.values() for k in external.superseded(rows)}  # an external's older versions
    ok = [(name, r) for name, rows in mats.items() for r in rows
          if r.get("status") == "ok" and id(r) not in old and r.get("component") in COMPONENTS
          and fnum(r.get("mean_ratio")) is not None and fnum(r.get("black_rmse")) != 0]
    cell = lambda r: (external.label(r), preset(r), r["scene"], r["component"])  # noqa: E731
    with_paper = {cell(r) for _, r in ok if r.get("profile") == "paper"}
    return [(name, r) for name, r in ok if r.get("profile") == "paper" or cell(r) not in with_paper]


def cells(mats):
    """The audit's cells, sorted by technique, preset, scene and component."""
    groups = {}
    for name, r in chosen_rows(mats):
        # an external renderer's cell is named with its program and version (external.label)
        key = (external.label(r), preset(r), r["scene"], r["component"], r["profile"])
        groups.setdefault(key, []).append((name, r))
    known = causes()
    out = []
    for key in sorted(groups):
        rs = [r for _, r in groups[key]]
        ratio = [fnum(r["mean_ratio"]) for r in rs]
        over = [x for x in (fnum(r.get("rmse_over_black")) for r in rs) if x is not None]
        outside = min(ratio) < BAND[0] or max(ratio) > BAND[1]
        why = cause_of(known, *key[:4]) if outside else {}
        out.append({"technique": key[0], "preset": key[1], "scene": key[2], "component": key[3],
                    "profile": key[4], "rows": len(rs),
                    "mean_ratio_min": f"{min(ratio):.3g}", "mean_ratio_max": f"{max(ratio):.3g}",
                    "rmse_over_black_min": f"{min(over):.3g}" if over else "",
                    "rmse_over_black_max": f"{max(over):.3g}" if over else "",
                    "worse_than_black": sum(1 for x in over if x > 1),
                    "outside_band": int(outside), "verdict": why.get("verdict", "open" if outside else ""),
                    "cause": why.get("cause", ""), "control": why.get("control", ""),
                    "matrices": " ".join(sorted({n for n, _ in groups[key]}))})
    return out


def write(results):
    rows = cells(matrices(results))
    path = os.path.join(results, "energy_audit.csv")
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=COLUMNS, lineterminator="\n")
        w.writeheader()
        w.writerows(rows)
    return path, rows


def span(lo, hi):
    return lo if lo == hi else f"{lo}-{hi}"


HEAD = ["technique", "preset", "scene", "component", "profile (rows)", "mean / reference's",
        "RMSE / black's", "cause (control)"]


def row_cells(c):
    flag = " (outside)" if c["outside_band"] else ""
    worse = f", {c['worse_than_black']} worse than black" if c["worse_than_black"] else ""
    cause = c["cause"] + (f" ({c['control']})" if c["control"] else "")
    if c["outside_band"]:
        cause = (f"{c['verdict']}: {cause}" if cause else "unexplained")
    return [c["technique"], c["preset"], c["scene"], c["component"], f"{c['profile']} ({c['rows']})",
            span(c["mean_ratio_min"], c["mean_ratio_max"]) + flag,
            span(c["rmse_over_black_min"], c["rmse_over_black_max"]) + worse, cause]


def counts_text(rows):
    outside = [c for c in rows if c["outside_band"]]
    explained = sum(1 for c in outside if c["verdict"] == "explained")
    partly = sum(1 for c in outside if c["verdict"] == "partly")
    quick = sum(1 for c in rows if c["profile"] != "paper")
    return (f"{len(rows)} cells, {len(outside)} outside {BAND[0]}-{BAND[1]}: {explained} explained by a "
            f"measured control, {partly} partly, {len(outside) - explained - partly} open; {quick} read "
            "from quick-profile rows")


def section_md(rows):
    if not rows:
        return []
    lines = ["## Energy audit", "", INTRO + " " + counts_text(rows) + ".", "",
             "| " + " | ".join(HEAD) + " |", "|" + "---|" * len(HEAD)]
    for c in rows:
        lines.append("| " + " | ".join(str(x).replace("|", "\\|") for x in row_cells(c)) + " |")
    return lines + [""]


def section_html(rows):
    if not rows:
        return ""
    head = "".join(f"<th>{html.escape(h)}</th>" for h in HEAD)
    body = "".join("<tr" + (' class="outside"' if c["outside_band"] else "") + ">"
                   + "".join(f"<td>{html.escape(str(x))}</td>" for x in row_cells(c)) + "</tr>"
                   for c in rows)
    return (f'<h2 id="energy">Energy audit</h2><p>{html.escape(INTRO)} {html.escape(counts_text(rows))}.</p>'
            f'<details class="energy"><summary>every cell ({len(rows)})</summary>'
            f'<table class="energy"><tr>{head}</tr>{body}</table></details>')
