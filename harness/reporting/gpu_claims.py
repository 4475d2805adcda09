"""The papers' time claims judged on a GPU: for each claim of claims.csv that a valid device run
(harness/reporting/gpu_rows.py) can answer, what that GPU measured, keyed by the claim's text.

- Orders of costs (LRSM Table 3's stages, the thesis' doubling from 128^2 to 256^2 rays and its
  multi-resolution speed-up, the LDM paper's tracing against splatting) get a verdict from the GPU's
  times, with the work the pipeline statistics counted beside it: counts follow the work asked for, not
  the machine's speed, and say whether a difference in time is a difference in work.
- Absolute times (the papers' tables) stay `not measurable here` (another GPU, and one whose raster
  work runs on a part of its chip), but show the GPU's number instead of llvmpipe's.

claims.py lays these over the papers' Claims: a claim the GPU judged takes the GPU's verdict (a
claim.py verdict), and llvmpipe's verdict moves into the reason; an order claim no GPU row answers
says it stands on llvmpipe's time alone."""
import os

from reporting import gpu_rows  # noqa: E402
from reporting import ldm_tables  # noqa: E402
from reporting import lrsm_tables  # noqa: E402
from reporting import thesis_tables  # noqa: E402
from reporting.claim import NOT_MEASURABLE, verdict  # noqa: E402
from reporting.gpu_summary import PAPER_VALUES, RASTER_LIMITS, param  # noqa: E402
from reporting.uncertainty import fnum  # noqa: E402

TIE = 0.05  # two GPU times within 5% of each other tie (their IQRs are under 1% here)



def run_key(r):
    return (r["matrix"], r["scene"], r["technique"], r["params"], r["width"], r["height"], r["time"])


def valid_passes(folder, matrix, valid_runs):
    """The passes rows of the valid runs of a matrix."""
    return [p for p in gpu_rows.read_csv(os.path.join(folder, f"{matrix}_passes.csv"))
            if (p["matrix"], p["scene"], p["technique"], p["params"], p["width"], p["height"],
                p["time"]) in valid_runs]


def work(p):
    """The invocations a pass row counted (fragment and compute), or None."""
    f, c = fnum(p.get("fragment_invocations")), fnum(p.get("compute_invocations"))
    return None if f is None and c is None else (f or 0) + (c or 0)


def order(a_ms, b_ms):
    """'>' when a is clearly above b (beyond TIE), '<' clearly below, 'tie' otherwise."""
    if abs(a_ms - b_ms) <= TIE * max(a_ms, b_ms):
        return "tie"
    return ">" if a_ms > b_ms else "<"


def counts_text(a_name, a, b_name, b):
    wa, wb = work(a), work(b)
    if wa is None or wb is None:
        return "work not counted"
    return (f"work counted: {a_name} {wa:,.0f} invocations ({a.get('kind')}) vs {b_name} "
            f"{wb:,.0f} ({b.get('kind')}); a loop inside an invocation (a cone's steps, a VPL sum) "
            "is not counted")


def table3_orders(folder, passes):
    """LRSM Table 3's stage orders at the paper's settings (1280x720), the paper's reading deciding
    and the defaults beside."""
    by = {}
    for p in passes:
        res = param(p, "voxel_res")
        if (p["technique"], res) in (("lrsm", "512"), ("vct", "256")):
            by[(p["technique"], param(p, "preset") or "default", p["pass"])] = p
    specs = [("Table 3: " + text, a, b) for text, a, b in lrsm_tables.TABLE3_CLAIMS]
    out = {}
    for text, (ta, pa), (tb, pb) in specs:
        parts, judged = [], None
        for preset in ("paper", "default"):
            a, b = by.get((ta, preset, pa)), by.get((tb, preset, pb))
            if not a or not b:
                continue
            am, bm = float(a["ms_median"]), float(b["ms_median"])
            o = order(am, bm)
            if preset == "paper":
                judged = verdict(o == ">")
            parts.append(f"preset {preset}: {ta} {pa} {am:.2f} ms {o} {tb} {pb} {bm:.2f} ms; "
                         + counts_text(pa, a, pb, b))
        if parts:
            out[text] = {"verdict": judged, "our_value": parts[0].split(";")[0],
                         "evidence": "judged on the paper's reading (preset paper), 1280x720; " + " | ".join(parts)}
    return out


def table3_times(passes):
    """Table 3's absolute stage times: this GPU's, each preset."""
    stage = {"diffuse_cones": "diffuse_cones", "specular_cone": "specular_cone"}
    out = {}
    for p in passes:
        method = {("lrsm", "512"): "LRSM", ("vct", "256"): "VCT"}.get((p["technique"], param(p, "voxel_res")))
        if not method:
            continue
        text = f"Table 3: {method} {stage.get(p['pass'], p['pass'])} time"
        out.setdefault(text, []).append(f"{float(p['ms_median']):.2f} ms ({param(p, 'preset') or 'default'}, "
                                        f"{p.get('kind', '')})")
    return {k: {"our_value": "; ".join(v)} for k, v in out.items()}


def ldm_orders(passes):
    """Sec. 5.2: the LDM (photon) tracing relatively cheap next to splatting, on Sponza at the
    paper's settings (512 directions, 800x800)."""
    by = {(p["scene"], p["pass"]): p for p in passes if p["technique"] == "ldm_indirect"
          and param(p, "directions") == "512"}
    a, b = by.get(("sponza", "photon_trace")), by.get(("sponza", "splat"))
    if not a or not b:
        return {}
    am, bm = float(a["ms_median"]), float(b["ms_median"])
    return {"Figure 10: Sec. 5.2: the LDM (photon) tracing relatively cheap next to splatting":
            {"verdict": verdict(order(am, bm) == "<"),
             "our_value": f"photon_trace {am:.2f} ms vs splat {bm:.2f} ms",
             "evidence": f"sponza {a['width']}x{a['height']}: photon_trace {am:.2f} ms vs splat {bm:.2f} ms; "
                         + counts_text("photon_trace", a, "splat", b)}}


GATHER_CLAIM = ("multi-resolution gathering much cheaper than rsm_gather (>= 2x at the largest image "
                "size run) at a small error cost (rel RMSE <= +0.05 or +25%)")


def gather_speedup(results, passes):
    """The multi-resolution speed-up: time from the GPU at its largest image size (splitting +
    gathering + upsampling against rsm_gather's gathering, same VPLs), error from the llvmpipe rows
    of the same matrix (the device run scores nothing)."""
    sums = {}
    for p in passes:
        if p["technique"] == "multires_ir" and p["pass"] in thesis_tables.MULTIRES_SCREEN_PASSES or \
                p["technique"] == "rsm_gather" and p["pass"] == thesis_tables.RSM_GATHERING:
            k = (p["scene"], int(p["width"]), p["technique"])
            ms, w = sums.get(k, (0.0, 0.0))
            sums[k] = (ms + float(p["ms_median"]), w + (work(p) or 0))
    if not sums:
        return {}
    top = max(w for _, w, _ in sums)
    ratios, parts = [], []
    for scene in sorted({s for s, _, _ in sums}):
        m, g = sums.get((scene, top, "multires_ir")), sums.get((scene, top, "rsm_gather"))
        if m and g and m[0] > 0:
            ratios.append(g[0] / m[0])
            parts.append(f"{scene} {top}^2: rsm_gather gathering {g[0]:.2f} ms / multires_ir {m[0]:.2f} ms = "
                         f"{g[0] / m[0]:.2f}x (fragments counted {g[1]:,.0f} vs {m[1]:,.0f})")
    errs = []
    for r in gpu_rows.read_csv(os.path.join(results, "thesis_gather_cost.csv")):
        if r.get("profile") == "paper" and r.get("status") == "ok" and r.get("component") == "indirect":
            errs.append(r)
    good = []
    if errs:
        big = max(int(r["width"]) for r in errs)
        by = {(r["scene"], r["technique"]): fnum(r["rel_rmse"]) for r in errs if int(r["width"]) == big}
        for scene in sorted({s for s, _ in by}):
            em, eg = by.get((scene, "multires_ir")), by.get((scene, "rsm_gather"))
            if em is not None and eg is not None:
                ok = em - eg <= thesis_tables.ERR_ABS or em <= eg * (1 + thesis_tables.ERR_REL)
                good.append(ok)
                parts.append(f"{scene} error on llvmpipe at {big}^2: rel RMSE {em:.3f} vs {eg:.3f}")
    if not ratios:
        return {}
    fast = all(x >= thesis_tables.SPEEDUP_MIN for x in ratios)
    return {GATHER_CLAIM: {"verdict": verdict(bool(fast and good and all(good))),
                           "our_value": f"{min(ratios):.2f}-{max(ratios):.2f}x at {top}^2",
                           "evidence": "; ".join(parts)}}


def thesis_claims(folder, valid_runs):
    """The ray-doubling claim and the absolute frame times of the thesis' tables."""
    path = os.path.join(PAPER_VALUES, "thesis_tables.csv")
    if not os.path.exists(path):
        return {}
    paper = thesis_tables.thesis_rows(path)
    recs, matched, _ = thesis_tables.rows_for(folder, paper)
    out = {}
    c = thesis_tables.claim_ray_doubling(matched, paper)
    if c.verdict != NOT_MEASURABLE:
        out[c.claim] = {"verdict": c.verdict, "our_value": "", "evidence": c.reason}
    for r in recs:
        if r.get("status") == "ok" and r.get("our_frame_ms"):
            what = (f"Table {r['table']} {r['paper_scene']}: {r['resolution']}^2 image, "
                    f"{r['caustic_photons']} photons, {r['ray_resolution']}^2 rays, t={r['time_s']}: frame time")
            out[what] = {"our_value": f"{r['our_frame_ms']} ms"}
    return out


def ldm_times(folder):
    path = os.path.join(PAPER_VALUES, "ldm_figures.csv")
    if not os.path.exists(path):
        return {}
    out = {}
    for r in ldm_tables.ldm_rows(folder, path):
        if r.get("our_ms"):
            out[f"Figure {r['figure']} {r['scene']} {r['method']} ({r['paper_settings']}): time"] = \
                {"our_value": f"{float(r['our_ms']):.1f} ms, {r.get('our_mb', '')} MB"}
    return out


def judged(results):
    """{claim text: {verdict (claim.py's, for an order; None where the paper's preset did not run),
    our_value, evidence}} with the run's renderer
    and raster limit in every entry; {} without a valid device run."""
    run = gpu_rows.newest_run(results)
    if not run:
        return {}
    gpu, folder, rows = run
    valid_runs = {run_key(r) for r in rows if r["_valid"]}
    renderer = next((r["renderer"] for r in rows), gpu)
    limit = next((f"{k}: {v}" for k, v in RASTER_LIMITS.items() if k in renderer), "")
    out = {}
    stages = valid_passes(folder, "lrsm_stages", valid_runs)
    out.update(table3_times(stages))
    out.update(table3_orders(folder, stages))
    out.update(ldm_orders(valid_passes(folder, "ldm_fig10", valid_runs)))
    out.update(thesis_claims(folder, valid_runs))
    out.update(gather_speedup(results, valid_passes(folder, "thesis_gather_cost", valid_runs)))
    out.update(ldm_times(folder))
    revs = ", ".join(sorted({r["git_revision"] for r in rows}))
    for v in out.values():
        v.update(renderer=renderer, limit=limit, run=f"{os.path.relpath(folder, results)} ({revs})")
    return out
