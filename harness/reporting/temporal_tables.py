#!/usr/bin/env python3
"""The sequences' tables, the papers' temporal claims and the sequences' animations
(ARCHITECTURE.md, "Metrics": "Temporal error").

usage: python3 -m reporting.temporal_tables RESULTS_DIR

Reads every runs table with the sequence columns (a matrix with `sequence` above 1: the
harness/matrices/temporal_*.matrix) and writes RESULTS_DIR/temporal_sequences.csv, a row per run and
component: the per-frame error's mean and worst frame, the temporal error and its two scales.
`claims(results)` returns the two papers' temporal claims as claim.Claim objects (claims.py writes
them into claims.csv);
`animations(results)` writes an animated WebP per sequence (reference | technique | error map, side
by side) from the frame images `gibench run` wrote, with Debian's ffmpeg.

Two ratios read the temporal error (both from the row's own numbers, so a row judges alone):
- `flicker` = temporal_rmse_denoised / (sqrt(2) x seq_rmse_denoised_mean). A technique whose error
  is the same from frame to frame (a bias that moves with the scene) changes as the reference does:
  0. One whose error is drawn anew every frame, independent between frames, scores 1 (the
  difference of two independent errors of RMSE e has RMSE sqrt(2) e). With the error split into a
  steady part and a part renewed every frame, flicker^2 is the renewed part's share of the error's
  energy.
- `over_frozen` = temporal_rmse_denoised / temporal_frozen: against a sequence that never changes
  (the temporal black image); at or above 1 the technique's changes are as wrong as standing still.

Stated thresholds (the choice this file makes):
- a row is judged only where the references' noise leaves its temporal error measurable: the noise
  a frame difference carries, sqrt(2) x ref noise, at most half the temporal RMSE measured
  (`resolved`); elsewhere `steady` is empty and a claim resting on it is not measurable here.
- "no temporal artifacts" (LRSM paper, Sec. 6, SPONZA DRAGON) holds for a component when flicker
  <= 0.5 (at most a quarter of its error's energy renewed each frame) and over_frozen < 1 (it
  follows the motion better than standing still); the claim holds when every component of lrsm
  does. vct, the paper's baseline, is judged alike beside it.
- "reusing the random numbers is steadier" (thesis, Ch. 4) holds at a photon count when the mean
  temporal_rmse_denoised over the seeds with the numbers reused is below the mean with them redrawn
  by more than either's spread over the seeds (max - min), and the claim when it holds at every
  photon count run.
"""
import math
import os
import shutil
import subprocess
import sys
import tempfile

from reporting.claim import LRSM, NOT_MEASURABLE, NOT_REPRODUCED, REPRODUCED, THESIS, Claim  # noqa: E402
from reporting.schema import fnum, fmt, matrices, param, write_csv  # noqa: E402

FLICKER_MAX, OVER_FROZEN_MAX = 0.5, 1.0

COLUMNS = ["matrix", "scene", "technique", "component", "params", "width", "height", "time", "dt",
           "sequence", "seq_rmse_mean", "seq_rmse_worst", "seq_worst_frame", "seq_rmse_denoised_mean",
           "temporal_rmse", "temporal_rmse_denoised", "temporal_peak", "temporal_frozen",
           "temporal_flip", "seq_ref_noise_rmse", "flicker", "over_frozen", "steady", "animation",
           "renderer", "status"]


def ratio(a, b):
    a, b = fnum(a), fnum(b)
    if a is None or b is None or b <= 0:
        return None
    return a / b


def flicker(r):
    e = fnum(r.get("seq_rmse_denoised_mean"))
    return ratio(r.get("temporal_rmse_denoised"), math.sqrt(2) * e if e else None)


def over_frozen(r):
    return ratio(r.get("temporal_rmse_denoised"), r.get("temporal_frozen"))


def resolved(r):
    """Whether the references' noise leaves the temporal error measurable: the noise a frame
    difference carries (sqrt(2) x a frame's) at most half the temporal RMSE measured, so at most a
    quarter of its energy is the noise taken out."""
    noise, t = fnum(r.get("seq_ref_noise_rmse")) or 0.0, fnum(r.get("temporal_rmse"))
    return t is not None and math.sqrt(2) * noise <= 0.5 * t


def steady(r):
    """'yes' / 'no' by the stated thresholds; '' where a ratio is undefined (no error, no motion)
    or the references are too noisy to tell (resolved)."""
    f, o = flicker(r), over_frozen(r)
    if f is None or o is None or not resolved(r):
        return ""
    return "yes" if f <= FLICKER_MAX and o < OVER_FROZEN_MAX else "no"


def sequence_runs(results):
    """The rows of every runs table that has the sequence columns, ok or not."""
    out = []
    for rows in matrices(results).values():
        if rows and "sequence" in rows[0]:
            out += rows
    return out


def animation_name(r):
    return f"{r['matrix']}/{r['image']}.webp" if r.get("image") else ""


def table(results):
    out = []
    for r in sequence_runs(results):
        row = {k: r.get(k, "") for k in COLUMNS}
        f, o = flicker(r), over_frozen(r)
        row.update(flicker=fmt(f), over_frozen=fmt(o), steady=steady(r) if r["status"] == "ok" else "",
                   animation=animation_name(r))
        out.append(row)
    return out


def claim(paper, source, text, paper_value, our_value, renderer, verdict, reason):
    """A temporal claim: machine-independent (errors, judged by the thresholds above)."""
    return Claim(paper, source, text, paper_value=paper_value, our_value=our_value, renderer=renderer,
                 verdict=verdict, reason=reason)


def describe(r):
    return (f"{r['component']} flicker {fmt(flicker(r), 3)}, over frozen {fmt(over_frozen(r), 3)} "
            f"(temporal RMSE {fmt(fnum(r['temporal_rmse_denoised']), 3)}, frame RMSE "
            f"{fmt(fnum(r['seq_rmse_denoised_mean']), 3)}, frozen {fmt(fnum(r['temporal_frozen']), 3)})")


def lrsm_claim(results):
    rows = [r for r in sequence_runs(results) if r["matrix"] == "temporal_lrsm_dragon"]
    text = ("SPONZA DRAGON is rendered smoothly without any temporal artifacts, every structure "
            "rebuilt every frame (Sec. 6)")
    thresholds = (f"stated thresholds: flicker <= {FLICKER_MAX} and temporal error under the frozen "
                  "scale for every component (harness/reporting/temporal_tables.py)")
    lrsm = [r for r in rows if r["technique"] == "lrsm" and param(r, "rebuild", 1.0) == 1.0]
    if not lrsm or any(r["status"] != "ok" for r in lrsm):
        why = "no sequence of lrsm on sponza_dragon ran" if not lrsm else "a run is not ok"
        return [claim(LRSM, "temporal_sequences.csv", text, "no temporal artifacts (qualitative)", "",
                      "", NOT_MEASURABLE, why)]
    verdicts = [steady(r) for r in lrsm]
    ok = all(v == "yes" for v in verdicts)
    unresolved = [r["component"] for r, v in zip(lrsm, verdicts) if v == ""]
    vct = [r for r in rows if r["technique"] == "vct" and r["status"] == "ok"]
    ours = "lrsm: " + "; ".join(describe(r) for r in lrsm)
    if vct:
        ours += " | vct: " + "; ".join(describe(r) for r in vct)
    failing = [r["component"] for r, v in zip(lrsm, verdicts) if v != "yes"]
    worst = max(over_frozen(r) or 0 for r in lrsm)
    reason = thresholds + (f": every component meets both (the closest to the frozen scale at "
                           f"{fmt(worst, 3)} of it)" if ok else ": not met by " + ", ".join(failing))
    r0 = lrsm[0]
    reason += (f"; {r0['sequence']} frames {r0['dt']} s apart ending at t = {r0['time']} s, "
               f"{r0['width']}x{r0['height']}")
    verdict = REPRODUCED if ok else NOT_REPRODUCED
    if unresolved and not [v for v in verdicts if v == "no"]:
        verdict = NOT_MEASURABLE
        reason += ("; the references' noise hides the temporal error of " + ", ".join(unresolved)
                   + ": more reference samples would tell")
    return [claim(LRSM, "temporal_sequences.csv", text, "no temporal artifacts (qualitative)", ours,
                  r0["renderer"], verdict, reason)]


def _by_level(rows):
    """{mask_level: {redraw: [temporal_rmse_denoised over seeds]}} of the ok rows."""
    out = {}
    for r in rows:
        v = fnum(r["temporal_rmse_denoised"])
        if r["status"] != "ok" or v is None:
            continue
        level = fmt(param(r, "mask_level"))
        redraw = fmt(param(r, "redraw", 0.0))
        out.setdefault(level, {}).setdefault(redraw, []).append(v)
    return out


def thesis_claim(results):
    rows = [r for r in sequence_runs(results) if r["matrix"] == "temporal_thesis_water"]
    text = ("the photons' pre-generated random numbers, reused every frame, keep the caustics "
            "temporally coherent on the animated water (Ch. 4)")
    levels = _by_level(rows)
    parts, holds = [], []
    for level in sorted(levels):
        reuse, redraw = levels[level].get("0", []), levels[level].get("1", [])
        if not reuse or not redraw:
            continue
        mr, md = sum(reuse) / len(reuse), sum(redraw) / len(redraw)
        spread = max(max(reuse) - min(reuse), max(redraw) - min(redraw))
        ok = md - mr > spread
        holds.append(ok)
        parts.append(f"mask level {level}: reused {fmt(mr, 4)}, redrawn {fmt(md, 4)} "
                     f"({fmt(100 * (md - mr) / md, 2)}% lower reused; seeds' spread {fmt(spread, 2)})")
    if not holds:
        return [claim(THESIS, "temporal_sequences.csv", text, "steadier with reuse (qualitative)", "",
                      "", NOT_MEASURABLE, "no water_room sequence with both settings ran")]
    ok = all(holds)
    reason = ("temporal_rmse_denoised, mean over seeds; stated threshold: lower with reuse by more "
              "than the seeds' spread at every photon count (harness/reporting/temporal_tables.py)")
    r0 = rows[0]
    reason += (f"; {r0['sequence']} frames {r0['dt']} s apart ending at t = {r0['time']} s, "
               f"{r0['width']}x{r0['height']}")
    if ok:
        reason += ("; the difference is small beside the temporal error itself: the caustics' "
                   "change with the water dominates what the photons' noise adds")
    flickers = [flicker(r) for r in rows if r["status"] == "ok" and flicker(r) is not None]
    if flickers:
        reason += (f"; neither setting is steady by the sequence table's threshold (flicker "
                   f"{fmt(min(flickers), 2)}-{fmt(max(flickers), 2)} > {FLICKER_MAX}): most of the "
                   "caustics' error is renewed every frame. Both settings share each frame's "
                   "reference, so its noise cancels in the comparison even where it hides the "
                   "temporal error itself (mask level 1)")
    return [claim(THESIS, "temporal_sequences.csv", text, "steadier with reuse (qualitative)",
                  "; ".join(parts), r0["renderer"], REPRODUCED if ok else NOT_REPRODUCED, reason)]


def claims(results):
    """The papers' temporal claims (Claims)."""
    return lrsm_claim(results) + thesis_claim(results)


def _frames(seq_dir, image, n):
    """The frame images' paths [(reference, technique, error)], None when one is missing."""
    out = []
    for k in range(n):
        names = [f"{image}_f{k:02d}_ref.png", f"{image}_f{k:02d}.png", f"{image}_f{k:02d}_error.png"]
        paths = [os.path.join(seq_dir, x) for x in names]
        if not all(os.path.exists(p) for p in paths):
            return None
        out.append(paths)
    return out


def animate(frames, path, fps=4):
    """An animated WebP of the frames, each reference | technique | error side by side, looping.
    Returns an error text, or '' when written."""
    ffmpeg = shutil.which("ffmpeg")
    if not ffmpeg:
        return "ffmpeg is not installed (Debian package ffmpeg)"
    with tempfile.TemporaryDirectory() as tmp:
        for k, (ref, tech, err) in enumerate(frames):
            out = os.path.join(tmp, f"{k:03d}.png")
            cmd = [ffmpeg, "-v", "error", "-y", "-i", ref, "-i", tech, "-i", err, "-filter_complex",
                   "[0][1][2]hstack=inputs=3", out]
            p = subprocess.run(cmd, capture_output=True, text=True)
            if p.returncode:
                return p.stderr.strip()
        cmd = [ffmpeg, "-v", "error", "-y", "-framerate", str(fps), "-i",
               os.path.join(tmp, "%03d.png"), "-vf", "scale=iw*2:ih*2:flags=neighbor",
               "-c:v", "libwebp_anim", "-lossless", "1", "-loop", "0", path + ".tmp.webp"]
        p = subprocess.run(cmd, capture_output=True, text=True)
        if p.returncode:
            return p.stderr.strip()
        os.replace(path + ".tmp.webp", path)
    return ""


def animations(results):
    """Writes RESULTS/animations/<matrix>/<image>.webp for every sequence row whose frames are there
    (kept when newer than its frames). Returns {animation name: error text or ''}."""
    done = {}
    for r in sequence_runs(results):
        name, n = animation_name(r), int(fnum(r.get("sequence")) or 0)
        if not name or r["status"] != "ok" or name in done:
            continue
        frames = _frames(os.path.join(results, "images", r["matrix"], "seq"), r["image"], n)
        if frames is None:
            done[name] = "the frames' images are absent"
            continue
        path = os.path.join(results, "animations", name)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        newest = max(os.path.getmtime(p) for f in frames for p in f)
        if os.path.exists(path) and os.path.getmtime(path) >= newest:
            done[name] = ""
            continue
        done[name] = animate(frames, path)
    return done


def write(results):
    rows = table(results)
    path = write_csv(os.path.join(results, "temporal_sequences.csv"), rows, COLUMNS)
    return path, rows


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: python3 -m reporting.temporal_tables RESULTS_DIR")
    path, rows = write(sys.argv[1])
    print(f"{path}: {len(rows)} sequence rows")
    for name, why in sorted(animations(sys.argv[1]).items()):
        if why:
            print(f"temporal_tables.py: no animation {name}: {why}", file=sys.stderr)
    for c in claims(sys.argv[1]):
        print(f"{c.verdict}: {c.claim}\n  ours: {c.our_value}\n  {c.reason}")


if __name__ == "__main__":
    main()
