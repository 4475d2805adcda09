"""The LDM paper's figures (Figures 8-10: time and memory per scene and setting,
paper-values/ldm_figures.csv) beside ours: RESULTS/ldm_figures_vs_ours.csv, written by
paper_tables.py. "Best match" is the run with the paper's settings when the profile ran them
(profile `paper`), else the run closest to them (the same scene and technique, the most directions
and resolution that ran): the `our_settings` column says which. `our_planned_mb` is the LDMs'
memory at the paper's own settings, planned (matrix ldm_memory) though not allocated.

`claims(results, paper_dir)` returns the paper's claims as claim.Claim objects, which claims.py
gathers into claims.csv: those ldm_claims.py judges (its rules), then the figures' absolute times, a
claim per row of ldm_figures_vs_ours.csv (not measurable here: the paper timed its own GPU).
"""
import os

from reporting import ldm_claims  # noqa: E402
from reporting.claim import ABSOLUTE_TIME, LDM, NOT_MEASURABLE, Claim  # noqa: E402
from reporting.ldm_claims import planned_ldm  # noqa: E402
from reporting.schema import papers_rows, params, passes_of, read_csv, run_key, runs_table, write_csv  # noqa: E402


def pass_ms(results, matrix, row, names):
    """The summed median ms of the passes `names` of row's run, "" when it has none of them."""
    ms = [v for k, v in passes_of(results, matrix).get(run_key(row), {}).items() if k in names]
    return f"{sum(ms):.6g}" if ms else ""


def closeness(row, want):
    """Sort key: exact parameter matches first, then larger settings (closer to the paper's)."""
    p = params(row)
    exact = sum(1 for k, v in want.items() if k in p and p[k] == v)
    size = int(row["width"]) * int(row["height"])
    return (exact, p.get("directions", 0), p.get("ldm_res", 0), size)


def ldm_rows(results, paper_csv):
    scene_of = {"Crytek Sponza": "sponza", "Hairball": "hairball"}
    out = []
    for pr in read_csv(paper_csv):
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
        rows = papers_rows([r for r in runs_table(results, matrix, ok_only=True)
                            if r["scene"] == scene and r["technique"] == tech])
        plan = None if tech == "hbao" else planned_ldm(results, scene, want.get("directions"),
                                                       want.get("ldm_res"), tech)
        if "dmax" in want:
            rows = [r for r in rows if params(r).get("dmax") == want["dmax"]] or rows
        best = max(rows, key=lambda r: closeness(r, want)) if rows else None
        rec = {"figure": fig, "scene": pr["scene"], "method": pr["method"], "paper_settings":
               f"N={pr['ldm_count'] or '-'} ldm_res={pr['ldm_res'] or '-'} image={pr['image_res']}"
               + (f" dmax={pr['dmax_m'] or 'inf'}" if pr["effect"].startswith("ao") else ""),
               "paper_ms": pr["ms"], "paper_mb": pr["mb"], "paper_gpu": pr["gpu"], "paper_note": pr["note"],
               "our_planned_mb": f"{plan['bytes'] / 1e6:.4g}" if plan else ""}
        if best:
            # The paper profile's images are at most 4x smaller per side than the paper's.
            exact = all(params(best).get(k) == v for k, v in want.items()) and \
                (best["width"] == pr["image_res"] or
                 (best["profile"] in ("paper", "gpu") and 4 * int(best["width"]) >= int(pr["image_res"])))
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


LDM_COLUMNS = ["figure", "scene", "method", "paper_settings", "paper_ms", "paper_mb", "paper_gpu", "paper_note",
               "our_settings", "our_ms", "our_photon_trace_ms", "our_mb", "our_planned_mb", "our_rmse",
               "our_rel_rmse", "our_ssim", "our_ref_spp", "our_renderer"]


def time_claim(r):
    """A figure's caption time (a row of ldm_rows): absolute, on the paper's GPU."""
    what = f"Figure {r['figure']} {r['scene']} {r['method']} ({r['paper_settings']}): time"
    pv = f"{r['paper_ms']} ms on {r['paper_gpu']}" + (f", {r['paper_mb']} MB" if r["paper_mb"] else "")
    ours = r.get("our_ms", "")
    ov = f"{ours} ms, {r['our_mb']} MB, rel RMSE {r['our_rel_rmse']}" if ours else ""
    if not ours:
        why = r["our_settings"]
    else:
        why = (f"absolute time on the paper's {r['paper_gpu']}; ours on {r['our_renderer']}"
               + ("; and not at the paper's settings (quick profile)" if "NOT" in r["our_settings"] else ""))
    return Claim(LDM, "ldm_figures_vs_ours.csv", what, ABSOLUTE_TIME, pv, ov, r.get("our_renderer", ""),
                 verdict=NOT_MEASURABLE, reason=why)


def claims(results, paper_dir):
    """The LDM paper's claims (Claims): the judged ones (ldm_claims.py), then the figures' times;
    [] without the paper's values (paper_dir/ldm_figures.csv)."""
    ldm = os.path.join(paper_dir, "ldm_figures.csv")
    if not os.path.exists(ldm):
        return []
    return ldm_claims.judged(results, read_csv(ldm)) + [time_claim(r) for r in ldm_rows(results, ldm)]


def ldm_table(results, paper_dir, source):
    """The LDM paper's figures beside ours: RESULTS/ldm_figures_vs_ours.csv."""
    ldm = os.path.join(paper_dir, "ldm_figures.csv")
    if not os.path.exists(ldm):
        print(f"paper_tables.py: no {ldm} (paper values not found under {source}); nothing to compare")
        return
    print("paper_tables.py: wrote", write_csv(os.path.join(results, "ldm_figures_vs_ours.csv"),
                                             ldm_rows(results, ldm), LDM_COLUMNS))
