#!/usr/bin/env python3
"""harness/reporting/energy_audit.py on constructed tables with known cells: a matrix's paper-profile rows are
read where it has any (its quick rows then left out), the quick rows where it has none (and the cell
says so); the least and most mean ratio and RMSE over black over a cell's rows; a cell outside
0.85-1.15 flagged, beside its cause where harness/energy_causes.csv has one and counted unexplained
where not, a cause written for every scene reaching the scenes without their own; presets are cells
of their own; rows that are not ok, or scored against a black reference, are left out. No GL."""
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "harness"))
sys.path.insert(0, os.path.join(HERE, "..", "common"))
from reporting import energy_audit  # noqa: E402
from script_checks import check, verdict  # noqa: E402


def row(tech, scene, comp, ratio, over, profile="paper", params="", status="ok"):
    return {"technique": tech, "scene": scene, "component": comp, "mean_ratio": str(ratio),
            "rmse_over_black": str(over), "profile": profile, "params": params, "status": status}


mats = {
    "figure": [row("lrsm", "sibenik", "indirect", 0.97, 0.3),
               row("lrsm", "sibenik", "indirect", 0.90, 0.35),
               row("lrsm", "sibenik", "indirect", 0.04, 0.96, params="voxel_res=256;preset=paper"),
               row("lrsm", "sibenik", "indirect", 0.2, 2.0, profile="quick"),
               row("vct", "sibenik", "glossy", 1.7, 1.2),
               row("vct", "sibenik", "glossy", float("nan"), 0.5, status="nonfinite"),
               dict(row("lrsm", "thin_wall_leak", "indirect", 1.0, 0.0), black_rmse="0")],
    "sweep": [row("rsm_gather", "ring", "indirect", 2.15, 1.1, profile="quick")],
}
energy_audit.causes = lambda: {
    ("vct", "default", "sibenik", "glossy"): {"verdict": "explained", "cause": "the specular cone's footprint",
                                              "control": "aperture 5: 1.1"},
    ("rsm_gather", "default", "*", "indirect"): {"verdict": "partly", "cause": "no VPL visibility",
                                                 "control": ""}}
cells = {(c["technique"], c["preset"], c["scene"], c["component"]): c for c in energy_audit.cells(mats)}

c = cells.get(("lrsm", "default", "sibenik", "indirect"))
check(c is not None and c["profile"] == "paper" and c["rows"] == 2,
      f"lrsm's default cell reads the two paper rows, not the quick one ({c})")
check(c is not None and (c["mean_ratio_min"], c["mean_ratio_max"]) == ("0.9", "0.97")
      and not c["outside_band"], "its span 0.9-0.97, inside the band")
p = cells.get(("lrsm", "paper", "sibenik", "indirect"))
check(p is not None and p["outside_band"] and p["cause"] == "",
      "the paper preset is a cell of its own, outside the band, unexplained")
v = cells.get(("vct", "default", "sibenik", "glossy"))
check(v is not None and v["rows"] == 1 and v["worse_than_black"] == 1 and v["outside_band"]
      and v["cause"] == "the specular cone's footprint", "vct glossy: the nonfinite row left out, "
      "worse than black counted, its cause joined")
q = cells.get(("rsm_gather", "default", "ring", "indirect"))
check(not any(k[2] == "thin_wall_leak" for k in cells), "a row against a black reference is no cell")
check(q is not None and q["profile"] == "quick", "a matrix without paper rows is read from its quick "
      "rows, and says so")
check(q is not None and q["verdict"] == "partly" and q["cause"] == "no VPL visibility",
      "a cause written for every scene ('*') reaches a scene without its own")
check(p is not None and p["verdict"] == "open", "a cell outside the band without a cause is open")
text = energy_audit.counts_text(list(cells.values()))
check("4 cells, 3 outside" in text and "1 explained" in text and "1 partly, 1 open" in text
      and "1 read from quick" in text,
      f"counts: {text}")
md = "\n".join(energy_audit.section_md(list(cells.values())))
check("unexplained" in md and "explained: the specular" in md and "(outside)" in md
      and "## Energy audit" in md,
      "the Markdown section flags the cells outside the band and the unexplained ones")

sys.exit(verdict())
