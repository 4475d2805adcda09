#!/usr/bin/env python3
"""The reproduction report, generated from the result CSVs only: RESULTS_DIR/REPORT.md and
RESULTS_DIR/report/index.html.

usage: python3 -m reporting.report RESULTS_DIR

- per paper, every claim of claims.csv (harness/reporting/claims.py): the paper's number, ours, the machine,
  the verdict and its reason;
- per matrix (RESULTS_DIR/<matrix>.csv), its plots (RESULTS_DIR/plots/<matrix>_*.png: speed against
  error first) and per row the images side by side (reference, technique, false-colour error map,
  the FLIP map where one was written) with the row's numbers, the reference's noise beside every
  error.
The page works offline from the file system: images are linked relative to it (../images, ../plots),
style.css is copied beside it, the scripts are inline (the checks below, and report_compare.js: each
gallery group's image comparison, A over B at a split, zoom, exposure, by keys). Each matrix is a collapsible <details> and
every image loads lazily, so a page of ~500 rows opens at once. Opening it with `?check` expands
every matrix, loads every image and writes how many loaded into <pre id="image-check"> (the browser
test reads it with chromium --dump-dom).
"""
import glob
import html
import os
import shutil
import sys

from reporting.claims import COLUMNS as CLAIM_COLUMNS  # noqa: E402
from reporting import schema  # noqa: E402
from reporting.schema import fmt, image_name, matrices, read_csv  # noqa: E402
from reporting.uncertainty import (error_interval, fnum, over_black, ranks, time_interval,  # noqa: E402
                         time_resolution, worse_than_black)
from reporting import answers  # noqa: E402
from reporting import shipped_images  # noqa: E402
from reporting import gpu_rows  # noqa: E402
from reporting.gpu_summary import RASTER_LIMITS  # noqa: E402
from reporting import cone_report  # noqa: E402
from reporting import energy_audit  # noqa: E402
from reporting import pass_work  # noqa: E402
from reporting import temporal_tables  # noqa: E402

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
    """{id(row): (error rank, time rank)} within each group of a matrix that estimates one image
    (answers.group_key: scene, component, camera, size, renderer, instant, the reference's
    parameters): ordered by the de-noised error and by the median time, rows whose intervals
    overlap share a rank ("2="), so the reader sees ties, not an order the noise made."""
    groups = {}
    for r in rows:
        if r["status"] == "ok":
            groups.setdefault(answers.group_key(r), []).append(r)
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


# ---- the answer: which technique for which effect ---------------------------------------------

TIE, STEP = " ≈ ", " → "


def is_software(renderer):
    return schema.is_software_renderer(renderer)


def ms_text(ms):
    return f"{ms:.2g}" if ms < 10 else f"{ms:.0f}"


def mb_text(b):
    mb = b / 1e6
    return f"{mb:.2g}" if mb < 10 else f"{mb:.0f}"


def err_text(e, digits=3):
    return f"{e:.{digits}g}"


def span_text(values, show):
    lo, hi = min(values), max(values)
    return show(lo) if show(lo) == show(hi) else f"{show(lo)}–{show(hi)}"


ERROR_WORDS = ("error: RMSE over the reference's mean, for glossy and caustics over a black image's; "
               "mean: the image's mean over the reference's")
OVER_BLACK = ("glossy", "caustic")  # components whose error reads as a share of a black image's


def shown_error(r):
    """The error a front shows for row r: the relative RMSE (over the reference's mean), or for
    glossy and caustics, whose references are mostly dark (a relative RMSE of 6 or 13 says
    nothing), the RMSE over a black image's (1: as far off as leaving the component out). Within
    a group both order the rows alike: the black image's RMSE is the group's own."""
    if r.get("component") in OVER_BLACK and fnum(r.get("black_rmse")):
        return (fnum(r.get("rmse_denoised")) or fnum(r.get("rmse")) or 0.0) / fnum(r["black_rmse"])
    return answers.relative_error(r)[1]


def mean_text(cands):
    """'mean 0.94' (or a span): the rows' image mean over the reference's."""
    means = [fnum(c[0].get("mean_ratio")) for c in cands]
    means = [m for m in means if m is not None]
    return "mean " + span_text(means, lambda m: f"{m:.2f}") if means else ""


def segment_text(tech, cands, memory, digits=3):
    """One technique's step of a front: 'lrsm 168–204 ms 1.62 mean 0.81–0.94 (9 settings)'."""
    costs = [c[2][1] for c in cands]
    errs = [err_text(shown_error(c[0]), digits) for c in cands]
    cost = span_text(costs, mb_text) + " MB" if memory else span_text(costs, ms_text) + " ms"
    err = errs[0] if errs[0] == errs[-1] else f"{errs[0]}–{errs[-1]}"
    mean = mean_text(cands)
    return (f"{tech} {cost} {err}" + (f" {mean}" if mean else "")
            + (f" ({len(cands)} settings)" if len(cands) > 1 else ""))


def last_error(cands, digits):
    return err_text(shown_error(cands[-1][0]), digits)


def front_parts(ans, memory=False):
    """[(joiner before it, text, settings)] of a front, cheapest first; the joiner is TIE where the
    step's error interval overlaps the previous step's (a tie: either will do), else STEP. A step
    whose error prints as its predecessor's at 3 digits prints both at 4 (it is clearly less)."""
    fr, ties = ans["front"], ans["ties"]
    index = {id(c): i for i, c in enumerate(fr)}
    segs = answers.segments(fr)
    joins, digits = [""], [3] * len(segs)
    for k in range(1, len(segs)):
        prev, mine = ({index[id(c)] for c in segs[j][1]} for j in (k - 1, k))
        tied = any(j in prev for i in mine for j in ties[i])
        joins.append(TIE if tied else STEP)
        if not tied and last_error(segs[k - 1][1], 3) == err_text(shown_error(segs[k][1][0][0])):
            digits[k - 1] = digits[k] = 4
    return [(joins[k], segment_text(t, cands, memory, digits[k]), "; ".join(c[0]["params"] for c in cands))
            for k, (t, cands) in enumerate(segs)]


def front_plain(ans, memory=False):
    parts = front_parts(ans, memory)
    if not parts:
        return "none better than a black image" if ans["black"] else ""
    return "".join(j + t for j, t, _ in parts)


def beaten_list(ans):
    """The techniques compared whose every usable setting another row beats (not worse than black)."""
    on = {c[0]["technique"] for c in ans["front"]}
    usable = {c[0]["technique"] for c in answers.candidates(ans["rows"], answers.time_cost, None)[0]}
    return ", ".join(sorted(usable - on))


def black_list(ans):
    """'ldm_indirect ×3, vct': the techniques with rows worse than a black image (settings counted)."""
    counts = {}
    for r in answers.distinct(ans["black"]):
        counts[r["technique"]] = counts.get(r["technique"], 0) + 1
    return ", ".join(t + (f" ×{n}" if n > 1 else "") for t, n in sorted(counts.items()))


def size_text(key):
    """The image size, and the camera, instant and reference parameters where they matter."""
    _, _, camera, w, h, _, t, ref = key
    return (f"{w}x{h}" + (f" camera {camera}" if camera not in ("", "0") else "")
            + (f" t={t}" if t != "0" else "") + (f" {ref}" if ref else ""))


def size_label(key, t, many):
    """A group's size and profile, and where its times come from: a GPU (the device run's size) or
    the renderer, named where the answers rank on more than one."""
    return (size_text(key) + f", {answers.profile_of(t['rows'])} profile"
            + (f", time on {t['rows'][0]['time_source']}" if answers.gpu_timed(t) else
               f" on {key[5]}" if many else ""))


def other_text(key, head):
    """Another group of a headline's component and scene, by what differs from the headline's."""
    parts = []
    if key[3:5] != head[3:5]:
        parts.append(f"{key[3]}x{key[4]}")
    if key[2] != head[2]:
        parts.append(f"camera {key[2]}")
    if key[6] != head[6]:
        parts.append(f"t={key[6]}")
    if key[7] != head[7]:
        parts.append(key[7] or "reference default")
    if key[5] != head[5]:
        parts.append(f"on {key[5].split(' (')[0]}")
    return " ".join(parts)


def answer_rows(results, mats):
    """Every group two or more techniques estimate, and the headline one per component and scene:
    (all, headline), each [{key, time, memory, others, plot (path from results or None), anchor}]."""
    rows = [r for rs in mats.values() for r in rs]
    rows += gpu_rows.timed_copies(rows, results)
    resolution = time_resolution(results)
    every = answers.answers(rows, resolution)

    def entry(key, t, m, others):
        plot = f"plots/{answers.plot_name(key)}.png"
        return {"key": key, "time": t, "memory": m, "others": others,
                "plot": plot if os.path.exists(os.path.join(results, plot)) else None,
                "anchor": "g-" + answers.plot_name(key)}
    return ([entry(k, t, m, []) for k, t, m in every],
            [entry(k, t, m, o) for k, t, m, o in answers.headline(every)])


def lone_components(mats, heads):
    """{component: techniques} of the components present that no two techniques estimate."""
    comps = {}
    for rs in mats.values():
        for r in rs:
            if r["status"] == "ok" and r["component"] in ANSWER_COMPONENTS:
                comps.setdefault(r["component"], set()).add(r["technique"])
    answered = {h["key"][0] for h in heads}
    return {c: sorted(t) for c, t in comps.items() if c not in answered}


ANSWER_COMPONENTS = ("ao", "direct", "indirect", "glossy", "caustic")


def mark_stale(mats):
    """Rows whose technique's sources changed since they ran (their technique_hash, or for rows
    written before the column their revision's, differs from the sources' now: gpu_rows.Hashes)
    get status `stale`: the answers leave them out, the tables show them as such."""
    hashes = gpu_rows.Hashes()
    for rows in mats.values():
        for r in rows:
            if r.get("status") == "ok" and r.get("technique") and \
                    hashes.of_row(r) != hashes.current(r["technique"]):
                r["status"] = "stale"
                r["message"] = "the technique's sources changed since this row ran (source_hash.py)"


def renderer_sentences(heads):
    """One sentence per renderer the answers ranked on: a GPU's times with its raster limit, a
    software renderer's as its own speed only."""
    out = []
    for rend in sorted({h["key"][5] for h in heads}):
        if is_software(rend):
            out.append(f"Where no valid GPU row exists, times are {rend}'s, a CPU rasterizer's: the ranking "
                       f"by time is {rend.split()[0]}'s and a GPU's may differ; memory and error rank the "
                       "same on any machine.")
        else:
            limit = next((f" ({k}: {v})" for k, v in RASTER_LIMITS.items() if k in rend), "")
            out.append(f"Times from {rend}{limit}, at the papers' image sizes (a timing-only device run, "
                       "results/gpu); errors from the paper profile's rows on llvmpipe at at most 4x smaller "
                       "sizes.")
    stale = sum(1 for h in heads for r in h["time"]["rows"] if r.get("status") == "stale")
    if stale:
        out.append(f"{stale} rows of these groups are stale (their technique changed since they ran) and "
                   "are left out.")
    return out


def findings_text(f):
    """A paper's findings as (title, sentences), from answers.findings."""
    c = f["counts"]
    total = sum(c.values())
    out = [f"{total} claims: {c['reproduced']} reproduced, {c['not reproduced']} not reproduced, "
           f"{c['not measurable here']} not measurable here."]
    if f["not_reproduced"]:
        items = []
        for st, n, pv, ov, why in f["not_reproduced"]:
            why = why.replace("; ", ", ")
            ours = f"ours {why}" if not ov or why.startswith(ov) else f"ours {ov} ({why})"
            items.append(f"{st}{f' ({n} settings)' if n > 1 else ''}: paper {pv or '-'}, {ours}")
        out.append("Not reproduced: " + "; ".join(items) + ".")
    if f["unmeasured"]:
        out.append("Not measurable here: " + "; ".join(f"{n} {what} (would take {by})"
                                                        for what, by, n in f["unmeasured"]) + ".")
    return f["paper"], out


def gallery_cells(results, group_rows):
    """The gallery of one group: [(caption, numbers, image path or None, error map path or None,
    error map's scale, params)]: the reference, then each technique's row nearest the group's
    median time (answers.at_common_cost). Paths are given whether or not the file exists."""
    picked = answers.at_common_cost(group_rows)
    ref = named = None
    # the least noisy reference the group's rows were scored against (a row's samples may have been raised)
    for r in sorted(group_rows, key=lambda r: -(fnum(r.get("ref_spp")) or 0)):
        path, _ = reference_png(os.path.join(results, "images", r["matrix"]), r)
        if path:
            ref = path
            break
        if named is None and r.get("ref_image"):
            named = os.path.join(results, "images", r["matrix"], r["ref_image"])
    ref = shipped_images.shipped(results, ref or named)
    cells = [("reference", "path-traced reference", ref, None, "", "")]
    for r in picked:
        base = os.path.join(results, "images", r["matrix"], r.get("image") or image_name(r))
        flip = base + "_flip.png"
        has_flip = os.path.exists(flip) or os.path.exists(shipped_images.copy_path(results, flip))
        emap, scale = (flip, "FLIP, 0–1") if has_flip else (base + "_error.png", "RMS error, own scale")
        what = "error over black's" if r.get("component") in OVER_BLACK else "rel. error"
        mean = fnum(r.get("mean_ratio"))
        nums = (f"{ms_text(fnum(r['gpu_ms_median']))} ms · {what} {err_text(shown_error(r))}"
                + (f" · mean {mean:.2f}" if mean is not None else "")
                + (f" · {mb_text(fnum(r['mem_bytes']))} MB" if fnum(r.get("mem_bytes")) else "")
                + (" · WORSE THAN BLACK" if worse_than_black(r) else ""))
        cells.append((r["technique"], nums, shipped_images.shipped(results, base + ".png"),
                      shipped_images.shipped(results, emap), scale, r["params"]))
    return cells


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
    var holders = document.querySelectorAll('.placeholder').length;
    out.textContent = 'images ' + imgs.length + ' loaded ' + (imgs.length - broken.length) +
      ' broken ' + broken.length + ' placeholders ' + holders + '\\n' +
      broken.map(function (i) { return 'BROKEN ' + i.getAttribute('src'); }).join('\\n');
  }
  window.addEventListener('load', report);
}
/* ?check also checks the sequences' animations into <pre id="animation-check">: each loaded at its
 * stated size, and playing: the browser's own decoder (ImageDecoder) reads it as animated, with the
 * stated number of frames, not all alike. */
function frameSum(bitmap) {
  var c = new OffscreenCanvas(bitmap.displayWidth, bitmap.displayHeight), g = c.getContext('2d');
  g.drawImage(bitmap, 0, 0);
  var p = g.getImageData(0, 0, c.width, c.height).data, s = 0;
  for (var i = 0; i < p.length; i++) s += p[i] * (i % 97);
  return s;
}
function plays(img) {
  return new Promise(function (done) {
    var x = new XMLHttpRequest();
    x.open('GET', img.src);
    x.responseType = 'arraybuffer';
    x.onerror = function () { done(false); };
    x.onload = async function () {
      try {
        var d = new ImageDecoder({data: x.response, type: 'image/webp'});
        await d.tracks.ready;
        var t = d.tracks.selectedTrack, sums = {};
        for (var k = 0; k < t.frameCount; k++)
          sums[frameSum((await d.decode({frameIndex: k})).image)] = 1;
        done(t.animated && t.frameCount === +img.dataset.frames && Object.keys(sums).length > 1);
      } catch (e) { done(false); }
    };
    x.send();
  });
}
if (location.search.indexOf('check') >= 0) {
  window.addEventListener('load', async function () {
    var anims = Array.prototype.slice.call(document.querySelectorAll('img.animation'));
    /* a lazy image may not have loaded by the page's load event: wait for each to decode */
    for (var j = 0; j < anims.length; j++) {
      anims[j].loading = 'eager';
      await anims[j].decode().catch(function () {});
    }
    var sized = anims.filter(function (i) {
      return i.naturalWidth === +i.dataset.width && i.naturalHeight === +i.dataset.height; });
    var playing = 0;
    for (var k = 0; k < anims.length; k++) playing += (await plays(anims[k])) ? 1 : 0;
    document.getElementById('animation-check').textContent = 'animations ' + anims.length +
      ' sized ' + sized.length + ' playing ' + playing;
  });
}
"""


def esc(x):
    return html.escape(str(x), quote=True)


def long_text(text, keep=180):
    """A long reason shows its start; the rest opens on a click (the table stays readable)."""
    if len(text) <= keep + 40:
        return esc(text)
    return f"<details class=\"more\"><summary>{esc(text[:keep])}…</summary>{esc(text[keep:])}</details>"


def claim_rows_html(claims, headers=True):
    out, paper = [], None
    for c in claims:
        if headers and c["paper"] != paper:
            paper = c["paper"]
            mine = [x for x in claims if x["paper"] == paper]
            out.append(f'<tr class="paper"><th colspan="7">{esc(paper)} '
                       f'<span class="counts">({esc(summary_counts(mine))})</span></th></tr>')
        v = c["verdict"]
        out.append(f'<tr class="claim {VERDICT_CLASS.get(v, "na")}"><td>{esc(c["claim"])}</td>'
                   f'<td>{esc(c["paper_value"])}</td><td>{esc(c["our_value"])}</td><td>{esc(c["renderer"])}</td>'
                   f'<td>{esc(c["cores"])}</td><td class="verdict">{esc(v)}</td><td>{long_text(c["reason"])}</td></tr>')
    return out


CLAIM_HEAD = ('<thead><tr><th>claim</th><th>paper</th><th>ours</th><th>renderer</th><th>cores</th>'
              '<th>verdict</th><th>reason</th></tr></thead>')


def split_claims(claims):
    """(error and memory claims, orders of times, {paper: its absolute GPU times}), by
    answers.claim_kind: what each depends on."""
    kinds = [answers.claim_kind(c) for c in claims]
    mi = [c for c, k in zip(claims, kinds) if k not in (answers.ABSOLUTE_TIME, answers.TIME_ORDER)]
    orders = [c for c, k in zip(claims, kinds) if k == answers.TIME_ORDER]
    absolute = {}
    for c, k in zip(claims, kinds):
        if k == answers.ABSOLUTE_TIME:
            absolute.setdefault(c["paper"], []).append(c)
    return mi, orders, absolute


def why_not_comparable(cs):
    ours = sorted({c["renderer"] for c in cs if c["renderer"]})
    return ("The paper timed its own GPU and ours ran on " + (", ".join(ours) or "another renderer")
            + ": a frame time belongs to its machine, so these stand side by side unjudged (the claims "
            "above compare what carries over: memory, error, orders and ratios).")


TOLERANCE_NOTE = ("One tolerance per kind of claim: memory holds within 25% of the paper's figure (whether "
                  "our bytes equal the paper's formula is stated beside); errors are compared as intervals "
                  "(overlap: a tie); orders of times at the machine's time resolution; qualitative claims by "
                  "the threshold their reason states. A claim tested at several settings is one row: it "
                  "holds where every setting measured holds.")
ORDERS_NOTE = ("An order or a ratio of two times carries over between machines only as far as their "
               "pipelines agree: each is judged on the renderer its row names (a GPU where a valid device "
               "run answers it, else llvmpipe, a CPU rasterizer).")


def claims_html(claims):
    """The claims that do not depend on the machine (memory, error, leaks) in one table, the orders
    of times (judged on the renderer named) in another, then each paper's absolute GPU times in a
    table of their own, collapsed."""
    mi, orders, absolute = split_claims(claims)
    out = [f'<p class="policy">{esc(TOLERANCE_NOTE)}</p>',
           f'<h3 id="claims-mi">Claims that do not depend on the machine ({len(mi)}: {esc(summary_counts(mi))})</h3>',
           f'<table id="claims">{CLAIM_HEAD}<tbody>'] + claim_rows_html(mi) + ["</tbody></table>"]
    out += [f'<h3 id="claims-orders">Orders of times, on the renderer named ({len(orders)}: '
            f'{esc(summary_counts(orders))})</h3><p>{esc(ORDERS_NOTE)}</p>',
            f'<table id="claims-orders-table">{CLAIM_HEAD}<tbody>'] + claim_rows_html(orders) + ["</tbody></table>"]
    n = sum(len(v) for v in absolute.values())
    out.append(f'<h3 id="claims-abs">The papers\' absolute GPU times ({n}), per paper</h3>')
    for paper, cs in absolute.items():
        out.append(f'<details class="absolute"><summary><b>{esc(paper)}</b>: {len(cs)} times. '
                   f'{esc(why_not_comparable(cs))}</summary><table class="claims-abs">{CLAIM_HEAD}<tbody>')
        out += claim_rows_html(cs, headers=False) + ["</tbody></table></details>"]
    return "\n".join(out)


def figure(src, caption, page_dir, cls=""):
    return (f'<figure class="{cls}"><img src="{esc(rel(src, page_dir))}" alt="{esc(caption)}" '
            f'loading="lazy"><figcaption>{esc(caption)}</figcaption></figure>')


def front_html(ans, memory=False):
    parts = front_parts(ans, memory)
    if not parts:
        return "<i>none better than a black image</i>" if ans["black"] else ""
    return "".join(f'{esc(j)}<span class="step" title="{esc(p)}">{esc(t)}</span>' for j, t, p in parts)


def answer_table_html(entries, page_dir, results, cls):
    """One row per group: component (once per run of rows), scene and size with the links to its plot
    and gallery, the front by time with the rows worse than black beneath, the front by memory."""
    out = [f'<table class="{cls}"><thead><tr><th></th><th>scene, size</th>'
           f'<th>least error for its time: Pareto front, cheapest first (ms, {esc(ERROR_WORDS)})</th>'
           f'<th>for its memory (MB, the same)</th></tr></thead><tbody>']
    prev, many = None, len({e["key"][5] for e in entries}) > 1
    for e in entries:
        key, t = e["key"], e["time"]
        size = size_label(key, t, many)
        links = [f'<a href="{esc(rel(os.path.join(results, e["plot"]), page_dir))}">plot</a>'] if e["plot"] else []
        if cls == "answers":
            links.append(f'<a href="#{esc(e["anchor"])}">images</a>')
        also = (f'<div class="also">also {esc(", ".join(other_text(k, key) for k in e["others"]))}</div>'
                if e["others"] else "")
        black = black_list(t)
        out.append(f'<tr class="answer{" first" if key[0] != prev else ""}" data-component="{esc(key[0])}" '
                   f'data-scene="{esc(key[1])}" data-size="{esc(size_text(key))}"><th>{esc(key[0]) if key[0] != prev else ""}</th>'
                   f'<td>{esc(key[1])} <span class="size">{esc(size)}</span> {" ".join(links)}{also}</td>'
                   f'<td title="compared: {esc(", ".join(t["techniques"]))}">{front_html(t)}'
                   + (f'<div class="beaten">beaten: {esc(beaten_list(t))}</div>' if beaten_list(t) else "")
                   + (f'<div class="black">worse than black: {esc(black)}</div>' if black else "")
                   + f'</td><td>{front_html(e["memory"], memory=True)}</td></tr>')
        prev = key[0]
    out.append("</tbody></table>")
    return "\n".join(out)


def answer_html(results, page_dir, heads, lone, claims):
    """The first screen: which technique for which effect, beside what each paper's claims came to."""
    left = ['<h2 id="answer">Which technique for which effect</h2>',
            "<p>" + esc(" ".join(renderer_sentences(heads))) + " A step → has clearly less error than the "
            "one before it; ≈ is a tie (error intervals overlap): either will do. Hover a step for its "
            "settings.</p>",
            answer_table_html(heads, page_dir, results, "answers")]
    if lone:
        left.append("<p>" + esc("Estimated by one technique only, so no comparison: " + "; ".join(
            f"{c} ({', '.join(t)})" for c, t in sorted(lone.items()))) + ".</p>")
    right = ['<h2 id="findings">Findings per paper</h2>']
    for f in answers.findings(claims):
        title, sentences = findings_text(f)
        right.append(f'<p class="finding"><b>{esc(title)}</b>. ' + " ".join(esc(x) for x in sentences) + "</p>")
    return ('<div class="first-screen"><div class="answer-col">' + "\n".join(left) + '</div><div class="findings-col">'
            + "\n".join(right) + "</div></div>")


def media_html(path, page_dir, caption, results):
    """An image, or a labelled placeholder (not a broken link) where its file is absent."""
    if path and os.path.exists(path):
        return f'<img src="{esc(rel(path, page_dir))}" alt="{esc(caption)}" loading="lazy">'
    where = rel(path, results) if path else "no file named"
    return f'<div class="placeholder" data-missing="{esc(where)}">{esc(caption)}: not written here<br><small>{esc(where)}</small></div>'


def gallery_html(results, page_dir, mats, heads):
    """Per headline group, the reference and each technique's row at a common cost side by side (at
    the scene's one exposure), their numbers beneath, then their error maps: the LRSM paper's Fig. 7."""
    rows = [r for rs in mats.values() for r in rs]
    out = ['<h2 id="gallery">Gallery: each technique at a common cost</h2>',
           "<p>Per component and scene, the reference and each technique's setting whose time is nearest "
           "the group's median time, at the scene's one exposure; their error maps beneath (FLIP maps "
           "share one scale, 0–1; an RMS error map is scaled to its own 99th percentile).</p>"]
    if not any(os.path.isdir(os.path.join(results, d)) for d in ("images", shipped_images.FOLDER)):
        out.append(f"<p><b>This folder holds no images</b> ({esc(os.path.basename(os.path.abspath(results)))}/images/"
                   "is written by a run, not committed): each cell names the file it would show.</p>")
    for e in heads:
        grp = e["time"]["rows"]  # a GPU-timed group's rows are the timed copies of llvmpipe's
        cells = gallery_cells(results, grp)
        key = e["key"]
        out.append(f'<section class="gallery" id="{esc(e["anchor"])}"><h3>{esc(key[0])}, {esc(key[1])} '
                   f'{esc(size_text(key))}</h3><table class="gallery"><tr>')
        out += [f'<th>{esc(c[0])}</th>' for c in cells]
        out.append("</tr><tr>")
        out += [f'<td>{media_html(c[2], page_dir, c[0], results)}</td>' for c in cells]
        out.append("</tr><tr>")
        out += [f'<td class="nums">{esc(c[1])}' + (f'<details class="more"><summary>settings</summary>'
                f'<div class="params">{esc(c[5])}</div></details>' if c[5] else "") + '</td>' for c in cells]
        out.append("</tr><tr>")
        out += [f'<td>{media_html(c[3], page_dir, "error map", results) if c[3] else ""}'
                f'<div class="scale">{esc(c[4])}</div></td>' for c in cells]
        out.append("</tr></table>")
        out.append(compare_html(cells, page_dir))
        out.append("</section>")
    return "\n".join(out)


def compare_html(cells, page_dir):
    """A gallery group's comparison (report_compare.js): every image of its cells that exists (the
    reference, each technique, their error maps with their scale) to pick as A and B, A the first
    technique and B the reference at first; each option carries its numbers from the CSVs."""
    options = []
    for caption, nums, img, emap, scale, _ in cells:
        if img and os.path.exists(img):
            options.append((caption, nums, img))
        if emap and os.path.exists(emap):
            options.append((f"{caption} error map", scale, emap))
    if len(options) < 2:
        return ""

    def select(cls, chosen):
        return (f'<select class="{cls}">' + "".join(
            f'<option value="{esc(rel(path, page_dir))}" data-nums="{esc(nums)}"'
            f'{" selected" if i == chosen else ""}>{i + 1} {esc(caption)}</option>'
            for i, (caption, nums, path) in enumerate(options)) + "</select>")
    first_technique = next((i for i, o in enumerate(options) if i and "error map" not in o[0]), 1)
    return ('<div class="compare"><div class="cmp-view" tabindex="0"><div class="cmp-stage">'
            '<img class="cmp-b" alt="B"><img class="cmp-a" alt="A"><div class="cmp-line"></div></div></div>'
            f'<div class="cmp-bar">A {select("cmp-pick-a", first_technique)} B {select("cmp-pick-b", 0)} '
            'split <input type="range" class="cmp-split" min="0" max="100" value="50"> '
            '<span class="cmp-state"></span></div><div class="cmp-nums"></div>'
            '<div class="cmp-help">Click the image, then: ← → move the split, f swaps A and B, 1-9 pick '
            'A (Shift: B), + − zoom (nearest pixel), e E exposure in stops, 0 resets.</div></div>')


SEQ_HEAD = ("scene", "technique", "component", "settings", "frames", "frame RMSE mean (worst, frame)",
            "temporal RMSE without noise", "frozen scale", "flicker", "/ frozen", "temporal FLIP",
            "steady")


def sequence_cells(r):
    """The numbers of a sequence row, in SEQ_HEAD's order after the settings."""
    return (f"{r['sequence']} x {fmt(r['dt'])} s to t={fmt(r['time'])}",
            f"{fmt(r['seq_rmse_mean'], 3)} ({fmt(r['seq_rmse_worst'], 3)}, {r['seq_worst_frame']})",
            fmt(r["temporal_rmse_denoised"], 3), fmt(r["temporal_frozen"], 3), fmt(r["flicker"], 3),
            fmt(r["over_frozen"], 3), fmt(r["temporal_flip"], 3), r["steady"])


def sequences_intro():
    return ("A sequence is N consecutive frames of one running technique (its state carried from frame "
            "to frame), each scored against the reference at its instant; the temporal error is the "
            "RMSE of its frame-to-frame changes against the reference's, the reference's noise taken "
            "out. Beside it the frozen scale (what a sequence that never changes scores) and two ratios "
            "(harness/reporting/temporal_tables.py): flicker = temporal error / (sqrt 2 x frame error), 0 for an "
            f"error steady over time, 1 for one drawn anew every frame; steady means flicker <= "
            f"{temporal_tables.FLICKER_MAX} and under the frozen scale. Each animation shows reference | "
            "technique | error map (one scale for the sequence), 4 frames a second.")


def sequences_html(results, page_dir, seq_rows):
    if not seq_rows:
        return ""
    out = ['<h2 id="sequences">Sequences: error over time</h2>', f"<p>{esc(sequences_intro())}</p>",
           '<table id="sequences-table"><tr>' + "".join(f"<th>{esc(h)}</th>" for h in SEQ_HEAD)
           + "<th>animation</th></tr>"]
    for r in seq_rows:
        anim = os.path.join(results, "animations", r["animation"]) if r["animation"] else ""
        cap = f"{r['scene']} {r['technique']} {r['component']}: reference | technique | error"
        media = media_html(anim, page_dir, cap, results).replace(
            "<img ", f'<img class="animation" data-frames="{esc(r["sequence"])}" '
            f'data-width="{3 * 2 * int(r["width"])}" data-height="{2 * int(r["height"])}" ', 1)
        out.append("<tr>" + "".join(f"<td>{esc(x)}</td>" for x in (r["scene"], r["technique"],
                                                                      r["component"]))
                   + f'<td class="params">{long_text(r["params"], 60)}</td>'
                   + "".join(f"<td>{esc(x)}</td>" for x in sequence_cells(r)) + f"<td>{media}</td></tr>")
    out.append("</table>")
    return "\n".join(out)


def sequences_md(seq_rows):
    if not seq_rows:
        return []
    lines = ["## Sequences: error over time", "", sequences_intro(), "",
             "| " + " | ".join(SEQ_HEAD) + " | animation |", "|" + "---|" * (len(SEQ_HEAD) + 1)]
    for r in seq_rows:
        anim = f"[webp](animations/{r['animation']})" if r["animation"] else ""
        lines.append("| " + " | ".join(md(x) for x in (
            r["scene"], r["technique"], r["component"], r["params"]) + sequence_cells(r))
            + f" | {anim} |")
    return lines + [""]


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
        title = (f'{r["scene"]} · {r["technique"]} · {r["component"]} · {r["width"]}x{r["height"]} · {r.get("profile", "")} profile'
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


def write_html(results, claims, mats, plots, seq_rows=(), energy=()):
    page_dir = os.path.join(results, "report")
    os.makedirs(page_dir, exist_ok=True)
    shutil.copyfile(os.path.join(HERE, "report_style.css"), os.path.join(page_dir, "style.css"))
    revs = sorted({r.get("git_revision", "") for rows in mats.values() for r in rows if r.get("git_revision")})
    every, heads = answer_rows(results, mats)
    parts = ['<!DOCTYPE html><html lang="en"><head><meta charset="utf-8">',
             '<title>gibench reproduction report</title><link rel="stylesheet" href="style.css"></head><body>',
             '<h1>gibench reproduction report</h1>',
             answer_html(results, page_dir, heads, lone_components(mats, heads), claims),
             f'<p class="source">Generated from the CSVs in <code>{esc(os.path.basename(os.path.abspath(results)))}/</code>: '
             f'{len(mats)} matrices, {sum(len(v) for v in mats.values())} rows; revisions '
             f'{esc(", ".join(revs) or "unknown")}.</p>',
             '<pre id="image-check"></pre><pre id="animation-check"></pre><pre id="compare-check"></pre>',
             '<nav><a href="#answer">Answer</a> · <a href="#claims-h">Claims</a> · '
             + ('<a href="#energy">Energy audit</a> · ' if energy else '') + '<a href="#gallery">Gallery</a> · '
             + ('<a href="#sequences">Sequences</a> · ' if seq_rows else '') +
             '<a href="#reading">Reading the numbers</a> · <a href="#all-answers">Every group</a> · '
             + " · ".join(f'<a href="#m-{esc(m)}">{esc(m)}</a>' for m in mats) + '</nav>',
             f'<h2 id="claims-h">Claims ({len(claims)}: {esc(summary_counts(claims))})</h2>',
             '<p>A verdict is <i>not measurable here</i> where the paper measured absolute times on its '
             'GPU (ours ran on the renderer shown), where our run did not run or ran out of memory, or '
             'where our settings differ from the paper\'s (quick profile).</p>',
             claims_html(claims),
             energy_audit.section_html(energy), pass_work.section_html(results),
             gpu_runs_html(results, page_dir),
             gallery_html(results, page_dir, mats, heads),
             sequences_html(results, page_dir, seq_rows),
             cone_report.section_html(results),
             '<h2 id="reading">How to read the numbers</h2><ul>'
             + "".join(f"<li>{esc(x)}</li>" for x in reading_guide(results, mats)) + '</ul>',
             '<h2 id="all-answers">The answer for every group: each size, camera, instant and reference setting</h2>',
             '<details class="all-answers"><summary>every group two or more techniques estimate '
             f'({len(every)})</summary>' + answer_table_html(every, page_dir, results, "answers-all") + '</details>',
             '<h2>Matrices</h2>',
             '<p>Each row: reference, technique and false-colour error map side by side; the RMSE with the '
             'reference\'s own noise beside it (an error near that noise cannot rank techniques).</p>']
    parts += [matrix_html(results, page_dir, m, rows, plots[m], time_resolution(results))
              for m, rows in mats.items()]
    with open(os.path.join(HERE, "report_compare.js")) as f:
        compare_js = f.read()
    parts.append(f"<script>{CHECK_SCRIPT}</script><script>{compare_js}</script></body></html>")
    path = os.path.join(page_dir, "index.html")
    with open(path, "w") as f:
        f.write("\n".join(parts) + "\n")
    return path


# ---- Markdown -------------------------------------------------------------------------------------

def md(text):
    return str(text).replace("|", "\\|").replace("\n", " ")


def answer_table_md(entries, cls="answers"):
    lines = ["| component | scene | size | least error for its time: the Pareto front, cheapest first (ms, "
             f"{ERROR_WORDS}) | for its memory (MB, the same) | worse than black | |",
             "|---|---|---|---|---|---|---|"]
    many = len({e["key"][5] for e in entries}) > 1
    for e in entries:
        key, t = e["key"], e["time"]
        size = (size_label(key, t, many)
                + (f" (also {', '.join(other_text(k, key) for k in e['others'])})" if e["others"] else ""))
        links = ([f"[plot]({e['plot']})"] if e["plot"] else []) + (["[images](#gallery)"] if cls == "answers" else [])
        beaten = beaten_list(t)
        lines.append("| " + " | ".join(md(x) for x in (key[0], key[1], size,
                                                          front_plain(t) + (f" (beaten: {beaten})" if beaten else ""),
                                                          front_plain(e["memory"], memory=True), black_list(t),
                                                          " ".join(links))) + " |")
    return lines


def claims_md(claims, with_renderer=True):
    lines, paper = [], None
    for c in claims:
        if c["paper"] != paper:
            paper = c["paper"]
            lines += ["", f"#### {paper}", "", "| claim | paper | ours | renderer | verdict | reason |",
                      "|---|---|---|---|---|---|"]
        lines.append("| " + " | ".join(md(c[k]) for k in ("claim", "paper_value", "our_value", "renderer",
                                                              "verdict", "reason")) + " |")
    return lines


def gallery_md(results, mats, heads):
    lines = ["## Gallery: each technique at a common cost", "",
             "Per component and scene, the reference and each technique's setting whose time is nearest the "
             "group's median time, at the scene's one exposure, error maps beneath (FLIP maps share one scale, "
             "0–1; an RMS error map is scaled to its own 99th percentile). An image this folder does not hold "
             "reads *not written here*.", ""]

    def cell(path, what):
        if path and os.path.exists(path):
            return f"![{what}]({rel(path, results)})"
        return f"*{what}: not written here*"
    for e in heads:
        cells = gallery_cells(results, e["time"]["rows"])
        lines += [f"### {e['key'][0]}, {e['key'][1]} {size_text(e['key'])}", "",
                  "| " + " | ".join(md(c[0]) for c in cells) + " |", "|" + "---|" * len(cells),
                  "| " + " | ".join(cell(c[2], c[0]) for c in cells) + " |",
                  "| " + " | ".join(md(c[1]) for c in cells) + " |",
                  "| " + " | ".join(cell(c[3], "error map") if c[3] else "" for c in cells) + " |", ""]
    return lines


def first_screen_md(results, mats, claims, heads):
    lines = ["# gibench reproduction report", "", "## Which technique for which effect", "",
             " ".join(renderer_sentences(heads)) + " A step → has clearly less error than the one before "
             "it; ≈ is a tie (error intervals overlap): either will do.", ""]
    lines += answer_table_md(heads)
    lone = lone_components(mats, heads)
    if lone:
        lines += ["", "Estimated by one technique only, so no comparison: " + "; ".join(
            f"{c} ({', '.join(t)})" for c, t in sorted(lone.items())) + "."]
    lines += ["", "## Findings per paper", ""]
    for f in answers.findings(claims):
        title, sentences = findings_text(f)
        lines += [f"**{title}**. " + " ".join(sentences), ""]
    return lines


def write_md(results, claims, mats, plots, seq_rows=(), energy=()):
    every, heads = answer_rows(results, mats)
    mi, orders, absolute = split_claims(claims)
    lines = first_screen_md(results, mats, claims, heads)
    lines += ["Generated from the CSVs in this folder; the page with every row's images is "
              "[report/index.html](report/index.html). Below: the claims, the gallery, how to read the "
              "numbers, the answer for every group, every matrix, and at the end the papers' "
              "absolute GPU times.", "",
              f"## Claims ({len(claims)}: {summary_counts(claims)})", "", TOLERANCE_NOTE, "",
              f"### Claims that do not depend on the machine ({len(mi)}: {summary_counts(mi)})"]
    lines += claims_md(mi)
    lines += ["", f"### Orders of times, on the renderer named ({len(orders)}: {summary_counts(orders)})", "",
              ORDERS_NOTE]
    lines += claims_md(orders)
    lines += ["", f"The papers' {sum(len(v) for v in absolute.values())} absolute GPU times are at the end "
              "([The papers' absolute GPU times](#the-papers-absolute-gpu-times)).", ""]
    lines += energy_audit.section_md(energy)
    lines += pass_work.section_md(results)
    lines += gallery_md(results, mats, heads)
    lines += sequences_md(seq_rows)
    lines += cone_report.section_md(results)
    lines += ["## How to read the numbers", ""] + [f"- {x}" for x in reading_guide(results, mats)]
    lines += ["", "## The answer for every group: each size, camera, instant and reference setting", ""] + answer_table_md(every, "answers-all")
    lines += ["", "## Matrices", ""]
    resolution = time_resolution(results)
    for m, rows in mats.items():
        lines += matrix_md(results, m, rows, plots[m], resolution)
    lines += ["## The papers' absolute GPU times", ""]
    for paper, cs in absolute.items():
        lines += [f"### {paper}", "", why_not_comparable(cs), ""] + claims_md(cs)[3:] + [""]
    lines += gpu_runs_md(results)
    path = os.path.join(results, "REPORT.md")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    return path


GPU_RUNS_TEXT = ("Matrices run on a GPU (harness/device/run_on_nvidia.sh), each summary beside the "
                 "papers' tables, with the machine, driver and clocks it ran at")


def gpu_runs(results):
    """The runs on a GPU: results/gpu/<gpu>/SUMMARY.md (harness/reporting/gpu_summary.py), by name."""
    paths = sorted(glob.glob(os.path.join(results, "gpu", "*", "SUMMARY.md")))
    return [(os.path.basename(os.path.dirname(p)), p) for p in paths]


def gpu_runs_md(results):
    runs = gpu_runs(results)
    if not runs:
        return []
    return (["## On a GPU", "", GPU_RUNS_TEXT + ":", ""]
            + [f"- [{name}](gpu/{name}/SUMMARY.md)" for name, _ in runs] + [""])


def gpu_runs_html(results, page_dir):
    runs = gpu_runs(results)
    if not runs:
        return ""
    links = ", ".join(f'<a href="{esc(rel(p, page_dir))}">{esc(name)}</a>' for name, p in runs)
    return f'<h3 id="gpu-runs">On a GPU</h3><p>{esc(GPU_RUNS_TEXT)}: {links}.</p>'


def matrix_md(results, m, rows, plots, resolution):
    rank = group_ranks(rows, resolution)
    lines = [f"### {m}", ""]
    lines += [f"![{p[:-4]}](plots/{p})" for p in plots if "_memory" not in p and "_sweep_" not in p]
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
            r["scene"], r["technique"], r["component"], f"{r['width']}x{r['height']} {r.get('profile', '')}", r["params"],
            time_text(r), fmt(r.get("first_frame_ms")),
            f"{fmt(r.get('rmse'))} ({fmt(r.get('ref_noise_rmse'))})", error_text(r), black_text(r),
            f"{rk[0]}, {rk[1]}" if rk[0] or rk[1] else "",
            fmt(r.get("rel_rmse")), fmt(r.get("ssim")), r["status"], imgs)) + " |")
    lines.append("")
    return lines


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
                   "harness/reporting/bench_timing.py): two medians closer than that are a tie (rank 'n=').")
    else:
        out.append("The timing benchmark (harness/reporting/bench_timing.py) has not been run into this folder: no "
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
        sys.exit("usage: python3 -m reporting.report RESULTS_DIR")
    results = sys.argv[1]
    claims_path = os.path.join(results, "claims.csv")
    if not os.path.exists(claims_path):
        sys.exit(f"report.py: {claims_path} not found: run harness/reporting/claims.py {results} first (make plots)")
    claims = read_csv(claims_path)
    missing = [c for c in CLAIM_COLUMNS if claims and c not in claims[0]]
    if missing:
        sys.exit(f"report.py: {claims_path}: columns {', '.join(missing)} missing")
    mats = matrices(results)
    mark_stale(mats)
    plots = plots_of(results, list(mats))
    seq_path, seq_rows = temporal_tables.write(results)
    if seq_rows:
        print(seq_path)
        for name, why in sorted(temporal_tables.animations(results).items()):
            if why:
                print(f"report.py: no animation {name}: {why}", file=sys.stderr)
    energy_path, energy = energy_audit.write(results)
    print(energy_path)
    print(write_md(results, claims, mats, plots, seq_rows, energy))
    print(write_html(results, claims, mats, plots, seq_rows, energy))
    shipped_images.prune(results)


if __name__ == "__main__":
    main()
