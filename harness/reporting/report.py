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
from reporting import external  # noqa: E402
from reporting import shipped_images  # noqa: E402
from reporting import gpu_rows  # noqa: E402
from reporting.gpu_summary import RASTER_LIMITS  # noqa: E402
from reporting import cone_report  # noqa: E402
from reporting import energy_audit  # noqa: E402
from reporting import pass_work  # noqa: E402
from reporting import temporal_tables  # noqa: E402
from reporting import report_model as M  # noqa: E402

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


def reported(r, column, text, note=external.TIMES):
    """A time or memory figure as shown; where r is an external renderer's, said to be the program's
    own (its timings.json: not gibench's timer queries nor its memory ledger), or that the program
    reported none."""
    if not external.is_external(r):
        return text
    value = fnum(r.get(column))
    return f"{text} ({note})" if value is not None and (value or column != "mem_bytes") else f"not {external.TIMES}"


def row_numbers(r, rank=("", "")):
    """(label, value) pairs shown with each row; the reference's noise beside every error. A failed
    external renderer's row has none: its status and message are its result (external.FAILURES)."""
    if external.failed(r):
        return []
    noise = fmt(r.get("ref_noise_rmse"))
    out = [("GPU ms (warm median)", reported(r, "gpu_ms_median", time_text(r))),
           ("first frame ms", reported(r, "first_frame_ms", fmt(r.get("first_frame_ms")),
                                       f"{external.TIMES}, else the command's wall time")),
           ("CPU ms", reported(r, "cpu_ms", fmt(r.get("cpu_ms")))),
           ("memory MB", reported(r, "mem_bytes", fmt(float(r["mem_bytes"]) / 1e6)) if r.get("mem_bytes") else ""),
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
    """One technique's step of a front: 'lrsm 168–204 ms 1.62 mean 0.81–0.94 (9 settings)'; an
    external renderer's named with its program and version, its cost said to be the program's own:
    'ext:x (external, render.py 1.0) 156 ms (reported by the program) 0.02 mean 1.00'."""
    tech = external.label(cands[0][0]) if external.is_external(cands[0][0]) else tech
    costs = [c[2][1] for c in cands]
    errs = [err_text(shown_error(c[0]), digits) for c in cands]
    cost = span_text(costs, mb_text) + " MB" if memory else span_text(costs, ms_text) + " ms"
    cost += external.times_note(cands[0][0])
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


def front_nodes(ans, memory=False):
    """A front as inline nodes: each step its text, its settings its title on the page."""
    parts = front_parts(ans, memory)
    if not parts:
        return [M.Em("none better than a black image")] if ans["black"] else []
    return [x for j, t, p in parts for x in (j, M.Span(t, cls="step", title=p))]


def beaten_list(ans):
    """The techniques compared whose every usable setting another row beats (not worse than black)."""
    on = {c[0]["technique"] for c in ans["front"]}
    usable = {c[0]["technique"] for c in answers.candidates(ans["rows"], answers.time_cost, None)[0]}
    names = external.labels(ans["rows"])
    return ", ".join(names.get(t, t) for t in sorted(usable - on))


def black_list(ans):
    """'ldm_indirect ×3, vct': the techniques with rows worse than a black image (settings counted)."""
    counts = {}
    for r in answers.distinct(ans["black"]):
        counts[r["technique"]] = counts.get(r["technique"], 0) + 1
    names = external.labels(ans["rows"])
    return ", ".join(names.get(t, t) + (f" ×{n}" if n > 1 else "") for t, n in sorted(counts.items()))


def unranked_list(ans):
    """'ext:x (external, x.py 1) timeout': the external renderers of the group that the front cannot
    rank, each with its status (the message is in its matrix's section), or `no time reported`
    where its program wrote no timings.json; '' where there are none."""
    out = {}
    for r in ans["rows"]:
        if external.failed(r):
            out.setdefault(external.label(r), set()).add(r["status"])
        elif external.is_external(r) and r.get("status") == "ok" and fnum(r.get("gpu_ms_median")) is None:
            out.setdefault(external.label(r), set()).add(f"no time {external.TIMES}")
    return "; ".join(f"{t} {', '.join(sorted(st))}" for t, st in sorted(out.items()))


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
                comps.setdefault(r["component"], set()).add(external.label(r))
    answered = {h["key"][0] for h in heads}
    return {c: sorted(t) for c, t in comps.items() if c not in answered}


ANSWER_COMPONENTS = ("ao", "direct", "indirect", "glossy", "caustic")


def mark_stale(mats):
    """Rows whose technique's sources changed since they ran (their technique_hash, or for rows
    written before the column their revision's, differs from the sources' now: gpu_rows.Hashes)
    get status `stale`: the answers leave them out, the tables show them as such. An external
    renderer's row has no sources here: it is stale where its table holds a newer version of the
    same external (external.superseded), never by a hash."""
    hashes = gpu_rows.Hashes()
    for rows in mats.values():
        old = external.superseded(rows)
        for r in rows:
            if r.get("status") != "ok" or not r.get("technique"):
                continue
            if external.is_external(r):  # no sources here: current by its version (external.py)
                if id(r) in old:
                    r["status"] = "stale"
                    r["message"] = (f"{r['technique']} version {external.version(r)} was superseded by version "
                                    f"{old[id(r)]} in this table (an external renderer is current by its version)")
            elif not hashes.is_current(r):
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
    ext = sorted({(r["technique"], external.reported_renderer(r)) for h in heads for r in h["time"]["rows"]
                  if external.is_external(r) and r.get("status") == "ok"})
    if ext:
        out.append("An external renderer's times and memory (" + ", ".join(
            t + (f" on {rend}" if rend else "") for t, rend in ext) + f") are {external.TIMES} in its "
            "timings.json, not gibench's GL timer queries nor its memory ledger; its errors are gibench's, "
            "against the same references; it ranks beside the built-ins of the run it ran in (the same machine).")
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
        note = external.times_note(r)  # an external's time and memory: the program's own
        nums = (f"{ms_text(fnum(r['gpu_ms_median']))} ms{note} · {what} {err_text(shown_error(r))}"
                + (f" · mean {mean:.2f}" if mean is not None else "")
                + (f" · {mb_text(fnum(r['mem_bytes']))} MB{note}" if fnum(r.get("mem_bytes")) else "")
                + (" · WORSE THAN BLACK" if worse_than_black(r) else ""))
        cells.append((external.label(r), nums, shipped_images.shipped(results, base + ".png"),
                      shipped_images.shipped(results, emap), scale, r["params"]))
    return cells


# ---- the page's scripts and widget -----------------------------------------------------------------------------------------

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


def summary_counts(claims):
    counts = {}
    for c in claims:
        counts[c["verdict"]] = counts.get(c["verdict"], 0) + 1
    return ", ".join(f"{n} {v}" for v, n in sorted(counts.items()))


GPU_RUNS_TEXT = ("Matrices run on a GPU (harness/device/run_on_nvidia.sh), each summary beside the "
                 "papers' tables, with the machine, driver and clocks it ran at")


def gpu_runs(results):
    """The runs on a GPU: results/gpu/<gpu>/SUMMARY.md (harness/reporting/gpu_summary.py), by name."""
    paths = sorted(glob.glob(os.path.join(results, "gpu", "*", "SUMMARY.md")))
    return [(os.path.basename(os.path.dirname(p)), p) for p in paths]


# ---- the document: built once, rendered to REPORT.md and to the page (report_model.py) ------------

ANSWER_HEAD = ("component", "scene", "size", "least error for its time: the Pareto front, cheapest first (ms, "
               f"{ERROR_WORDS})", "for its memory (MB, the same)")


def answer_table(entries, cls):
    """One row per group: component and scene (on the page each once per run of rows), the size with
    the links to its plot and gallery, the front by time with the techniques it beats and the rows
    worse than black beneath, the front by memory."""
    rows, prev, many = [], None, len({e["key"][5] for e in entries}) > 1
    for e in entries:
        key, t = e["key"], e["time"]
        links = ([M.Link("plot", e["plot"])] if e["plot"] else []) + \
            ([M.Link("images", "#" + e["anchor"], md_href="#gallery")] if cls == "answers" else [])
        also = ([M.Span("also " + ", ".join(other_text(k, key) for k in e["others"]), cls="also", block=True)]
                if e["others"] else [])
        beaten, black, unranked = beaten_list(t), black_list(t), unranked_list(t)
        front = (front_nodes(t) + ([M.Span(f"beaten: {beaten}", cls="beaten", block=True)] if beaten else [])
                 + ([M.Span(f"worse than black: {black}", cls="black", block=True)] if black else [])
                 + ([M.Span(f"not ranked: {unranked}", cls="unranked", block=True)] if unranked else []))
        rows.append(M.Row([M.Cell(key[0], header=True), key[1],
                           [M.Span(size_label(key, t, many), cls="size")] + [x for l in links for x in (" ", l)] + also,
                           M.Cell(front, title="compared: " + ", ".join(
                               external.labels(t["rows"]).get(x, x) for x in t["techniques"])),
                           front_nodes(e["memory"], memory=True)],
                          cls="answer" + (" first" if key[0] != prev else ""),
                          attrs={"data-component": key[0], "data-scene": key[1], "data-size": size_text(key)}))
        prev = key[0]
    return M.Table(ANSWER_HEAD, rows, cls=cls, merge=[0, 1])


def matrix_section(results, name, rows, plots, resolution):
    """A matrix: its plots (speed against error first), then per row its names, status, settings,
    numbers (row_numbers) and images: reference, technique, error map, FLIP map. The page shows each
    row as a block with its images, collapsed under the matrix's counts; Markdown a table row per row,
    the images linked."""
    img_dir = os.path.join(results, "images", name)
    rank = group_ranks(rows, resolution)
    ok = sum(1 for r in rows if r["status"] == "ok")
    renderers = sorted({r.get("renderer", "") for r in rows if r.get("renderer") and not external.is_external(r)})
    renderers += sorted({f"{r['technique']} on {external.reported_renderer(r)} ({external.TIMES})" for r in rows
                         if r["status"] == "ok" and external.reported_renderer(r)})
    cards = []
    for r in rows:
        figures = []
        ref, n = reference_png(img_dir, r)
        if ref:
            figures.append(M.Figure(rel(ref, results), "reference"))
        base = os.path.join(img_dir, r.get("image") or image_name(r))
        if not os.path.exists(base + ".png"):
            figures.append(M.Span(f"no images of this row in images/{name}/ (run with images)", cls="noimg", block=True))
        elif not ref:
            figures.append(M.Span(f"reference: {n} candidate images (the CSV does not name which)", cls="noimg",
                                  block=True))
        figures += [M.Figure(rel(base + suffix + ".png", results), caption)
                    for suffix, caption in (("", "technique"), ("_error", "error map"), ("_flip", "FLIP map"))
                    if os.path.exists(base + suffix + ".png")]
        cards.append(M.Card(
            [r["scene"], external.label(r), r["component"], f'{r["width"]}x{r["height"]}', f'{r.get("profile", "")} profile',
             f't={r["time"]}' if r.get("time") not in ("", "0", None) else ""],
            r["status"],
            [M.Span(r["params"], cls="params", block=True)]
            + ([M.Span(r["message"], cls="message", block=True)] if r.get("message") else []),
            row_numbers(r, rank.get(id(r), ("", ""))), figures, cls=f'row status-{r["status"]}'))
    plot_box = [M.Box([M.Figure(f"plots/{p}", p[:-4], cls="plot") for p in plots], cls="plots")] if plots else []
    return M.Details([M.Strong(name), f" — {len(rows)} rows, {ok} ok; {', '.join(renderers)}"],
                     plot_box + [M.Cards(cards, ("scene", "technique", "component", "size", "profile", "instant"),
                                         "settings", "images")],
                     cls="matrix", id=f"m-{name}", md_title=name, md_level=3)


CLAIM_HEAD = ("claim", "paper", "ours", "renderer", "cores", "verdict", "reason")


def claim_rows(claims, by_paper=True):
    """A table row per claim, each paper's rows after a row naming it with its counts."""
    out, paper = [], None
    for c in claims:
        if by_paper and c["paper"] != paper:
            paper = c["paper"]
            mine = [x for x in claims if x["paper"] == paper]
            out.append(M.GroupRow([paper, " ", M.Span(f"({summary_counts(mine)})", cls="counts")], cls="paper"))
        cells = [c["claim"], c["paper_value"], c["our_value"], c["renderer"], c["cores"],
                 M.Cell(c["verdict"], cls="verdict"), M.Cell(M.More(c["reason"]))]
        out.append(M.Row(cells, cls=f'claim {VERDICT_CLASS.get(c["verdict"], "na")}'))
    return out


def absolute_claims(absolute):
    """Each paper's absolute GPU times, collapsed on the page (Markdown: a heading per paper)."""
    return [M.Details([M.Strong(paper), f": {len(cs)} times. {why_not_comparable(cs)}"],
                      [M.Only(M.MD, M.Para(why_not_comparable(cs))),
                       M.Table(CLAIM_HEAD, claim_rows(cs, by_paper=False), cls="claims-abs")],
                      cls="absolute", md_title=paper, md_level=3) for paper, cs in absolute.items()]


def claims_section(claims):
    """The claims that do not depend on the machine (memory, error, leaks) in one table, the orders
    of times (judged on the renderer named) in another; each paper's absolute GPU times follow on
    the page, collapsed, and in Markdown at the end (absolute_claims)."""
    mi, orders, absolute = split_claims(claims)
    n = sum(len(v) for v in absolute.values())
    return [M.Heading(2, f"Claims ({len(claims)}: {summary_counts(claims)})", id="claims-h"),
            M.Para(["A verdict is ", M.Em("not measurable here"), " where the paper measured absolute "
                    "times on its GPU (ours ran on the renderer shown), where our run did not run or ran out "
                    "of memory, or where our settings differ from the paper's (quick profile)."]),
            M.Para(TOLERANCE_NOTE, cls="policy"),
            M.Heading(3, f"Claims that do not depend on the machine ({len(mi)}: {summary_counts(mi)})", id="claims-mi"),
            M.Table(CLAIM_HEAD, claim_rows(mi), id="claims"),
            M.Heading(3, f"Orders of times, on the renderer named ({len(orders)}: {summary_counts(orders)})",
                      id="claims-orders"),
            M.Para(ORDERS_NOTE),
            M.Table(CLAIM_HEAD, claim_rows(orders), id="claims-orders-table"),
            M.Only(M.HTML, [M.Heading(3, f"The papers' absolute GPU times ({n}), per paper", id="claims-abs")]
                   + absolute_claims(absolute)),
            M.Only(M.MD, M.Para([f"The papers' {n} absolute GPU times are at the end (",
                                 M.Link("The papers' absolute GPU times", "#the-papers-absolute-gpu-times"), ")."]))]


def first_screen(mats, claims, heads):
    """Which technique for which effect, beside what each paper's claims came to."""
    lone = lone_components(mats, heads)
    answer = [M.Heading(2, "Which technique for which effect", id="answer"),
              M.Para([" ".join(renderer_sentences(heads)) + " A step → has clearly less error than the one "
                      "before it; ≈ is a tie (error intervals overlap): either will do.",
                      M.Raw(" Hover a step for its settings.", [])]),
              answer_table(heads, "answers")]
    if lone:
        answer.append(M.Para("Estimated by one technique only, so no comparison: " + "; ".join(
            f"{c} ({', '.join(t)})" for c, t in sorted(lone.items())) + "."))
    findings = [M.Heading(2, "Findings per paper", id="findings")]
    for f in answers.findings(claims):
        title, sentences = findings_text(f)
        findings.append(M.Para([M.Strong(title), ". " + " ".join(sentences)], cls="finding"))
    return M.Box([M.Box(answer, cls="answer-col"), M.Box(findings, cls="findings-col")], cls="first-screen")


def gallery_table(results, cells):
    """One group's cells: captions, images, their numbers and settings, error maps and their scale."""
    def media(path, caption):
        return M.Media(rel(path, results) if path else None, caption, bool(path and os.path.exists(path)))
    return M.Table([M.Cell(c[0], header=True) for c in cells], [
        M.Row([media(c[2], c[0]) for c in cells]),
        M.Row([M.Cell([c[1]] + ([M.More(c[5], summary="settings")] if c[5] else []), cls="nums") for c in cells]),
        M.Row([[media(c[3], "error map") if c[3] else "", M.Span(c[4], cls="scale", block=True)] for c in cells])],
        cls="gallery")


def gallery_section(results, page_dir, heads):
    """Per headline group, the reference and each technique's row at a common cost side by side (at
    the scene's one exposure), their numbers beneath, then their error maps: the LRSM paper's Fig. 7;
    on the page each group's comparison widget beneath."""
    out = [M.Heading(2, "Gallery: each technique at a common cost", id="gallery"),
           M.Para(["Per component and scene, the reference and each technique's setting whose time is nearest "
                  "the group's median time, at the scene's one exposure, error maps beneath (FLIP maps share one "
                  "scale, 0–1; an RMS error map is scaled to its own 99th percentile). An image this folder "
                  "does not hold reads ", M.Em("not written here"), "."])]
    if not any(os.path.isdir(os.path.join(results, d)) for d in ("images", shipped_images.FOLDER)):
        out.append(M.Para([M.Strong("This folder holds no images"), f" ({os.path.basename(os.path.abspath(results))}"
                           "/images/ is written by a run, not committed): each cell names the file it would show."]))
    for e in heads:
        cells = gallery_cells(results, e["time"]["rows"])  # a GPU-timed group's rows: timed copies of llvmpipe's
        key = e["key"]
        out.append(M.Box([M.Heading(3, f"{key[0]}, {key[1]} {size_text(key)}"), gallery_table(results, cells),
                          M.Raw(compare_html(cells, page_dir), [])], cls="gallery", id=e["anchor"], tag="section"))
    return out


def sequences_section(results, seq_rows):
    """Each sequence's numbers and its animation (on the page: checked by ?check; Markdown: linked)."""
    if not seq_rows:
        return []
    rows = []
    for r in seq_rows:
        anim = os.path.join(results, "animations", r["animation"]) if r["animation"] else ""
        cap = f"{r['scene']} {r['technique']} {r['component']}: reference | technique | error"
        media = M.Media(rel(anim, results) if anim else None, cap, bool(anim and os.path.exists(anim)),
                        attrs={"class": "animation", "data-frames": r["sequence"],
                               "data-width": 3 * 2 * int(r["width"]), "data-height": 2 * int(r["height"])},
                        md_link="webp")
        rows.append(M.Row([r["scene"], r["technique"], r["component"],
                           M.Cell(M.More(r["params"], keep=60), cls="params")] + list(sequence_cells(r)) + [media]))
    return [M.Heading(2, "Sequences: error over time", id="sequences"), M.Para(sequences_intro()),
            M.Table(list(SEQ_HEAD) + ["animation"], rows, id="sequences-table")]


def gpu_runs_section(results):
    """The runs on a GPU, each linking its summary."""
    runs = gpu_runs(results)
    if not runs:
        return []
    links = [x for name, p in runs for x in (", ", M.Link(name, rel(p, results)))][1:]
    return [M.Heading(2, "On a GPU", id="gpu-runs"), M.Para([GPU_RUNS_TEXT + ": "] + links + ["."])]


def navigation(mats, seq_rows, energy):
    """The page's links to its sections and to each matrix."""
    names = ["Answer", "Claims"] + (["Energy audit"] if energy else []) + ["Gallery"] + \
        (["Sequences"] if seq_rows else []) + ["Reading the numbers", "Every group"]
    hrefs = ["#answer", "#claims-h"] + (["#energy"] if energy else []) + ["#gallery"] + \
        (["#sequences"] if seq_rows else []) + ["#reading", "#all-answers"]
    links = [(n, h) for n, h in zip(names, hrefs)] + [(m, f"#m-{m}") for m in mats]
    return M.Raw("<nav>" + " · ".join(f'<a href="{esc(h)}">{esc(n)}</a>' for n, h in links) + "</nav>", [])


def preamble(results, mats, seq_rows, energy):
    """Where the numbers come from: on the page with the checks' outputs and the navigation, in
    Markdown with the way to the page."""
    revs = sorted({r.get("git_revision", "") for rows in mats.values() for r in rows if r.get("git_revision")})
    return [M.Only(M.HTML, [
                M.Para(["Generated from the CSVs in ", M.Code(os.path.basename(os.path.abspath(results)) + "/"),
                        f": {len(mats)} matrices, {sum(len(v) for v in mats.values())} rows; revisions "
                        f"{', '.join(revs) or 'unknown'}."], cls="source"),
                M.Raw('<pre id="image-check"></pre><pre id="animation-check"></pre><pre id="compare-check"></pre>', []),
                navigation(mats, seq_rows, energy)]),
            M.Only(M.MD, M.Para(["Generated from the CSVs in this folder; the page with every row's images is ",
                                 M.Link("report/index.html", "report/index.html"), ". Below: the claims, the "
                                 "gallery, how to read the numbers, the answer for every group, every matrix, and "
                                 "at the end the papers' absolute GPU times."]))]


def document(results, claims, mats, plots, seq_rows=(), energy=()):
    """The whole report as model nodes, for both formats."""
    page_dir = os.path.join(results, "report")
    every, heads = answer_rows(results, mats)
    resolution = time_resolution(results)
    _, _, absolute = split_claims(claims)
    return ([M.Heading(1, "gibench reproduction report"), first_screen(mats, claims, heads)]
            + preamble(results, mats, seq_rows, energy) + claims_section(claims)
            + [M.Raw(energy_audit.section_html(energy), energy_audit.section_md(energy)),
               M.Raw(pass_work.section_html(results), pass_work.section_md(results)),
               M.Only(M.HTML, gpu_runs_section(results))]
            + gallery_section(results, page_dir, heads) + sequences_section(results, seq_rows)
            + [M.Raw(cone_report.section_html(results), cone_report.section_md(results)),
               M.Heading(2, "How to read the numbers", id="reading"), M.Bullets(reading_guide(results, mats)),
               M.Heading(2, "The answer for every group: each size, camera, instant and reference setting",
                         id="all-answers"),
               M.Details(f"every group two or more techniques estimate ({len(every)})",
                         [answer_table(every, "answers-all")], cls="all-answers", md_level=0),
               M.Heading(2, "Matrices"),
               M.Para("Each row: reference, technique and false-colour error map side by side; the RMSE with the "
                      "reference's own noise beside it (an error near that noise cannot rank techniques).")]
            + [matrix_section(results, m, rows, plots[m], resolution) for m, rows in mats.items()]
            + [M.Only(M.MD, [M.Heading(2, "The papers' absolute GPU times")] + absolute_claims(absolute)
                      + gpu_runs_section(results))])


def write_report(results, claims, mats, plots, seq_rows=(), energy=()):
    """REPORT.md and report/index.html (with its style sheet beside it) from one document."""
    nodes = document(results, claims, mats, plots, seq_rows, energy)
    md_path = os.path.join(results, "REPORT.md")
    with open(md_path, "w") as f:
        f.write(M.to_markdown(nodes))
    page_dir = os.path.join(results, "report")
    os.makedirs(page_dir, exist_ok=True)
    shutil.copyfile(os.path.join(HERE, "report_style.css"), os.path.join(page_dir, "style.css"))
    with open(os.path.join(HERE, "report_compare.js")) as f:
        compare_js = f.read()
    page = ['<!DOCTYPE html><html lang="en"><head><meta charset="utf-8">',
            '<title>gibench reproduction report</title><link rel="stylesheet" href="style.css"></head><body>',
            M.to_html(nodes), f"<script>{CHECK_SCRIPT}</script><script>{compare_js}</script></body></html>"]
    html_path = os.path.join(page_dir, "index.html")
    with open(html_path, "w") as f:
        f.write("\n".join(page) + "\n")
    return md_path, html_path


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
               + (": " + "; ".join(sorted({f"{r['matrix']} {r['scene']} {external.label(r)} {r['component']}"
                                           for r in worse})[:12]) + (" ..." if len(worse) > 12 else "")
                  if worse else "") + ".")
    out.append("The RMSE without the noise takes the reference's own noise out of the error "
               "(sqrt(rmse^2 - noise^2)) with a 95% interval (metrics.h, gib_rmse_interval); rows whose "
               "intervals overlap share a rank ('n='): a tie, not an order.")
    out.append(f"{noisy} of {len(ok)} ok rows ({100 * noisy / max(len(ok), 1):.1f}%) are ref_noisy (the "
               "reference's noise above a fifth of the row's error even after its samples were raised "
               "to rank its rows, up to ref_spp_growth times the matrix's).")
    ext = [r for rows in mats.values() for r in rows if external.is_external(r)]
    if ext:
        failed = sum(1 for r in ext if external.failed(r))
        out.append(f"{len(ext)} rows are external renderers' (" + ", ".join(sorted({external.label(r) for r in ext}))
                   + "; README.md, \"Bring your own renderer\"): gibench ran the program on the scene and scored "
                   "its image against the same reference as the built-ins', so its error ranks as theirs; its "
                   f"times, memory and renderer are {external.TIMES} (its timings.json), not gibench's GL timer "
                   "queries nor its memory ledger, and rank beside the built-ins of the run it ran in. An "
                   "external is current by its version: a table's rows of an older version of it are stale. "
                   f"{failed} failed (" + "/".join(external.FAILURES) + "): the status and its message are "
                   "the row's result, no number.")
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
    for path in write_report(results, claims, mats, plots, seq_rows, energy):
        print(path)
    shipped_images.prune(results)


if __name__ == "__main__":
    main()
