#!/usr/bin/env python3
"""The reproduction report, generated from the result CSVs only: RESULTS_DIR/REPORT.md and
RESULTS_DIR/report/index.html.

usage: report.py RESULTS_DIR

- per paper, every claim of claims.csv (harness/claims.py): the paper's number, ours, the machine,
  the verdict and its reason;
- per matrix (RESULTS_DIR/<matrix>.csv), its plots (RESULTS_DIR/plots/<matrix>_*.png: speed against
  error first) and per row the images side by side (reference, technique, false-colour error map,
  the FLIP map where one was written) with the row's numbers, the reference's noise beside every
  error.
The page works offline from the file system: images are linked relative to it (../images, ../plots),
style.css is copied beside it, the one script is inline. Each matrix is a collapsible <details> and
every image loads lazily, so a page of ~500 rows opens at once. Opening it with `?check` expands
every matrix, loads every image and writes how many loaded into <pre id="image-check"> (the browser
test reads it with chromium --dump-dom).
"""
import glob
import html
import os
import shutil
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from claims import COLUMNS as CLAIM_COLUMNS  # noqa: E402
from schema import fmt, image_name, matrices, read_csv  # noqa: E402
from uncertainty import (error_interval, fnum, over_black, ranks, time_interval,  # noqa: E402
                         time_resolution, worse_than_black)

HERE = os.path.dirname(os.path.abspath(__file__))
VERDICT_CLASS = {"reproduced": "yes", "not reproduced": "no", "not measurable here": "na"}


def reference_png(img_dir, r):
    """The reference preview beside a row's images: the row's `ref_image` column where the run wrote
    it; for older tables, found by scene, component and size, shown only where that names one file
    (else None and how many candidates)."""
    if r.get("ref_image"):
        path = os.path.join(img_dir, r["ref_image"])
        return (path, 1) if os.path.exists(path) else (None, 0)
    cands = sorted(glob.glob(os.path.join(
        glob.escape(img_dir), f"reference_{r['scene']}_{r['component']}_{r['width']}x{r['height']}_*.png")))
    return (cands[0], 1) if len(cands) == 1 else (None, len(cands))


def group_ranks(rows, resolution):
    """{id(row): (error rank, time rank)} within each (scene, component, size, instant) of a
    matrix: ordered by the de-noised error and by the median time, rows whose intervals overlap
    share a rank ("2="), so the reader sees ties, not an order the noise made."""
    groups = {}
    for r in rows:
        if r["status"] == "ok":
            groups.setdefault((r["scene"], r["component"], r["width"], r["height"], r.get("time")), []).append(r)
    out = {}
    for g in groups.values():
        errs = [(id(r), error_interval(r)) for r in g if error_interval(r)]
        times = [(id(r), time_interval(fnum(r.get("gpu_ms_median")), resolution)) for r in g
                 if fnum(r.get("gpu_ms_median")) is not None]
        er, tr = ranks(errs), ranks(times)
        for r in g:
            out[id(r)] = (er.get(id(r), ""), tr.get(id(r), ""))
    return out


def error_text(r):
    """The RMSE with the reference's noise taken out and its 95% interval."""
    iv = error_interval(r)
    if iv is None:
        return fmt(r.get("rmse"))
    return f"{fmt(iv[1])} [{fmt(iv[0], 3)}, {fmt(iv[2], 3)}]"


def black_text(r):
    ratio = over_black(r)
    if ratio is None:
        return ""
    return f"{ratio:.3g}" + (" WORSE THAN BLACK" if ratio > 1 else "")


def time_text(r):
    iqr = r.get("gpu_ms_iqr")
    return fmt(r.get("gpu_ms_median")) + (f" (IQR {fmt(iqr, 2)})" if iqr else "")


def row_numbers(r, rank=("", "")):
    """(label, value) pairs shown with each row; the reference's noise beside every error."""
    noise = fmt(r.get("ref_noise_rmse"))
    out = [("GPU ms (warm median)", time_text(r)), ("first frame ms", fmt(r.get("first_frame_ms"))),
           ("CPU ms", fmt(r.get("cpu_ms"))),
           ("memory MB", fmt(float(r["mem_bytes"]) / 1e6) if r.get("mem_bytes") else ""),
           ("RMSE", f"{fmt(r.get('rmse'))} (ref noise {noise})"),
           ("RMSE without the noise [95%]", error_text(r)),
           ("RMSE / black image's", black_text(r)),
           ("rank: error, time", f"{rank[0]}, {rank[1]}" if rank[0] or rank[1] else ""),
           ("rel RMSE", fmt(r.get("rel_rmse"))), ("SSIM", fmt(r.get("ssim")))]
    for col, label in (("flip", "FLIP"), ("hdrflip", "HDR-FLIP")):
        if col in r:
            out.append((label, fmt(r.get(col))))
    out.append(("ref spp", r.get("ref_spp", "")))
    if r.get("ref_noisy") == "1":
        out.append(("note", "reference too noisy to rank (noise > 1/5 of the error)"))
    return out


def plots_of(results, names):
    """{matrix: [plot png names]}: every plots/<matrix>_*.png, given to the longest matrix name it
    starts with (lrsm_sweeps_cones_* belongs to lrsm_sweeps_cones, not lrsm_sweeps); speed-against-
    error plots (no _memory / _sweep_ suffix) first."""
    out = {m: [] for m in names}
    for p in sorted(glob.glob(os.path.join(results, "plots", "*.png"))):
        base = os.path.basename(p)
        owners = [m for m in names if base.startswith(m + "_")]
        if owners:
            out[max(owners, key=len)].append(base)
    for m in out:
        out[m].sort(key=lambda b: ("_memory" in b or "_sweep_" in b, b))
    return out


def rel(path, start):
    return os.path.relpath(path, start).replace(os.sep, "/")


# ---- HTML -----------------------------------------------------------------------------------------

CHECK_SCRIPT = """
function openTarget() {  /* a link to #m-<matrix> opens that matrix */
  var d = location.hash && document.getElementById(decodeURIComponent(location.hash.slice(1)));
  if (d && d.tagName === 'DETAILS') { d.open = true; d.scrollIntoView(); }
}
window.addEventListener('hashchange', openTarget);
/* ?open=<matrix> opens that matrix in place (the README's screenshot) */
var om = /[?&]open=([^&#]*)/.exec(location.search);
if (om) { var od = document.getElementById('m-' + decodeURIComponent(om[1])); if (od) od.open = true; }
function toggleNa(box) { document.getElementById('claims').classList.toggle('show-na', box.checked); }
window.addEventListener('load', openTarget);
if (location.search.indexOf('check') >= 0) {
  document.querySelectorAll('details').forEach(function (d) { d.open = true; });
  var imgs = Array.prototype.slice.call(document.images);
  imgs.forEach(function (i) { i.loading = 'eager'; });
  function report() {
    var pending = imgs.filter(function (i) { return !i.complete; });
    if (pending.length) { setTimeout(report, 50); return; }
    var broken = imgs.filter(function (i) { return i.naturalWidth === 0; });
    var out = document.getElementById('image-check');
    out.textContent = 'images ' + imgs.length + ' loaded ' + (imgs.length - broken.length) +
      ' broken ' + broken.length + '\\n' +
      broken.map(function (i) { return 'BROKEN ' + i.getAttribute('src'); }).join('\\n');
  }
  window.addEventListener('load', report);
}
"""


def esc(x):
    return html.escape(str(x), quote=True)


def long_text(text, keep=180):
    """A long reason shows its start; the rest opens on a click (the table stays readable)."""
    if len(text) <= keep + 40:
        return esc(text)
    return f"<details class=\"more\"><summary>{esc(text[:keep])}…</summary>{esc(text[keep:])}</details>"


def claims_html(claims):
    out = ['<table id="claims"><thead><tr><th>claim</th><th>paper</th><th>ours</th><th>renderer</th>'
           '<th>cores</th><th>verdict</th><th>reason</th></tr></thead><tbody>']
    paper = None
    for c in claims:
        if c["paper"] != paper:
            paper = c["paper"]
            mine = [x for x in claims if x["paper"] == paper]
            out.append(f'<tr class="paper"><th colspan="7">{esc(paper)} '
                       f'<span class="counts">({esc(summary_counts(mine))})</span></th></tr>')
        v = c["verdict"]
        out.append(f'<tr class="claim {VERDICT_CLASS.get(v, "na")}"><td>{esc(c["claim"])}</td>'
                   f'<td>{esc(c["paper_value"])}</td><td>{esc(c["our_value"])}</td><td>{esc(c["renderer"])}</td>'
                   f'<td>{esc(c["cores"])}</td><td class="verdict">{esc(v)}</td><td>{long_text(c["reason"])}</td></tr>')
    out.append("</tbody></table>")
    return "\n".join(out)


def figure(src, caption, page_dir, cls=""):
    return (f'<figure class="{cls}"><img src="{esc(rel(src, page_dir))}" alt="{esc(caption)}" '
            f'loading="lazy"><figcaption>{esc(caption)}</figcaption></figure>')


def matrix_html(results, page_dir, name, rows, plots, resolution):
    img_dir = os.path.join(results, "images", name)
    rank = group_ranks(rows, resolution)
    ok = sum(1 for r in rows if r["status"] == "ok")
    renderers = sorted({r.get("renderer", "") for r in rows if r.get("renderer")})
    out = [f'<details class="matrix" id="m-{esc(name)}"><summary><b>{esc(name)}</b> — {len(rows)} rows, '
           f'{ok} ok; {esc(", ".join(renderers))}</summary>']
    if plots:
        out.append('<div class="plots">')
        out += [figure(os.path.join(results, "plots", p), p[:-4], page_dir, "plot") for p in plots]
        out.append("</div>")
    for r in rows:
        title = (f'{r["scene"]} · {r["technique"]} · {r["component"]} · {r["width"]}x{r["height"]}'
                 + (f' · t={r["time"]}' if r.get("time") not in ("", "0", None) else ""))
        out.append(f'<div class="row status-{esc(r["status"])}"><h4>{esc(title)} '
                   f'<span class="status">{esc(r["status"])}</span></h4>'
                   f'<div class="params">{esc(r["params"])}</div>')
        if r.get("message"):
            out.append(f'<div class="message">{esc(r["message"])}</div>')
        out.append('<dl>' + "".join(f"<dt>{esc(k)}</dt><dd>{esc(v)}</dd>" for k, v in row_numbers(r, rank.get(id(r), ("", ""))))
                   + '</dl><div class="images">')
        ref, n = reference_png(img_dir, r)
        if ref:
            out.append(figure(ref, "reference", page_dir))
        base = os.path.join(img_dir, r.get("image") or image_name(r))
        if not os.path.exists(base + ".png"):
            out.append(f'<div class="noimg">no images of this row in images/{esc(name)}/ (run with images)</div>')
        elif not ref:
            out.append(f'<div class="noimg">reference: {n} candidate images (the CSV does not name which)</div>')
        for suffix, caption in (("", "technique"), ("_error", "error map"), ("_flip", "FLIP map")):
            if os.path.exists(base + suffix + ".png"):
                out.append(figure(base + suffix + ".png", caption, page_dir))
        out.append("</div></div>")
    out.append("</details>")
    return "\n".join(out)


def summary_counts(claims):
    counts = {}
    for c in claims:
        counts[c["verdict"]] = counts.get(c["verdict"], 0) + 1
    return ", ".join(f"{n} {v}" for v, n in sorted(counts.items()))


def write_html(results, claims, mats, plots):
    page_dir = os.path.join(results, "report")
    os.makedirs(page_dir, exist_ok=True)
    shutil.copyfile(os.path.join(HERE, "report_style.css"), os.path.join(page_dir, "style.css"))
    revs = sorted({r.get("git_revision", "") for rows in mats.values() for r in rows if r.get("git_revision")})
    parts = ['<!DOCTYPE html><html lang="en"><head><meta charset="utf-8">',
             '<title>gibench reproduction report</title><link rel="stylesheet" href="style.css"></head><body>',
             '<h1>gibench reproduction report</h1>',
             f'<p>Generated from the CSVs in <code>{esc(os.path.basename(os.path.abspath(results)))}/</code>: '
             f'{len(mats)} matrices, {sum(len(v) for v in mats.values())} rows; revisions '
             f'{esc(", ".join(revs) or "unknown")}.</p>',
             '<pre id="image-check"></pre>',
             '<nav><a href="#claims-h">Claims</a> · <a href="#reading">Reading the numbers</a> · ' + " · ".join(
                 f'<a href="#m-{esc(m)}">{esc(m)}</a>' for m in mats) + '</nav>',
             f'<h2 id="claims-h">Claims ({len(claims)}: {esc(summary_counts(claims))})</h2>',
             '<p>A verdict is <i>not measurable here</i> where the paper measured absolute times on its '
             'GPU (ours ran on the renderer shown), where our run did not run or ran out of memory, or '
             'where our settings differ from the paper\'s (quick profile).</p>',
             f'<label><input type="checkbox" onchange="toggleNa(this)"> show the '
             f'{sum(1 for c in claims if c["verdict"] == "not measurable here")} claims not measurable here '
             f'(their rows are in the table, hidden until asked)</label>',
             claims_html(claims),
             '<h2 id="reading">How to read the numbers</h2><ul>'
             + "".join(f"<li>{esc(x)}</li>" for x in reading_guide(results, mats)) + '</ul>',
             '<h2>Matrices</h2>',
             '<p>Each row: reference, technique and false-colour error map side by side; the RMSE with the '
             'reference\'s own noise beside it (an error near that noise cannot rank techniques).</p>']
    parts += [matrix_html(results, page_dir, m, rows, plots[m], time_resolution(results))
              for m, rows in mats.items()]
    parts.append(f"<script>{CHECK_SCRIPT}</script></body></html>")
    path = os.path.join(page_dir, "index.html")
    with open(path, "w") as f:
        f.write("\n".join(parts) + "\n")
    return path


# ---- Markdown -------------------------------------------------------------------------------------

def md(text):
    return str(text).replace("|", "\\|").replace("\n", " ")


def write_md(results, claims, mats, plots):
    lines = ["# gibench reproduction report", "",
             "Generated from the CSVs in this folder; the page with every row's images is "
             "[report/index.html](report/index.html).", "",
             f"## Claims ({len(claims)}: {summary_counts(claims)})", ""]
    paper = None
    for c in claims:
        if c["paper"] != paper:
            paper = c["paper"]
            lines += ["", f"### {paper}", "", "| claim | paper | ours | renderer | verdict | reason |",
                      "|---|---|---|---|---|---|"]
        lines.append("| " + " | ".join(md(c[k]) for k in ("claim", "paper_value", "our_value", "renderer",
                                                              "verdict", "reason")) + " |")
    lines += ["", "## How to read the numbers", ""] + [f"- {x}" for x in reading_guide(results, mats)]
    lines += ["", "## Matrices", ""]
    resolution = time_resolution(results)
    for m, rows in mats.items():
        rank = group_ranks(rows, resolution)
        lines += [f"### {m}", ""]
        lines += [f"![{p[:-4]}](plots/{p})" for p in plots[m] if "_memory" not in p and "_sweep_" not in p]
        lines += ["", "| scene | technique | component | size | params | GPU ms (IQR) | first frame ms "
                  "| RMSE (ref noise) | RMSE without noise [95%] | / black | rank: error, time | rel RMSE "
                  "| SSIM | status | images |", "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
        for r in rows:
            rk = rank.get(id(r), ("", ""))
            name = image_name(r)
            imgs = ""
            if os.path.exists(os.path.join(results, "images", m, name + ".png")):
                imgs = f"[image](images/{m}/{name}.png) [error](images/{m}/{name}_error.png)"
            lines.append("| " + " | ".join(md(x) for x in (
                r["scene"], r["technique"], r["component"], f"{r['width']}x{r['height']}", r["params"],
                time_text(r), fmt(r.get("first_frame_ms")),
                f"{fmt(r.get('rmse'))} ({fmt(r.get('ref_noise_rmse'))})", error_text(r), black_text(r),
                f"{rk[0]}, {rk[1]}" if rk[0] or rk[1] else "",
                fmt(r.get("rel_rmse")), fmt(r.get("ssim")), r["status"], imgs)) + " |")
        lines.append("")
    path = os.path.join(results, "REPORT.md")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    return path


def reading_guide(results, mats):
    """The facts a reader needs before comparing two rows: how times were taken and what this
    machine can resolve, what the errors are measured against, and how many rows cannot be ranked."""
    ok = [r for rows in mats.values() for r in rows if r["status"] == "ok"]
    noisy = sum(1 for r in ok if r.get("ref_noisy") == "1")
    worse = [r for r in ok if worse_than_black(r)]
    warm = sorted({(r.get("warmup"), r.get("frames")) for r in ok})
    res = time_resolution(results)
    out = ["Times are medians of warm frames (warm-up, timed frames: "
           + ", ".join(f"{w}, {f}" for w, f in warm)
           + "), with their interquartile range; every run's cold first frame (shader compiles, first "
           "use) is rendered before the warm-up and reported apart (first frame ms, create included)."]
    if res is not None:
        out.append(f"This machine resolves time differences of {100 * res:.1f}% (the 95th percentile of "
                   "the run-to-run difference of the same runs, timing_resolution.csv, "
                   "harness/bench_timing.py): two medians closer than that are a tie (rank 'n=').")
    else:
        out.append("The timing benchmark (harness/bench_timing.py) has not been run into this folder: no "
                   "time difference is called a tie, and small ones may be noise.")
    out.append("Every error stands beside what an all-black image scores against the same reference "
               "(RMSE / black image's): above 1, the technique is further from the reference than "
               f"leaving the component out. {len(worse)} of {len(ok)} ok rows are worse than black"
               + (": " + "; ".join(sorted({f"{r['matrix']} {r['scene']} {r['technique']} {r['component']}"
                                           for r in worse})[:12]) + (" ..." if len(worse) > 12 else "")
                  if worse else "") + ".")
    out.append("The RMSE without the noise takes the reference's own noise out of the error "
               "(sqrt(rmse^2 - noise^2)) with a 95% interval (metrics.h, gib_rmse_interval); rows whose "
               "intervals overlap share a rank ('n='): a tie, not an order.")
    out.append(f"{noisy} of {len(ok)} ok rows ({100 * noisy / max(len(ok), 1):.1f}%) are ref_noisy (the "
               "reference's noise above a fifth of the row's error even after its samples were raised "
               "to rank its rows, up to ref_spp_growth times the matrix's).")
    return out


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: report.py RESULTS_DIR")
    results = sys.argv[1]
    claims_path = os.path.join(results, "claims.csv")
    if not os.path.exists(claims_path):
        sys.exit(f"report.py: {claims_path} not found: run harness/claims.py {results} first (make plots)")
    claims = read_csv(claims_path)
    missing = [c for c in CLAIM_COLUMNS if claims and c not in claims[0]]
    if missing:
        sys.exit(f"report.py: {claims_path}: columns {', '.join(missing)} missing")
    mats = matrices(results)
    plots = plots_of(results, list(mats))
    print(write_md(results, claims, mats, plots))
    print(write_html(results, claims, mats, plots))


if __name__ == "__main__":
    main()
