#!/usr/bin/env python3
"""Sets the papers' own numbers (../shared/paper-values/*.csv, copied into results/paper/) beside
ours: for every row of a paper table that gibench reproduces, the run of ours that matches its
settings best, with our time, memory and error, and the renderer it ran on.

usage: paper_tables.py RESULTS_DIR [--paper-values DIR]

Writes RESULTS_DIR/<table>_vs_ours.csv. "Best match" is the run with the paper's settings when the
profile ran them (profile `paper`), else the run closest to them (the same scene and technique, the
most directions and resolution that ran): the `our_settings` column says which, so a reader never
takes a quick-profile number for the paper's configuration.
"""
import argparse
import csv
import os
import shutil
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from plot import parse_params  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)


params = parse_params


def load(results, matrix):
    path = os.path.join(results, matrix + ".csv")
    if not os.path.exists(path):
        return []
    with open(path, newline="") as f:
        return [r for r in csv.DictReader(f) if r["status"] == "ok"]


def pass_ms(results, matrix, row, names):
    path = os.path.join(results, matrix + "_passes.csv")
    if not os.path.exists(path):
        return ""
    total = 0.0
    found = False
    with open(path, newline="") as f:
        for p in csv.DictReader(f):
            if (p["scene"], p["technique"], p["params"], p["width"], p["height"], p["profile"]) == \
               (row["scene"], row["technique"], row["params"], row["width"], row["height"], row["profile"]) \
               and p["pass"] in names:
                total += float(p["ms_median"])
                found = True
    return f"{total:.6g}" if found else ""


def closeness(row, want):
    """Sort key: exact parameter matches first, then larger settings (closer to the paper's)."""
    p = params(row["params"])
    exact = sum(1 for k, v in want.items() if k in p and p[k] == v)
    size = int(row["width"]) * int(row["height"])
    return (exact, p.get("directions", 0), p.get("ldm_res", 0), size)


def ldm_rows(results, paper_csv):
    scene_of = {"Crytek Sponza": "sponza", "Hairball": "hairball"}
    out = []
    with open(paper_csv, newline="") as f:
        for pr in csv.DictReader(f):
            fig, scene = pr["figure"], scene_of.get(pr["scene"], pr["scene"])
            matrix = f"ldm_fig{fig}"
            tech = {"LDM": "ldm_ao", "HBAO": "hbao"}.get(pr["method"], "ldm_indirect")
            want = {}
            if pr["ldm_count"]:
                want["directions"] = float(pr["ldm_count"])
            if pr["ldm_res"]:
                want["ldm_res"] = float(pr["ldm_res"])
            if pr["dmax_m"]:
                want["dmax"] = float(pr["dmax_m"])  # Sponza is in cm: the paper's "1280 m" is 1280 units
            elif tech == "ldm_ao":
                want["dmax"] = float("inf")
            rows = [r for r in load(results, matrix) if r["scene"] == scene and r["technique"] == tech]
            if "dmax" in want:
                rows = [r for r in rows if params(r["params"]).get("dmax") == want["dmax"]] or rows
            best = max(rows, key=lambda r: closeness(r, want)) if rows else None
            rec = {"figure": fig, "scene": pr["scene"], "method": pr["method"], "paper_settings":
                   f"N={pr['ldm_count'] or '-'} ldm_res={pr['ldm_res'] or '-'} image={pr['image_res']}"
                   + (f" dmax={pr['dmax_m'] or 'inf'}" if pr["effect"].startswith("ao") else ""),
                   "paper_ms": pr["ms"], "paper_mb": pr["mb"], "paper_gpu": pr["gpu"], "paper_note": pr["note"]}
            if best:
                exact = all(params(best["params"]).get(k) == v for k, v in want.items()) and \
                    best["width"] == pr["image_res"]
                rec.update({
                    "our_settings": f"{best['params']} {best['width']}x{best['height']} profile={best['profile']}"
                                    + ("" if exact else " (NOT the paper's settings: see profile)"),
                    "our_ms": best["gpu_ms_median"],
                    "our_photon_trace_ms": pass_ms(results, matrix, best, {"photon_trace"}) if tech == "ldm_indirect" else "",
                    "our_mb": f"{float(best['mem_bytes']) / 1e6:.4g}",
                    "our_rmse": best["rmse"], "our_rel_rmse": best["rel_rmse"], "our_ssim": best["ssim"],
                    "our_ref_spp": best["ref_spp"], "our_renderer": best["renderer"]})
            else:
                rec["our_settings"] = "not run (scene data absent or matrix not run)"
            out.append(rec)
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("results")
    ap.add_argument("--paper-values", default=os.environ.get("GIBENCH_PAPER_VALUES",
                                                             os.path.join(ROOT, "..", "shared", "paper-values")))
    a = ap.parse_args()
    paper_dir = os.path.join(a.results, "paper")
    os.makedirs(paper_dir, exist_ok=True)
    # Keep a copy of the papers' numbers with the results, so the comparison reads on its own.
    if os.path.isdir(a.paper_values):
        for name in os.listdir(a.paper_values):
            if name.endswith(".csv"):
                shutil.copy(os.path.join(a.paper_values, name), os.path.join(paper_dir, name))
    ldm = os.path.join(paper_dir, "ldm_figures.csv")
    if not os.path.exists(ldm):
        print(f"paper_tables.py: no {ldm} (paper values not found under {a.paper_values}); nothing to compare")
        return
    rows = ldm_rows(a.results, ldm)
    cols = ["figure", "scene", "method", "paper_settings", "paper_ms", "paper_mb", "paper_gpu", "paper_note",
            "our_settings", "our_ms", "our_photon_trace_ms", "our_mb", "our_rmse", "our_rel_rmse", "our_ssim",
            "our_ref_spp", "our_renderer"]
    out = os.path.join(a.results, "ldm_figures_vs_ours.csv")
    with open(out, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=cols)
        w.writeheader()
        for r in rows:
            w.writerow({c: r.get(c, "") for c in cols})
    print("paper_tables.py: wrote", out)


if __name__ == "__main__":
    sys.exit(main())
