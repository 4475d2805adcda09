#!/usr/bin/env python3
"""Gathers every claim of every paper that gibench sets beside its own numbers into one table,
RESULTS_DIR/claims.csv: a row per claim with the paper's value, ours, the machine ours ran on, its
kind and a verdict `reproduced` / `not reproduced` / `not measurable here`, with the reason. A
claim tested at several settings is one row (counted_once), its settings the evidence beneath it.

usage: python3 -m reporting.claims RESULTS_DIR [--runs DIR]

Each paper's module returns its claims as claim.Claim objects, judged from the result rows in
memory: thesis_tables.claims, lrsm_tables.claims, ldm_tables.claims (with ldm_claims.py's rules)
and temporal_tables.claims; this file gathers them and writes claims.csv once. The claims read the
runs and the papers' values (DIR/paper/, which paper_tables.py copies there) of RESULTS_DIR, or of
--runs DIR where given (claims.csv, and the cores, stay RESULTS_DIR's); a paper without its values
gives no claims. The kinds, verdicts and the tolerance of each kind of claim are claim.py's, stated
once there. What this file adds:
- the time claims a valid device run answers carry the GPU's numbers (gpu_claims.py): an order the
  GPU judged takes its verdict, llvmpipe's moving into the reason; an absolute time shows the GPU's
  number, still not measurable here;
- a claim tested at several settings counts once (counted_once).
The result CSVs do not record the CPU's cores; `cores` comes from RESULTS_DIR/history.sqlite (the
machines `gibench run` recorded) where exactly one core count was recorded with the row's renderer,
and stays empty otherwise (a renderer string alone does not name a machine).
"""
import argparse
import dataclasses
import os
import sqlite3
import sys

from reporting import gpu_claims  # noqa: E402  (the time claims a valid device run answers)
from reporting import ldm_tables  # noqa: E402
from reporting import lrsm_tables  # noqa: E402
from reporting import temporal_tables  # noqa: E402  (the papers' temporal claims, from the sequence tables)
from reporting import thesis_tables  # noqa: E402
from reporting.claim import (ABSOLUTE_TIME, COLUMNS, KINDS, LDM, LRSM, MACHINE_INDEPENDENT,  # noqa: E402,F401
                             NOT_MEASURABLE, NOT_REPRODUCED, REPRODUCED, THESIS, TIME_ORDER, VERDICTS, Claim,
                             memory_verdict, paper_number)
from reporting.schema import write_csv  # noqa: E402


def papers(results):
    """[(paper, its Claims)] in the order claims.csv gives them: the thesis, LRSM, LDM."""
    temporal = temporal_tables.claims(results)
    paper_dir = os.path.join(results, "paper")
    return [(THESIS, thesis_tables.claims(results, paper_dir) + [c for c in temporal if c.paper == THESIS]),
            (LRSM, lrsm_tables.claims(results, paper_dir) + [c for c in temporal if c.paper == LRSM]),
            (LDM, ldm_tables.claims(results, paper_dir))]


ORDER = {REPRODUCED: 0, NOT_REPRODUCED: 1, NOT_MEASURABLE: 2}


# The order-of-cost claims: judged on a GPU where a valid device run answers them, else on
# llvmpipe's time, which the reason then says.
ORDER_CLAIMS = tuple("Table 3: " + text for text, _, _ in lrsm_tables.TABLE3_CLAIMS) + (
    "Figure 10: Sec. 5.2: the LDM (photon) tracing relatively cheap next to splatting",
    gpu_claims.GATHER_CLAIM)


def on_gpu(c, g):
    """Claim c with what the GPU measured laid over it (gpu_claims.judged's entry g)."""
    before = f"{c.renderer or 'llvmpipe'}: {c.verdict}" + (f" ({c.our_value})" if c.our_value else "")
    where = f"{g['renderer']}, device run {g['run']}" + (f"; raster limit: {g['limit']}" if g["limit"] else "")
    if "verdict" in g:
        return dataclasses.replace(c, verdict=g["verdict"] or NOT_MEASURABLE, our_value=g["our_value"],
                                   renderer=g["renderer"], cores="",
                                   reason=f"judged on {where}: {g['evidence']}; before, {before}")
    return dataclasses.replace(c, our_value=g["our_value"], renderer=g["renderer"], cores="",
                               reason=f"absolute time on the paper's GPU; ours on {where} (not comparable as a "
                                      f"number: the order claims compare ratios); {before}")


def overlay_gpu(claims, gpu):
    out = []
    for c in claims:
        g = gpu.get(c.claim)
        if g and (c.kind == ABSOLUTE_TIME or "verdict" in g):
            out.append(on_gpu(c, g))
        elif c.claim.startswith(ORDER_CLAIMS) and c.verdict != NOT_MEASURABLE:
            out.append(dataclasses.replace(c, reason="judged on llvmpipe's time alone (a CPU rasterizer; no "
                                                     "valid GPU row answers it): " + c.reason))
        else:
            out.append(c)
    return out


def stem(text):
    """A claim's words before its settings (the first ' (' or ' ['): the claim itself."""
    cut = [i for i in (text.find(" ("), text.find(" [")) if i > 0]
    return text[:min(cut)] if cut else text


def joined(values):
    """The distinct non-empty values in first-met order, '; '-joined."""
    return "; ".join(dict.fromkeys(v for v in values if v))


def counted_once(claims):
    """A claim tested at several settings (Claims of one paper, source and kind whose texts share a
    stem) becomes one Claim, the Claims at its settings beneath it (`settings`): it holds
    (`reproduced`) where every setting measured holds, it does not (`not reproduced`) where one
    measured setting fails, and it is `not measurable here` where no setting was measured. Its value
    is how many settings held; its reason names each setting with its own verdict and reason (' || '
    between settings), the evidence beneath the verdict."""
    groups = {}
    for c in claims:
        groups.setdefault((c.paper, c.source, c.kind, stem(c.claim)), []).append(c)
    out = []
    for (paper, source, kind, claim), g in groups.items():
        if len(g) == 1:
            out.append(g[0])
            continue
        measured = [c for c in g if c.verdict != NOT_MEASURABLE]
        held = sum(c.verdict == REPRODUCED for c in measured)
        verdict = (NOT_MEASURABLE if not measured else
                   REPRODUCED if held == len(measured) else NOT_REPRODUCED)
        value = (f"{len(g)} settings, none measurable here" if not measured else
                 f"holds at {held} of {len(measured)} settings measured" + (
                     f" ({len(g) - len(measured)} not measurable here)" if len(measured) < len(g) else ""))
        evidence = " || ".join(f"{c.claim[len(claim):].strip()} {c.verdict}"
                               + (f": {c.reason}" if c.reason else "") for c in g)
        cores = {c.cores for c in g}
        out.append(Claim(paper, source, claim, kind, joined(c.paper_value for c in g), value,
                         joined(c.renderer for c in g), cores.pop() if len(cores) == 1 else "", verdict,
                         f"{value}: {evidence}", settings=g))
    return out


def claims(results, runs=None):
    """Per paper, the Claims with a verdict first, then the ones not measurable here (stable), each
    claim once over its settings (counted_once); the time claims a valid device run answers carry
    the GPU's numbers (gpu_claims.py). runs: the folder the claims are judged on (default results)."""
    runs = runs or results
    out = []
    gpu = gpu_claims.judged(runs)
    for _, part in papers(runs):
        out += sorted(counted_once(overlay_gpu(part, gpu)), key=lambda c: ORDER[c.verdict])
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


def write(results, runs=None):
    """Writes RESULTS/claims.csv from the Claims, a row each, the cores filled in; returns (its path,
    the Claims)."""
    found = claims(results, runs)
    cores = cores_by_renderer(results)
    for c in found:
        if not c.cores and c.renderer in cores:
            c.cores = str(cores[c.renderer])
    return write_csv(os.path.join(results, "claims.csv"), [c.row() for c in found], COLUMNS), found


def main():
    ap = argparse.ArgumentParser(description="writes RESULTS_DIR/claims.csv")
    ap.add_argument("results")
    ap.add_argument("--runs", help="judge the claims on this folder's runs and paper values (default RESULTS_DIR)")
    a = ap.parse_args()
    path, found = write(a.results, a.runs)
    counts = {}
    for c in found:
        counts[c.verdict] = counts.get(c.verdict, 0) + 1
    print(f"{path}: {len(found)} claims (" + ", ".join(f"{n} {k}" for k, n in sorted(counts.items())) + ")")


if __name__ == "__main__":
    main()
