#!/usr/bin/env python3
"""gibench plots, drawn with gnuplot from the result CSVs (ARCHITECTURE.md, "Matrices, CSV and reproduction"):

- speed against error, one plot per (matrix, scene, component): each point is one run (technique +
  parameters) at its median GPU frame time (bar: its interquartile range) and relative RMSE with the
  reference's noise taken out (bar: its 95% interval; overlapping bars are a tie); the line joins
  the Pareto front (answers.py's, as the report's tables: no run beats it on both, ties called
  within the error intervals and the time resolution, runs worse than black left out); a dotted line marks what an all-black image
  scores, and a red ring every run worse than it (harness/reporting/uncertainty.py);
- sweeps: for every parameter a matrix varies over three or more values, GPU time and relative RMSE
  against that parameter, one line per technique and setting of the other parameters (scaling curves:
  time against LDM count, resolution, dmax...). An unbounded value (inf) is drawn at the right end;
- error against memory (the ledger's peak bytes), per (matrix, scene, component) whose runs differ
  in memory (structure resolutions, layers: the LRSM paper's Table 2 and the sweeps);
- across matrices: where runs of different matrices estimate the same component of the same scene
  at the same size on the same renderer (ldm_indirect, lrsm, vct and the thesis' rsm_gather and
  multires_ir on `indirect`: thesis_indirect.matrix runs them on lrsm_sweeps' scenes and sizes and on
  the thesis' scenes), speed and memory against error of them all in one plot
  (cross_<scene>_<component>_<size>);
- the reference path tracer's throughput against Embree on the same rays, by scene, beside the
  lean tracer's (results/bench_reference.csv, `gibench bench reference`).
Error is the relative RMSE, or the RMSE where the reference's mean is 0 (a view that should be black,
thin_wall_leak's); rows without a finite error or time are left out of the plots (not the CSV).
Writes PNG and SVG. Uses only the standard library and gnuplot (Debian's gnuplot-nox).

usage: python3 -m reporting.plot RESULTS_DIR [--out PLOTS_DIR]
"""
import argparse
import os
import shutil
import subprocess
import sys

from reporting.schema import fnum as finite_num, matrices, params, read_csv  # noqa: E402
from reporting.uncertainty import error_interval, time_interval, time_resolution, worse_than_black  # noqa: E402
from reporting import answers  # noqa: E402
from reporting import external  # noqa: E402


def technique_label(r):
    """A point set's name: the technique, an external renderer's with its program and version
    (external.py)."""
    return external.label(r)


def axis_note(rows, what="times"):
    """What an axis adds where external renderers' rows are plotted: their figures are the programs'
    own (timings.json), not gibench's; '' without any."""
    return f"; ext: {what} {external.TIMES}" if any(external.is_external(r) for r in rows) else ""


def param_text(k, v):
    return f"{k}={v:g}" if isinstance(v, float) else f"{k}={v}"


def gp_quote(s):
    return '"' + s.replace("\\", "\\\\").replace('"', '\\"') + '"'


def error_metric(rows):
    """Relative RMSE, or RMSE where no row has a finite one: a reference whose mean is 0 (a view
    that should be black, as thin_wall_leak's) makes every relative error infinite."""
    if any(finite_num(r["rel_rmse"]) is not None for r in rows):
        return "rel_rmse", "relative RMSE against the reference"
    return "rmse", "RMSE against the reference (its mean is 0: relative error undefined)"


def black_level(r, metric):
    """What an all-black image scores against the row's reference, in the plot's metric."""
    black, rmse, rel = (finite_num(r.get(k)) for k in ("black_rmse", "rmse", "rel_rmse"))
    if black is None:
        return None
    if metric == "rmse":
        return black
    return black * rel / rmse if rel and rmse else None


X_AXES = {"time": ("gpu_ms_median", 1.0, "GPU time per frame, median (ms)"),
          "memory": ("mem_bytes", 1e-6, "technique memory, peak (MB, ledger)")}


def plot_group(key, rows, out_dir, renderer, x="time", name=None, label_matrix=False):
    """Speed (x = "time") or memory (x = "memory") against error, one point per run."""
    matrix, scene, component = key
    col, scale, xlabel = X_AXES[x]
    metric, ylabel = error_metric(rows)
    base = os.path.join(out_dir, name or f"{matrix}_{scene}_{component}" + ("" if x == "time" else "_memory"))
    # Label each point with the parameters that vary among its technique's runs here (all of a
    # technique's parameters make labels that cover the plot).
    varying = {}
    for r in rows:
        for k, v in params(r).items():
            varying.setdefault((r["technique"], k), set()).add(v)
    by_tech, worse, blacks = {}, [], []
    for r in rows:
        short = ";".join(param_text(k, v) for k, v in params(r).items()
                         if len(varying[(r["technique"], k)]) > 1 and not (k == "version" and external.is_external(r)))
        xv, iv = finite_num(r.get(col)), error_interval(r, relative=metric == "rel_rmse")
        if xv is None or iv is None or xv <= 0:
            continue  # unplottable (no memory figure, an infinite error): the CSV keeps the row
        spread = (finite_num(r.get("gpu_ms_iqr")) or 0.0) if x == "time" else 0.0
        tech = technique_label(r) + (f" ({r['matrix']})" if label_matrix else "")
        point = (xv * scale, iv[1], short,
                 r["width"] + "x" + r["height"] + (f" t={r['time']}" if r.get("time", "0") != "0" else ""),
                 max(xv - spread / 2, xv * 0.5) * scale, (xv + spread / 2) * scale, iv[0], iv[2])
        by_tech.setdefault(tech, []).append(point)
        if worse_than_black(r):
            worse.append(point)
        black = black_level(r, metric)
        if black is not None:
            blacks.append(black)
    if not by_tech or all(p[1] == 0 for pts in by_tech.values() for p in pts):
        return None  # nothing to compare: every run exact (a component the scene lacks: black)
    data_path = base + ".dat"
    with open(data_path, "w") as f:
        blocks = []
        for tech, pts in sorted(by_tech.items()):
            f.write(f"# {tech}\n")
            for p in pts:
                f.write(f"{p[0]:.6g} {p[1]:.6g} \"{p[2]} {p[3]}\" {p[4]:.6g} {p[5]:.6g} {p[6]:.6g} {p[7]:.6g}\n")
            f.write("\n\n")
            blocks.append(tech)
        f.write("# pareto front (answers.py's: ties called, rows worse than black left out)\n")
        cost = answers.time_cost if x == "time" else answers.memory_cost
        front = answers.answer(rows, cost)["front"]
        for c in front:  # at the plot's own error (answers ranks by the RMSE: the same order)
            f.write(f"{finite_num(c[0][col]) * scale:.6g} "
                    f"{error_interval(c[0], relative=metric == 'rel_rmse')[1]:.6g}\n")
        if not front:
            f.write("NaN NaN\n")  # keeps the block, so the next one's index holds
        f.write("\n\n# worse than a black image\n")
        for p in worse or [(float("nan"), float("nan"))]:
            f.write(f"{p[0]:.6g} {p[1]:.6g}\n")
    # Each run with its spread: the time's interquartile range, the error's 95% interval with the
    # reference's noise accounted for (bars that overlap are a tie, not a rank).
    plots = [f"{gp_quote(data_path)} index {i} using 1:2:4:5:6:7 with xyerrorbars pt 7 ps 1.1 "
             f"title {gp_quote(t)}" for i, t in enumerate(blocks)]
    # Each point labelled with its parameters, small, so the plot can be read without the CSV.
    plots += [f"{gp_quote(data_path)} index {i} using 1:2:3 with labels font ',6' offset char 0.6,0.6 "
              "left noenhanced notitle" for i in range(len(blocks))]
    plots.append(f"{gp_quote(data_path)} index {len(blocks)} using 1:2 with lines lw 1.5 dt 2 lc rgb 'gray40' "
                 "title 'Pareto front'")
    if worse:
        plots.append(f"{gp_quote(data_path)} index {len(blocks) + 1} using 1:2 with points pt 6 ps 2.6 lw 2 "
                     "lc rgb 'red' title 'worse than a black image'")
    if blacks:
        level = sorted(blacks)[len(blacks) // 2]
        plots.append(f"{level:.6g} with lines lw 2 dt 3 lc rgb 'black' title 'a black image scores'")
    title = f"{matrix}: {scene}, component {component} ({renderer})"
    script = []
    for term, ext in (("pngcairo size 900,600 font 'sans,10'", "png"), ("svg size 900,600", "svg")):
        script += [f"set terminal {term}", f"set output {gp_quote(base + '.' + ext)}",
                   f"set title {gp_quote(title)} noenhanced",
                   f"set xlabel {gp_quote(xlabel + axis_note(rows, 'times' if x == 'time' else 'memory'))}",
                   f"set ylabel {gp_quote(ylabel + ', reference noise removed (bars: 95% interval)')}",
                   "set logscale x", "set grid", "set key outside right top noenhanced",
                   "plot " + ", ".join(plots), "unset output"]
    subprocess.run(["gnuplot"], input="\n".join(script) + "\n", text=True, check=True)
    os.remove(data_path)
    return base + ".png"


def cross_groups(groups):
    """Runs of different matrices that estimate the same component of the same scene at the same
    image size on the same renderer (e.g. ldm_indirect, lrsm, vct, rsm_gather and multires_ir on
    `indirect`): one plot of them all, when they hold at least two techniques from at least two
    matrices."""
    merged = {}
    for (matrix, scene, component), rows in groups.items():
        for r in rows:
            merged.setdefault((scene, component, r["width"] + "x" + r["height"], external.group_renderer(r)),
                              []).append(r)
    out = {}
    for k, rows in merged.items():
        if len({r["technique"] for r in rows}) >= 2 and len({r["matrix"] for r in rows}) >= 2:
            out[k] = rows
    return out


def sweep_plots(key, rows, out_dir, renderer):
    """One sweep plot per parameter with >= 3 distinct values within a technique."""
    matrix, scene, component = key
    metric, _ = error_metric(rows)
    written = []
    values = {}
    for r in rows:
        for k, v in params(r).items():
            values.setdefault((r["technique"], k), set()).add(v)
    names = sorted({k for (t, k), vals in values.items()
                    if len(vals) >= 3 and all(isinstance(v, float) for v in vals)})  # a number to sweep
    for name in names:
        series = {}
        for r in rows:
            p = params(r)
            if name not in p:
                continue
            others = ", ".join(param_text(k, v) for k, v in sorted(p.items()) if k != name
                               and len(values[(r["technique"], k)]) > 1)
            label = technique_label(r) + (f" ({others})" if others else "") + f" {r['width']}x{r['height']}"
            err, ms = finite_num(r[metric]), finite_num(r["gpu_ms_median"])
            if err is None or ms is None or err <= 0 or ms <= 0:
                continue  # both axes are logarithmic (a black reference and image give error 0)
            series.setdefault(label, []).append((p[name], float(r["gpu_ms_median"]), err))
        finite = [x for pts in series.values() for x, _, _ in pts if x != float("inf")]
        if not finite:
            continue
        inf_at = max(finite) * 4 if max(finite) > 0 else 1
        base = os.path.join(out_dir, f"{matrix}_{scene}_{component}_sweep_{name}")
        data_path = base + ".dat"
        labels = []
        with open(data_path, "w") as f:
            for label, pts in sorted(series.items()):
                for x, ms, err in sorted(pts):
                    f.write(f"{inf_at if x == float('inf') else x:.6g} {ms:.6g} {err:.6g}\n")
                f.write("\n\n")
                labels.append(label)
        logx = min(finite) > 0 and max(finite) / max(min(finite), 1e-30) >= 10
        has_inf = any(x == float("inf") for pts in series.values() for x, _, _ in pts)
        script = []
        for term, ext in (("pngcairo size 900,800 font 'sans,10'", "png"), ("svg size 900,800", "svg")):
            script += [f"set terminal {term}", f"set output {gp_quote(base + '.' + ext)}",
                       "set multiplot layout 2,1 title " + gp_quote(f"{matrix}: {scene}, {component}, sweep of {name} ({renderer})") + " noenhanced",
                       "set grid", "set key outside right top noenhanced",
                       "set logscale x" if logx else "unset logscale x",
                       (f"set xtics add ('inf' {inf_at:.6g})" if has_inf else "set xtics autofreq"),
                       f"set xlabel {gp_quote(name)} noenhanced", "set ylabel 'GPU ms per frame (median)'", "set logscale y",
                       "plot " + ", ".join(f"{gp_quote(data_path)} index {i} using 1:2 with linespoints pt 7 title {gp_quote(l)}"
                                           for i, l in enumerate(labels)),
                       "set logscale y", f"set ylabel '{metric} (log)'",
                       "plot " + ", ".join(f"{gp_quote(data_path)} index {i} using 1:3 with linespoints pt 7 title {gp_quote(l)}"
                                           for i, l in enumerate(labels)),
                       "unset multiplot", "unset output", "unset xtics", "set xtics autofreq"]
        subprocess.run(["gnuplot"], input="\n".join(script) + "\n", text=True, check=True)
        os.remove(data_path)
        written.append(base + ".png")
    return written


def bench_plot(results, out_dir):
    """The reference path tracer's throughput against Embree on the same rays, by scene, beside
    the lean tracer's (the same kind of paths, little else done; absent from older files):
    paired medians with their least and greatest over the repeats, and the issue's target of 0.7
    (results/bench_reference.csv)."""
    path = os.path.join(results, "bench_reference.csv")
    if not os.path.exists(path):
        return None
    rows = read_csv(path)
    scenes, by = [], {}
    for r in rows:
        if r["measure"] in ("path_tracer", "lean_tracer"):
            if r["scene"] not in scenes:
                scenes.append(r["scene"])
            by[(r["scene"], r["measure"])] = r
    scenes = [s for s in scenes if (s, "path_tracer") in by]
    if not scenes:
        return None
    has_lean = any((sc, "lean_tracer") in by for sc in scenes)  # older files have none
    base = os.path.join(out_dir, "reference_throughput")
    data_path = base + ".dat"
    with open(data_path, "w") as f:
        for s in scenes:
            cols = [f"{s} ({int(by[(s, 'path_tracer')]['triangles']):,} triangles)"]
            for m in ("path_tracer", "lean_tracer"):
                r = by.get((s, m))
                cols += ([r["vs_replay_paired_median"], r["vs_replay_paired_min"],
                          r["vs_replay_paired_max"]] if r else ["NaN"] * 3)
            f.write(" ".join(gp_quote(c) if i == 0 else c for i, c in enumerate(cols)) + "\n")
    r0 = by[(scenes[0], "path_tracer")]
    # two lines: gnuplot reads \n in a double-quoted string as a line break
    title = (gp_quote("reference path tracer: its rays/s over Embree's alone on the same rays")[:-1]
             + "\\n" + gp_quote(f"{r0['component']} {r0['width']}x{r0['height']} {r0['spp']} spp, "
                                  f"{r0['cores']} cores, {r0['machine']}; median of {r0['repeats']} "
                                  "paired repeats, bars: least and greatest")[1:])
    script = []
    for term, ext in (("pngcairo size 900,560 font 'sans,10'", "png"), ("svg size 900,560", "svg")):
        script += [f"set terminal {term}", f"set output {gp_quote(base + '.' + ext)}",
                   f"set title {title} noenhanced",
                   "set style data histogram", "set style histogram errorbars gap 2 lw 1",
                   "set style fill solid 0.6 border -1", "set boxwidth 0.9",
                   "set yrange [0:1.15]", f"set xrange [-0.5:{len(scenes) - 0.5}]",
                   "set grid ytics", "set key inside left top",
                   "set ylabel 'paired ratio (1 = Embree alone)'",
                   f"plot {gp_quote(data_path)} using 2:3:4:xtic(1) title 'path tracer', "
                   + ("'' using 5:6:7 title 'lean tracer (little but tracing)', " if has_lean else "")
                   + "0.7 with lines dt 2 lw 2 lc rgb 'red' title 'issue target 0.7'",
                   "unset output"]
    subprocess.run(["gnuplot"], input="\n".join(script) + "\n", text=True, check=True)
    os.remove(data_path)
    return base + ".png"


def answer_data(path, ans, resolution):
    """Writes the data blocks of one answer plot: one per technique (x, y, x lo, x hi, y lo, y hi),
    then the front (each technique's step labelled once), then the rows worse than black; returns
    the techniques and whether any row is worse than black."""
    rows = answers.usable_rows(ans["rows"])
    techs = sorted({r["technique"] for r in rows})
    names = {r["technique"]: technique_label(r) for r in rows}
    with open(path, "w") as f:
        for t in techs:
            f.write(f"# {t}\n")
            for r in (r for r in rows if r["technique"] == t):
                ms, e = finite_num(r["gpu_ms_median"]), answers.relative_error(r)
                lo, _, hi = time_interval(ms, resolution)
                f.write(f"{ms:.6g} {e[1]:.6g} {lo:.6g} {hi:.6g} {e[0]:.6g} {e[2]:.6g}\n")
            f.write("\n\n")
        f.write("# pareto front (answers.py: ties called)\n")
        first = {id(seg[0][0]) for _, seg in answers.segments(ans["front"])}
        for c in ans["front"]:
            r = c[0]
            label = external.label(r) if id(r) in first else ""
            f.write(f"{finite_num(r['gpu_ms_median']):.6g} {answers.relative_error(r)[1]:.6g} {gp_quote(label)}\n")
        if not ans["front"]:
            f.write('NaN NaN ""\n')  # keeps the block, so the next one's index holds (not plotted)
        f.write("\n\n# worse than a black image\n")
        worse = [r for r in rows if worse_than_black(r)]
        for r in worse:
            f.write(f"{finite_num(r['gpu_ms_median']):.6g} {answers.relative_error(r)[1]:.6g}\n")
    return [names[t] for t in techs], bool(worse)


def answer_plot(key, ans, out_dir, resolution):
    """The answer table's plot of one group (answers.py): every technique's usable rows, time
    against relative error; bars: the time's interval at the machine's resolution and the error's
    95% interval; the Pareto front the table lists, the rows worse than a black image ringed, and
    what a black image scores as a horizontal line."""
    component, scene, camera, w, h, renderer, t, ref = key
    base = os.path.join(out_dir, answers.plot_name(key))
    data = base + ".dat"
    techs, worse = answer_data(data, ans, resolution)
    n = len(techs)
    blacks = sorted(b for b in (black_level(r, "rel_rmse") for r in answers.usable_rows(ans["rows"]))
                    if b is not None)
    plots = [f"{gp_quote(data)} index {i} using 1:2:3:4:5:6 with xyerrorbars pt 7 ps 1 title {gp_quote(t)}"
             for i, t in enumerate(techs)]
    if ans["front"]:  # empty where every row is worse than black
        plots.append(f"{gp_quote(data)} index {n} using 1:2 with lines lw 2 lc rgb 'gray30' title 'Pareto front'")
        plots.append(f"{gp_quote(data)} index {n} using 1:2:3 with labels font ',9' offset char 0.8,0.9 left "
                     "noenhanced notitle")
    if worse:
        plots.append(f"{gp_quote(data)} index {n + 1} using 1:2 with points pt 6 ps 2.4 lw 2 lc rgb 'red' "
                     "title 'worse than a black image'")
    if blacks:
        plots.append(f"{blacks[len(blacks) // 2]:.6g} with lines lw 2 dt 3 lc rgb 'black' "
                     "title 'a black image scores'")
    res = f"{100 * resolution:.0f}%" if resolution else "none measured"
    title = (f"{component}, {scene} camera {camera}, {w}x{h}" + (f" t={t}" if t != "0" else "")
             + (f" {ref}" if ref else "") + f" ({renderer}): time resolution {res}")
    script = []
    for term, ext in (("pngcairo size 900,560 font 'sans,10'", "png"), ("svg size 900,560", "svg")):
        script += [f"set terminal {term}", f"set output {gp_quote(base + '.' + ext)}",
                   f"set title {gp_quote(title)} noenhanced", "set logscale x", "set grid",
                   "set xlabel " + gp_quote("GPU time per frame, median (ms); bars: the machine's time resolution"
                                            + axis_note(answers.usable_rows(ans["rows"]))),
                   "set ylabel 'relative RMSE, reference noise removed (bars: 95% interval)'",
                   "set key outside right top noenhanced", "plot " + ", ".join(plots), "unset output"]
    subprocess.run(["gnuplot"], input="\n".join(script) + "\n", text=True, check=True)
    os.remove(data)
    return base + ".png"


def answer_plots(results, out_dir):
    """One speed-against-error plot per group the answer table ranks (answers.py)."""
    rows = [r for rs in matrices(results).values() for r in rs]
    resolution = time_resolution(results)
    return [answer_plot(key, t, out_dir, resolution) for key, t, _ in answers.answers(rows, resolution)]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("results")
    ap.add_argument("--out", default=None)
    a = ap.parse_args()
    out = a.out or os.path.join(a.results, "plots")
    if not shutil.which("gnuplot"):
        sys.exit("plot.py: gnuplot not found: run `make deps` (Debian package gnuplot-nox)")
    os.makedirs(out, exist_ok=True)
    bench = bench_plot(a.results, out)
    if bench:
        print("plot.py: wrote", bench)
    for path in answer_plots(a.results, out):
        print("plot.py: wrote", path)
    groups, renderers = {}, {}
    for rows in matrices(a.results).values():
        for r in rows:
            if r.get("status") != "ok":
                continue
            key = (r["matrix"], r["scene"], r["component"])
            groups.setdefault(key, []).append(r)
            renderers[key] = external.group_renderer(r)
    if not groups:
        print(f"plot.py: no ok rows in {a.results}/*.csv; nothing to plot")
        return
    for key, rows in sorted(groups.items()):
        for path in [plot_group(key, rows, out, renderers[key])] + sweep_plots(key, rows, out, renderers[key]):
            if path:
                print("plot.py: wrote", path)
        # Error against memory where the runs' memory differs (structure resolutions, layers...).
        if len({r["mem_bytes"] for r in rows}) >= 2:
            path = plot_group(key, rows, out, renderers[key], x="memory")
            if path:
                print("plot.py: wrote", path)
    for (scene, component, size, renderer), rows in sorted(cross_groups(groups).items()):
        for x in ("time", "memory"):
            path = plot_group(("all matrices", scene, component), rows, out, renderer, x=x, label_matrix=True,
                              name=f"cross_{scene}_{component}_{size}" + ("" if x == "time" else "_memory"))
            if path:
                print("plot.py: wrote", path)


if __name__ == "__main__":
    main()
