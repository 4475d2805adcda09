#!/usr/bin/env python3
"""Gathers every claim of every paper that paper_tables.py set beside our numbers into one table,
RESULTS_DIR/claims.csv: a row per claim with the paper's value, ours, the machine ours ran on, its
kind and a verdict `reproduced` / `not reproduced` / `not measurable here`, with the reason. A
claim tested at several settings is one row (counted_once), its settings the evidence beneath it.

usage: python3 -m reporting.claims RESULTS_DIR

Reads only the CSVs paper_tables.py writes (thesis_tables.csv, lrsm_table2.csv, lrsm_table3.csv,
lrsm_fig7.csv, lrsm_dynamic.csv, ldm_figures_vs_ours.csv, ldm_claims.csv); a missing file gives no
rows.
Kinds, by what a claim depends on: `machine_independent` (memory, error, leaks: any machine judges
them), `time_order` (an order or ratio of times: judged on the renderer the row names) or
`absolute_time` (a paper's absolute time on its GPU).
Verdict rules (the choice this file makes, stated once):
- a row whose table already says reproduced yes/no keeps that verdict;
- an absolute time measured on the paper's GPU is `not measurable here` on another renderer (a
  time on llvmpipe says nothing about a GTX 770's), as is a row that did not run;
- tolerances, one per kind of claim: memory holds within MEMORY_TOLERANCE (25%) of the paper's
  figure, every paper alike (byte counts do not depend on the renderer; a paper's figure may count
  what ours does not, or round); whether our bytes equal the paper's own formula is a separate fact,
  stated in the reason, never the verdict. Errors are compared as intervals (overlap: a tie, no
  tolerance), orders of times at the machine's time resolution, qualitative claims by the threshold
  their table states (a leak visible from 1% of display white). A run refused for memory is
  measured by its plan (what the ledger recorded before it would have allocated), the same bytes.
The result CSVs do not record the CPU's cores; `cores` comes from RESULTS_DIR/history.sqlite (the
machines `gibench run` recorded) where exactly one core count was recorded with the row's renderer,
and stays empty otherwise (a renderer string alone does not name a machine).
"""
import os
import re
import sqlite3
import sys

from reporting.schema import read_csv, status, write_csv  # noqa: E402  (a CSV's rows, [] when absent)
from reporting.uncertainty import MEMORY_TOLERANCE  # noqa: E402
from reporting import temporal_tables  # noqa: E402  (the papers' temporal claims, from the sequence tables)
from reporting import gpu_claims  # noqa: E402  (the time claims a valid device run answers)
from reporting import lrsm_tables  # noqa: E402  (Table 3's stage-order claims)

COLUMNS = ["paper", "source", "claim", "kind", "paper_value", "our_value", "renderer", "cores",
           "verdict", "reason"]
MACHINE_INDEPENDENT, ABSOLUTE_TIME = "machine_independent", "absolute_time"
TIME_ORDER = "time_order"  # an order or ratio of times: judged on the renderer the row names
REPRODUCED, NOT_REPRODUCED, NOT_MEASURABLE = "reproduced", "not reproduced", "not measurable here"
THESIS = "Le 2014 (thesis): interactive caustics and multi-resolution indirect illumination"
LRSM = "Sugihara et al. 2014: Layered Reflective Shadow Maps (LRSM)"
LDM = "Layered depth maps (LDM) for ambient occlusion and indirect light"


def read(results, name):
    return read_csv(os.path.join(results, name))


def verdict_of(text):
    """The tables' `reproduced` column: yes / no, anything else (missing, not comparable ...)."""
    t = (text or "").strip().lower()
    if t == "yes":
        return REPRODUCED, ""
    if t == "no":
        return NOT_REPRODUCED, ""
    return NOT_MEASURABLE, text or "no run of ours matches (missing)"


def row(paper, source, claim, paper_value, our_value, renderer, verdict, reason, cores="",
        kind=MACHINE_INDEPENDENT):
    return {"paper": paper, "source": source, "claim": claim, "kind": kind, "paper_value": paper_value,
            "our_value": our_value, "renderer": renderer, "cores": cores, "verdict": verdict,
            "reason": reason}


def thesis(results):
    out = []
    rows = read(results, "thesis_tables.csv")
    # claim lines leave the renderer empty: theirs is the one the table's rows ran on
    renderers = sorted({r["renderer"] for r in rows if r["renderer"]})
    for r in rows:
        if r["kind"] == "claim":
            v, why = verdict_of(r["reproduced"])
            out.append(row(THESIS, "thesis_tables.csv", r["claim"], r.get("paper_value", ""),
                           r.get("our_value", ""), r["renderer"] or "; ".join(renderers), v,
                           r["evidence"] if v != NOT_MEASURABLE else why + "; " + r["evidence"]))
        elif r["kind"] == "row":
            what = (f"Table {r['table']} {r['paper_scene']}: {r['resolution']}^2 image, "
                    f"{r['caustic_photons']} photons, {r['ray_resolution']}^2 rays, t={r['time_s']}: "
                    f"frame time")
            if r["status"] != "ok":
                reason = "not run here: " + (r["note"] or r["status"])
            else:
                reason = ("the thesis timed its GPU; ours ran on " + (r["renderer"] or "another renderer")
                          + " at " + r["our_settings"].split(" profile=")[0].rsplit(" ", 1)[-1]
                          + ": absolute times are not comparable (the linear-tracing and speed-up "
                          "claims compare ratios instead)")
            out.append(row(THESIS, "thesis_tables.csv", what,
                           f"{r['paper_frame_ms']} ms ({r['paper_fps']} fps)" if r["paper_frame_ms"] else "",
                           f"{r['our_frame_ms']} ms" if r["our_frame_ms"] else "", r["renderer"],
                           NOT_MEASURABLE, reason, kind=ABSOLUTE_TIME))
    return out


def lrsm_table2(results):
    """Table 2: memory per structure, compared exactly (byte counts do not depend on the renderer),
    and its frame times (absolute, on the paper's GPUs)."""
    out = []
    for r in read(results, "lrsm_table2.csv"):
        if r["structure"] == "frame_ms":
            out.append(lrsm_table2_time(r))
            continue
        if not r["paper_mb"]:
            continue  # a formula's figure with no number of the paper's beside it
        what = f"Table 2 {r['paper_scene']} {r['technique']} {r['structure']} memory ({r['setting']})"
        planned = r["status"] == status("out_of_memory") and r["ours_mb"]
        if r["status"] == "missing" or not r["ours_mb"]:
            v, why = NOT_MEASURABLE, "no run of ours measured this structure"
        elif r["status"] != "ok" and not planned:
            v, why = NOT_MEASURABLE, f"our run ended {r['status']} on this machine ({r['note']})".rstrip(" ()")
        else:
            v, why = memory_verdict(float(r["ours_mb"]), paper_number(r["paper_mb"]))
            why += (f"; against the formula: ours {r['ours_vs_formula']}, the paper's {r['paper_vs_formula']}"
                    + ("; ours planned, not allocated (over memory_budget_mb)" if planned else ""))
        out.append(row(LRSM, "lrsm_table2.csv", what, f"{r['paper_mb']} MB",
                       f"{r['ours_mb']} MB" if r["ours_mb"] else "", "", v, why))
    return out


def paper_number(text):
    """A paper's figure as a number: '156.4', or 'about 3000 (3 GB)' read as 3000."""
    m = re.search(r"[-+]?\d+(?:\.\d+)?", text)
    return float(m.group(0)) if m else float("nan")


def memory_verdict(ours_mb, paper_mb):
    """(verdict, reason) of a memory claim under the one tolerance for memory."""
    ratio = ours_mb / paper_mb
    v = REPRODUCED if abs(ratio - 1) <= MEMORY_TOLERANCE else NOT_REPRODUCED
    return v, f"ours {ours_mb:g} MB = {ratio:.3f}x the paper's (tolerance {100 * MEMORY_TOLERANCE:.0f}%)"


def lrsm_table2_time(r):
    """Table 2's performance row: a frame time on the paper's GPUs."""
    paper = r["note"].split("; ours ")[0].replace("paper: ", "")
    ours = r["note"].split("; ours ", 1)[1] if "; ours " in r["note"] else ""
    return row(LRSM, "lrsm_table2.csv", f"Table 2 {r['paper_scene']}: frame time ({r['setting']})", paper,
               "" if ours.startswith("not measured") else ours, "", NOT_MEASURABLE,
               "absolute frame time on the paper's GPUs" + ("; ours: " + ours if ours else ""),
               kind=ABSOLUTE_TIME)


def lrsm_table3(results):
    """Table 3: the stage-order claims, and the absolute stage times (not measurable here)."""
    out = []
    for r in read(results, "lrsm_table3.csv"):
        if r["kind"] == "claim":
            v, why = verdict_of(r["reproduced"])
            out.append(row(LRSM, "lrsm_table3.csv", "Table 3: " + r["stage"], r["paper_gtx770_ms"] + " ms",
                           r["our_ms"] + " ms" if r["our_ms"] else "", r["our_renderer"], v,
                           why or "the order of the two stage times, compared on this renderer"))
        elif r["paper_gtx770_ms"] or r["paper_iris_pro_ms"]:
            out.append(row(LRSM, "lrsm_table3.csv", f"Table 3: {r['method']} {r['stage']} time",
                           f"{r['paper_gtx770_ms']} ms (GTX 770), {r['paper_iris_pro_ms']} ms (Iris Pro)",
                           r["our_ms"] + " ms" if r["our_ms"] else "", r["our_renderer"], NOT_MEASURABLE,
                           "absolute stage time on the paper's GPUs; ours on "
                           + (r["our_renderer"] or "no run") + " (the stage-order claims compare ratios)",
                           kind=ABSOLUTE_TIME))
    return out


def lrsm_fig7(results):
    """Figure 7: the thin-wall leak."""
    out = []
    for r in read(results, "lrsm_fig7.csv"):
        if r["kind"] != "claim":
            continue
        v, why = verdict_of(r["reproduced"])
        out.append(row(LRSM, "lrsm_fig7.csv", f"Figure 7: {r['claim']} ({r['params']} {r['size']})",
                       "LRSM leaks, VCT does not", r["evidence"].split(";")[0], r["renderer"], v,
                       (why + "; " if why else "") + r["evidence"]))
    return out


def lrsm_dynamic(results):
    """SPONZA DRAGON: interactive with every structure rebuilt."""
    out = []
    for r in read(results, "lrsm_dynamic.csv"):
        if r["kind"] != "claim":
            continue
        v, why = verdict_of(r["reproduced"])
        out.append(row(LRSM, "lrsm_dynamic.csv", "SPONZA DRAGON: " + r["claim"], "", r["note"],
                       r["renderer"], v, why or r["note"], kind=ABSOLUTE_TIME))
    return out


def lrsm(results):
    return lrsm_table2(results) + lrsm_table3(results) + lrsm_fig7(results) + lrsm_dynamic(results)


def ldm(results):
    return ldm_claims(results) + ldm_times(results)


def ldm_claims(results):
    """The LDM paper's machine-independent claims (ldm_claims.csv): accuracy, orders, shares,
    memory."""
    out = []
    for r in read(results, "ldm_claims.csv"):
        v, why = verdict_of(r["reproduced"])
        out.append(row(LDM, "ldm_claims.csv", f"Figure {r['figure']}: {r['claim']}", r["paper_value"],
                       r["our_value"], r["renderer"], v,
                       r["evidence"] if v != NOT_MEASURABLE else why + ("; " + r["evidence"] if r["evidence"] else ""),
                       kind=r.get("kind") or MACHINE_INDEPENDENT))
    return out


def ldm_times(results):
    """The LDM paper's absolute times (its figures' captions)."""
    out = []
    for r in read(results, "ldm_figures_vs_ours.csv"):
        what = f"Figure {r['figure']} {r['scene']} {r['method']} ({r['paper_settings']}): time"
        pv = f"{r['paper_ms']} ms on {r['paper_gpu']}" + (f", {r['paper_mb']} MB" if r["paper_mb"] else "")
        ov = (f"{r['our_ms']} ms, {r['our_mb']} MB, rel RMSE {r['our_rel_rmse']}" if r["our_ms"] else "")
        if not r["our_ms"]:
            why = r["our_settings"]
        else:
            why = (f"absolute time on the paper's {r['paper_gpu']}; ours on {r['our_renderer']}"
                   + ("; and not at the paper's settings (quick profile)" if "NOT" in r["our_settings"] else ""))
        out.append(row(LDM, "ldm_figures_vs_ours.csv", what, pv, ov, r["our_renderer"], NOT_MEASURABLE, why,
                       kind=ABSOLUTE_TIME))
    return out


ORDER = {REPRODUCED: 0, NOT_REPRODUCED: 1, NOT_MEASURABLE: 2}


# The order-of-cost claims: judged on a GPU where a valid device run answers them, else on
# llvmpipe's time, which the reason then says.
ORDER_CLAIMS = tuple("Table 3: " + text for text, _, _ in lrsm_tables.TABLE3_CLAIMS) + (
    "Figure 10: Sec. 5.2: the LDM (photon) tracing relatively cheap next to splatting",
    gpu_claims.GATHER_CLAIM)


# The claims whose verdict rests on an order or a ratio of times (with an error beside, for Fig. 9):
# they carry over between machines only as far as the renderer's pipeline resembles the paper's GPU,
# so they are a class of their own, judged on the renderer each row names.
TIME_ORDER_STEMS = ORDER_CLAIMS + ("photon tracing time roughly linear", "photon tracing about doubles",
                                   "Figure 9: fewer LDMs are faster",
                                   "Figure 9: lower-resolution LDMs are faster",
                                   "Figure 10: Sec. 5.2: splatting is the bottleneck")


def classed(rows):
    """The rows with kind time_order where their claim is an order of times."""
    return [dict(r, kind=TIME_ORDER) if r["kind"] == MACHINE_INDEPENDENT and
            r["claim"].startswith(TIME_ORDER_STEMS) else r for r in rows]


def on_gpu(r, g):
    """Claim row r with what the GPU measured laid over it (gpu_claims.judged's entry g)."""
    before = f"{r['renderer'] or 'llvmpipe'}: {r['verdict']}" + (f" ({r['our_value']})" if r["our_value"] else "")
    where = f"{g['renderer']}, device run {g['run']}" + (f"; raster limit: {g['limit']}" if g["limit"] else "")
    if "verdict" in g:
        v, _ = verdict_of(g["verdict"])
        return dict(r, verdict=v, our_value=g["our_value"], renderer=g["renderer"], cores="",
                    reason=f"judged on {where}: {g['evidence']}; before, {before}")
    return dict(r, our_value=g["our_value"], renderer=g["renderer"], cores="",
                reason=f"absolute time on the paper's GPU; ours on {where} (not comparable as a number: the "
                       f"order claims compare ratios); {before}")


def overlay_gpu(rows, gpu):
    out = []
    for r in rows:
        g = gpu.get(r["claim"])
        if g and (r["kind"] == ABSOLUTE_TIME or "verdict" in g):
            out.append(on_gpu(r, g))
        elif r["claim"].startswith(ORDER_CLAIMS) and r["verdict"] != NOT_MEASURABLE:
            out.append(dict(r, reason="judged on llvmpipe's time alone (a CPU rasterizer; no valid GPU row "
                                      "answers it): " + r["reason"]))
        else:
            out.append(r)
    return out


def stem(text):
    """A claim's words before its settings (the first ' (' or ' ['): the claim itself."""
    cut = [i for i in (text.find(" ("), text.find(" [")) if i > 0]
    return text[:min(cut)] if cut else text


def joined(values):
    """The distinct non-empty values in first-met order, '; '-joined."""
    return "; ".join(dict.fromkeys(v for v in values if v))


def counted_once(rows):
    """A claim tested at several settings (rows of one paper, source and kind whose claims share a
    stem) becomes one row: it holds (`reproduced`) where every setting measured holds, it does not
    (`not reproduced`) where one measured setting fails, and it is `not measurable here` where no
    setting was measured. Its value is how many settings held; its reason names each setting with
    its own verdict and reason (' || ' between settings), the evidence beneath the verdict."""
    groups = {}
    for r in rows:
        groups.setdefault((r["paper"], r["source"], r["kind"], stem(r["claim"])), []).append(r)
    out = []
    for (paper, source, kind, claim), g in groups.items():
        if len(g) == 1:
            out.append(g[0])
            continue
        measured = [r for r in g if r["verdict"] != NOT_MEASURABLE]
        held = sum(r["verdict"] == REPRODUCED for r in measured)
        verdict = (NOT_MEASURABLE if not measured else
                   REPRODUCED if held == len(measured) else NOT_REPRODUCED)
        value = (f"{len(g)} settings, none measurable here" if not measured else
                 f"holds at {held} of {len(measured)} settings measured" + (
                     f" ({len(g) - len(measured)} not measurable here)" if len(measured) < len(g) else ""))
        evidence = " || ".join(f"{r['claim'][len(claim):].strip()} {r['verdict']}"
                               + (f": {r['reason']}" if r["reason"] else "") for r in g)
        cores = {r["cores"] for r in g}
        out.append(row(paper, source, claim, joined(r["paper_value"] for r in g), value,
                       joined(r["renderer"] for r in g), verdict, f"{value}: {evidence}",
                       cores.pop() if len(cores) == 1 else "", kind))
    return out


def claims(results):
    """Per paper, the claims with a verdict first, then the ones not measurable here (stable), each
    claim once over its settings (counted_once); the time claims a valid device run answers carry
    the GPU's numbers (gpu_claims.py)."""
    out = []
    gpu = gpu_claims.judged(results)
    for part in (thesis(results) + temporal_tables.thesis_claim(results),
                 lrsm(results) + temporal_tables.lrsm_claim(results), ldm(results)):
        out += sorted(classed(counted_once(overlay_gpu(part, gpu))), key=lambda r: ORDER[r["verdict"]])
    return out


def cores_by_renderer(results):
    """{renderer: cores} for the renderers the history recorded with one core count only."""
    path = os.path.join(results, "history.sqlite")
    if not os.path.exists(path):
        return {}
    try:
        db = sqlite3.connect(f"file:{path}?mode=ro", uri=True, timeout=10)
        found = db.execute("SELECT renderer, group_concat(DISTINCT cores) FROM machine GROUP BY renderer").fetchall()
        db.close()
    except sqlite3.Error as e:
        print(f"claims.py: {path}: {e}: cores left empty", file=sys.stderr)
        return {}
    return {r: c for r, c in found if c and "," not in str(c)}


def write(results):
    rows = claims(results)
    cores = cores_by_renderer(results)
    for r in rows:
        if not r["cores"] and r["renderer"] in cores:
            r["cores"] = str(cores[r["renderer"]])
    return write_csv(os.path.join(results, "claims.csv"), rows, COLUMNS), rows


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: python3 -m reporting.claims RESULTS_DIR")
    path, rows = write(sys.argv[1])
    counts = {}
    for r in rows:
        counts[r["verdict"]] = counts.get(r["verdict"], 0) + 1
    print(f"{path}: {len(rows)} claims (" + ", ".join(f"{n} {k}" for k, n in sorted(counts.items())) + ")")


if __name__ == "__main__":
    main()
