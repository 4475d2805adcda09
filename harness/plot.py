#!/usr/bin/env python3
"""gibench plots: speed against error, one plot per (matrix, scene, component), drawn with gnuplot
from the result CSVs (DESIGN.md, "Matrices, CSV and reproduction").

Each point is one run (technique + parameters) at its median GPU frame time and relative RMSE
against the reference; the line joins the Pareto front (runs no other run beats in both). Writes
PNG and SVG. Uses only the standard library and gnuplot (Debian's gnuplot-nox).

usage: plot.py RESULTS_DIR [--out PLOTS_DIR]
"""
import argparse
import csv
import os
import shutil
import subprocess
import sys


def pareto(points):
    """Points (x, y, ...) not dominated in both x and y, sorted by x."""
    front, best = [], float("inf")
    for p in sorted(points, key=lambda p: (p[0], p[1])):
        if p[1] < best:
            front.append(p)
            best = p[1]
    return front


def gp_quote(s):
    return '"' + s.replace("\\", "\\\\").replace('"', '\\"') + '"'


def plot_group(key, rows, out_dir, renderer):
    matrix, scene, component = key
    base = os.path.join(out_dir, f"{matrix}_{scene}_{component}")
    by_tech = {}
    for r in rows:
        by_tech.setdefault(r["technique"], []).append(
            (float(r["gpu_ms_median"]), float(r["rel_rmse"]), r["params"], r["width"] + "x" + r["height"]))
    data_path = base + ".dat"
    with open(data_path, "w") as f:
        blocks = []
        for tech, pts in sorted(by_tech.items()):
            f.write(f"# {tech}\n")
            for p in pts:
                f.write(f"{p[0]:.6g} {p[1]:.6g} \"{p[2]} {p[3]}\"\n")
            f.write("\n\n")
            blocks.append(tech)
        f.write("# pareto front\n")
        for p in pareto([p for pts in by_tech.values() for p in pts]):
            f.write(f"{p[0]:.6g} {p[1]:.6g}\n")
    plots = [f"{gp_quote(data_path)} index {i} using 1:2 with points pt 7 ps 1.2 title {gp_quote(t)}"
             for i, t in enumerate(blocks)]
    plots.append(f"{gp_quote(data_path)} index {len(blocks)} using 1:2 with lines lw 1.5 dt 2 lc rgb 'gray40' "
                 "title 'Pareto front'")
    title = f"{matrix}: {scene}, component {component} ({renderer})"
    script = []
    for term, ext in (("pngcairo size 900,600 font 'sans,10'", "png"), ("svg size 900,600", "svg")):
        script += [f"set terminal {term}", f"set output {gp_quote(base + '.' + ext)}",
                   f"set title {gp_quote(title)} noenhanced",
                   "set xlabel 'GPU time per frame, median (ms)'",
                   "set ylabel 'relative RMSE against the reference'",
                   "set logscale x", "set grid", "set key outside right top noenhanced",
                   "plot " + ", ".join(plots), "unset output"]
    subprocess.run(["gnuplot"], input="\n".join(script) + "\n", text=True, check=True)
    os.remove(data_path)
    return base + ".png"


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("results")
    ap.add_argument("--out", default=None)
    a = ap.parse_args()
    out = a.out or os.path.join(a.results, "plots")
    if not shutil.which("gnuplot"):
        sys.exit("plot.py: gnuplot not found: run `make deps` (Debian package gnuplot-nox)")
    os.makedirs(out, exist_ok=True)
    groups, renderers = {}, {}
    for name in sorted(os.listdir(a.results)):
        if not name.endswith(".csv") or name.endswith("_passes.csv"):
            continue
        with open(os.path.join(a.results, name), newline="") as f:
            for r in csv.DictReader(f):
                if r.get("status") != "ok":
                    continue
                key = (r["matrix"], r["scene"], r["component"])
                groups.setdefault(key, []).append(r)
                renderers[key] = r["renderer"]
    if not groups:
        print(f"plot.py: no ok rows in {a.results}/*.csv; nothing to plot")
        return
    for key, rows in sorted(groups.items()):
        print("plot.py: wrote", plot_group(key, rows, out, renderers[key]))


if __name__ == "__main__":
    main()
