"""The LDM paper's (Aalund et al. 2015) claims, judged on our rows: `claims(results, paper)` returns
them as claim.Claim objects (the claim, the paper's value and ours, the verdict and the evidence as
its reason), which claims.py gathers into claims.csv. The orders of times (Figs. 9 and 10) are of
kind time_order, the rest machine-independent; the paper's absolute times are ldm_tables.py's.

The rules (the choices this file makes, stated once):
- Fig. 8, accuracy: at every dmax of ours >= the figure's 1280 (large dmax), LDM AO is closer to the
  reference than HBAO when its RMSE interval (uncertainty.error_interval: the reference's noise
  taken out) lies wholly below HBAO's. Overlapping intervals are a tie, and a tie is not a win.
- Fig. 9, trading quality for time: a pair of LDM runs differing in one setting (ldm_res, or the
  number of directions) trades when the smaller setting is faster (medians apart by more than the
  machine's time resolution, uncertainty.compare_times) and less accurate (RMSE intervals apart).
  A claim per scene and setting holds when every such pair trades.
- Fig. 10 and Sec. 5.2, the passes: the shares of the frame by pass on Sponza, at the run closest to
  the paper's settings. Splatting "a majority of the render time": the splat pass against all the
  other passes of the frame together, at the pass time resolution (a tie is no majority); the
  LDM tracing "relatively cheap": photon_trace below splat at that resolution. The paper's own
  per-pass shares cannot be formed: its frame totals were in the figure's image, not its text.
- Figs. 8-10, memory at the paper's own settings (512 LDMs of 200^2 and 50^2): the LDMs' plan
  (matrix ldm_memory, structure "ldm" of mem_planned_by_structure) against the paper's MB
  (decimal), reproduced within claim.MEMORY_TOLERANCE: a list node per fragment, so memory follows the depth
  complexity of the scene as modelled and framed, which differs between their Sponza and ours
  (and our hairball is a procedural stand-in).
"""
import re

from reporting.claim import (LDM, MACHINE_INDEPENDENT, MEMORY_TOLERANCE, NOT_MEASURABLE, TIME_ORDER,  # noqa: E402
                             Claim, verdict)
from reporting.schema import params, passes_of, run_key, runs, runs_table  # noqa: E402
from reporting.uncertainty import compare_times, error_interval, fnum, overlap, time_resolution  # noqa: E402

LARGE_DMAX = 1280.0  # the figure's dmax (Sponza is in cm: "1280 m" is 1280 units)
SCENE = {"Crytek Sponza": "sponza", "Hairball": "hairball"}


def claim(source, figure, text, paper_value, our_value, holds, evidence, renderer="", kind=MACHINE_INDEPENDENT):
    """A claim of Figure `figure`, judged on the runs table `source`; holds True / False, or a text:
    why it is not measurable here (the evidence, where there is some, after it)."""
    if isinstance(holds, str):
        return Claim(LDM, source, f"Figure {figure}: {text}", kind, paper_value, our_value, renderer,
                     verdict=NOT_MEASURABLE, reason=holds + ("; " + evidence if evidence else ""))
    return Claim(LDM, source, f"Figure {figure}: {text}", kind, paper_value, our_value, renderer,
                 verdict=verdict(holds), reason=evidence)


def interval_text(iv):
    return f"{iv[1]:.4g} [{iv[0]:.4g}, {iv[2]:.4g}]"


def closest(rows):
    """The run closest to the paper's LDM settings: the most directions, then resolution."""
    def key(r):
        p = params(r)
        return (p.get("directions", 0), p.get("ldm_res", 0), p.get("photon_res", 0), int(r["width"]))
    return max(rows, key=key) if rows else None


# ---- Figure 8: accuracy at large dmax -----------------------------------------------------------

def fig8_accuracy(results):
    rows = runs_table(results, "ldm_fig8", ok_only=True)
    by = {}
    for tech in ("ldm_ao", "hbao"):
        for d in {params(r).get("dmax") for r in rows if r["technique"] == tech}:
            by[(tech, d)] = closest([r for r in rows if r["technique"] == tech and params(r).get("dmax") == d])
    large = sorted(d for t, d in by if t == "ldm_ao" and d is not None and d >= LARGE_DMAX
                   and ("hbao", d) in by)
    if not large:
        return [claim("ldm_fig8.csv", "8", "LDM AO closer to the reference than HBAO at large dmax", "LDM closer", "",
                      "no run of ours has both at dmax >= 1280 (ldm_fig8 not run)", "")]
    return [fig8_at(by[("ldm_ao", d)], by[("hbao", d)], d) for d in large]


def fig8_at(ldm, hbao, d):
    a, b = error_interval(ldm), error_interval(hbao)
    tie = overlap(a, b)
    win = not tie and a[1] < b[1]
    why = ("the intervals overlap: a tie, not a win" if tie else
           "LDM's interval lies wholly below HBAO's" if win else "HBAO's interval lies below LDM's")
    return claim("ldm_fig8.csv", "8", f"LDM AO closer to the reference than HBAO at large dmax (dmax={d:g}, the figure's "
                 f"{LARGE_DMAX:g} or more)", "LDM resembles the reference, HBAO fails (Fig. 8, Sec. 5.1)",
                 f"RMSE LDM {a[1]:.4g}, HBAO {b[1]:.4g}", win,
                 f"RMSE with the reference's noise taken out: LDM {interval_text(a)} vs HBAO "
                 f"{interval_text(b)}: {why}", ldm["renderer"])


# ---- Figure 9: fewer, low-resolution LDMs trade quality for time --------------------------------

def trade_pairs(rows, axis):
    """(smaller, larger) pairs of runs that differ in `axis` alone, adjacent in it."""
    groups = {}
    for r in rows:
        p = params(r)
        other = tuple(sorted((k, v) for k, v in p.items() if k != axis))
        groups.setdefault((r["scene"], r["width"], r["height"], other), []).append(r)
    out = []
    for g in groups.values():
        g.sort(key=lambda r: params(r).get(axis, 0))
        out += list(zip(g, g[1:]))
    return out


def pair_trades(lo, hi, resolution):
    """(trades, evidence) for a pair: the smaller setting faster and less accurate."""
    t = compare_times(fnum(lo["gpu_ms_median"]), fnum(hi["gpu_ms_median"]), resolution)
    a, b = error_interval(lo), error_interval(hi)
    worse = not overlap(a, b) and a[1] > b[1]
    p, q = params(lo), params(hi)
    what = f"N={p.get('directions', 0):g} ldm_res={p.get('ldm_res', 0):g} vs N={q.get('directions', 0):g} " \
           f"ldm_res={q.get('ldm_res', 0):g}"
    return t == "<" and worse, (f"{what}: {float(lo['gpu_ms_median']):.4g} vs {float(hi['gpu_ms_median']):.4g} ms "
                                f"({'faster' if t == '<' else 'a tie' if t == 'tie' else 'slower'}), RMSE "
                                f"{interval_text(a)} vs {interval_text(b)} "
                                f"({'less accurate' if worse else 'a tie' if overlap(a, b) else 'more accurate'})")


def fig9_trade(results):
    rows = runs(runs_table(results, "ldm_fig9", ok_only=True))
    res = time_resolution(results)
    out = []
    for scene in sorted({r["scene"] for r in rows}):
        mine = [r for r in rows if r["scene"] == scene]
        for axis, word in (("ldm_res", "lower-resolution"), ("directions", "fewer")):
            pairs = trade_pairs(mine, axis)
            if not pairs:
                continue
            judged = [pair_trades(lo, hi, res) for lo, hi in pairs]
            n = sum(ok for ok, _ in judged)
            out.append(claim("ldm_fig9.csv", "9", f"{word} LDMs are faster and less accurate ({scene})",
                             "quality traded for time with fewer low-resolution LDMs (Sec. 5.1)",
                             f"{n} of {len(judged)} pairs trade", n == len(judged),
                             "; ".join(e for _, e in judged) + (f"; times tie within {100 * res:.0f}% "
                             "(the machine's resolution)" if res else "; no timing resolution measured: "
                             "no time called a tie"), mine[0]["renderer"], TIME_ORDER))
    return out or [claim("ldm_fig9.csv", "9", "fewer low-resolution LDMs trade quality for time", "", "",
                         "no pair of runs of ours (ldm_fig9 not run)", "", kind=TIME_ORDER)]


# ---- Figure 10: the passes' shares of the frame -------------------------------------------------

def fig10_passes(results, paper):
    rows = [r for r in runs(runs_table(results, "ldm_fig10", ok_only=True)) if r["scene"] == "sponza"]
    passes = passes_of(results, "ldm_fig10")
    best = closest([r for r in rows if passes.get(run_key(r))])
    if not best:
        return [claim("ldm_fig10.csv", "10", "splatting a majority of the render time, LDM tracing cheap", "", "",
                      "no Sponza run of ours with pass times (ldm_fig10 not run)", "", kind=TIME_ORDER)]
    ms = passes[run_key(best)]
    total = sum(ms.values())
    share = {k: v / total for k, v in ms.items()}
    res = time_resolution(results, "pass")
    split = ", ".join(f"{k} {100 * v:.1f}%" for k, v in sorted(share.items(), key=lambda kv: -kv[1]))
    splat, trace = ms.get("splat", 0.0), ms.get("photon_trace", 0.0)
    rest = total - splat
    majority = compare_times(splat, rest, res) == ">"
    cheap = compare_times(trace, splat, res) == "<"
    routine = total - ms.get("ldm_build", 0.0) - ms.get("ldm_count", 0.0)
    where = ""
    if routine:
        alone = compare_times(splat, routine - splat, res)
        where = (f"; without the LDM construction (Fig. 7's 'unlisted pass' before the routine) splat is "
                 f"{100 * splat / routine:.1f}% and photon_trace {100 * trace / routine:.1f}% (splat against "
                 f"the rest: {'a majority' if alone == '>' else 'a tie' if alone == 'tie' else 'a minority'})")
    note = f"pass times tie within {100 * res:.0f}% (the machine's pass resolution)" if res else \
        "no timing resolution measured: no time called a tie"
    traced = "; ".join(f"{r['note'].split(';')[0]} {r['ms']} ms" for r in paper if r["figure"] == "10")
    return [
        claim("ldm_fig10.csv", "10", "Sec. 5.2: splatting is the bottleneck, a majority of the render time",
              "splat > half the frame", f"splat {100 * share.get('splat', 0):.1f}% of the frame",
              majority, f"shares of the frame: {split}{where}; {note}", best["renderer"], TIME_ORDER),
        claim("ldm_fig10.csv", "10", "Sec. 5.2: the LDM (photon) tracing relatively cheap next to splatting",
              "photon_trace < splat", f"photon_trace {trace:.4g} ms vs splat {splat:.4g} ms",
              cheap, f"{split}; {note}", best["renderer"], TIME_ORDER),
        claim("ldm_fig10.csv", "10", "caption: photon tracing's share of the frame",
              f"photon tracing {traced}; frame totals not in the text", f"photon_trace "
              f"{100 * share.get('photon_trace', 0):.1f}% of the frame",
              "the paper's frame totals were in the figure's image, lost with it: no share of the "
              "paper's to compare with", f"shares of the frame: {split}", best["renderer"])]


# ---- Figures 8-10: memory at the paper's settings -----------------------------------------------

def plan_of(r):
    """{'bytes', 'heads', 'nodes', 'fragments'} of a run's planned LDMs (None if it planned none)."""
    m = re.search(r"(?:^|;)ldm=(\d+)", r.get("mem_planned_by_structure") or "")
    if not m:
        return None
    out = {"bytes": int(m.group(1))}
    for k, pat in (("heads", r"heads (\d+)"), ("nodes", r"nodes (\d+)"), ("fragments", r"for (\d+) fragments")):
        f = re.search(pat, r.get("message", ""))
        out[k] = int(f.group(1)) if f else None
    return out


def planned_ldm(results, scene, directions, ldm_res, technique="ldm_ao"):
    """The plan of the LDMs at these settings (matrix ldm_memory): technique's row, else any
    technique's (the LDMs are the same); None when no row planned them."""
    rows = [r for r in runs(runs_table(results, "ldm_memory")) if r["scene"] == scene
            and params(r).get("directions") == directions and params(r).get("ldm_res") == ldm_res]
    rows.sort(key=lambda r: r["technique"] != technique)
    for r in rows:
        p = plan_of(r)
        if p:
            return dict(p, row=r)
    return None


def memory_claim(pr, fig, plan, ratio_note):
    n, res, mb = int(pr["ldm_count"]), int(pr["ldm_res"]), float(pr["mb"])
    what = f"{pr['scene']}: {n} LDMs of {res}^2 take {pr['mb']} MB"
    if not plan:
        return claim("ldm_memory.csv", fig, what, f"{pr['mb']} MB", "", "no plan of ours at these settings (matrix "
                     "ldm_memory not run, or its row planned nothing)", "")
    ours = plan["bytes"] / 1e6
    ok = abs(ours / mb - 1) <= MEMORY_TOLERANCE
    heads = 4 * n * res * res
    ev = [f"ours {ours:.1f} MB = {ours / mb:.2f}x the paper's (tolerance {100 * MEMORY_TOLERANCE:.0f}%)"]
    if plan["fragments"]:
        ev.append(f"{plan['fragments']} fragments, {plan['fragments'] / (n * res * res):.2f} a map pixel, "
                  f"8 B a node + 4 B a head (heads {heads / 1e6:.2f} MB)")
        ev.append(f"the paper's {pr['mb']} MB would hold {(mb * 1e6 - heads) / 8 / (n * res * res):.2f} 8-byte "
                  f"nodes a pixel, or {(mb * 1e6 - heads) / 12 / (n * res * res):.2f} 12-byte ones (its node "
                  "layout is not stated)")
    if ratio_note:
        ev.append(ratio_note)
    if pr["scene"] == "Hairball":
        ev.append("our hairball is a procedural stand-in (288k triangles, theirs 2.88M)")
    ev.append("planned, not allocated (memory_budget_mb)")
    return claim("ldm_memory.csv", fig, what, f"{pr['mb']} MB", f"{ours:.1f} MB", ok, "; ".join(ev), plan["row"]["renderer"])


def memory_claims(results, paper):
    rows = [pr for pr in paper if pr["mb"] and pr["ldm_count"] and pr["ldm_res"]]
    plans, out, seen = {}, [], set()
    for pr in rows:
        key = (pr["figure"], pr["scene"], pr["ldm_count"], pr["ldm_res"], pr["mb"])
        if key in seen:
            continue  # Fig. 10's two views: one memory
        seen.add(key)
        tech = "ldm_indirect" if pr["effect"].startswith("indirect") else "ldm_ao"
        plan = planned_ldm(results, SCENE.get(pr["scene"], pr["scene"]), float(pr["ldm_count"]),
                           float(pr["ldm_res"]), tech)
        plans[key] = (pr, plan)
    for key, (pr, plan) in plans.items():
        out.append(memory_claim(pr, pr["figure"], plan, scaling_note(pr, plan, plans.values())))
    return out


def scaling_note(pr, plan, all_plans):
    """Where the paper gives the same scene at two LDM resolutions: both figures' ratio against the
    ratio of their pixels, and ours."""
    for other, oplan in all_plans:
        if other["scene"] == pr["scene"] and other["ldm_count"] == pr["ldm_count"] and \
                int(other["ldm_res"]) > int(pr["ldm_res"]):
            px = (int(other["ldm_res"]) / int(pr["ldm_res"])) ** 2
            ours = f", ours {oplan['bytes'] / plan['bytes']:.2f}x" if plan and oplan else ""
            ratio = float(other["mb"]) / float(pr["mb"])
            return (f"the paper's {other['mb']} MB at {other['ldm_res']}^2 is {ratio:.2f}x "
                    f"its {pr['mb']} MB at {pr['ldm_res']}^2 for {px:g}x the pixels{ours}: lists of a node per "
                    "fragment grow with the pixels, so no one node size gives both of the paper's figures")
    return ""


def judged(results, paper):
    """Every judged claim of the LDM paper, in the order of its figures (Claims)."""
    return fig8_accuracy(results) + fig9_trade(results) + fig10_passes(results, paper) + \
        memory_claims(results, paper)
