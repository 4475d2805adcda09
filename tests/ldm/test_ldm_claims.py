#!/usr/bin/env python3
"""The papers' machine-independent claims on constructed result tables (no GL): harness/reporting/ldm_claims.py
(the LDM paper's Figs. 8-10), thesis_tables.py's list pool and claims.py's kinds and planned memory.

- Fig. 8: LDM's RMSE interval wholly below HBAO's at dmax >= 1280 is reproduced; overlapping
  intervals are a tie and not reproduced; a small dmax is not judged.
- Fig. 9: a pair of runs trades when the smaller setting is faster beyond the time resolution and
  less accurate beyond the intervals; a time within the resolution is a tie.
- Fig. 10: splatting a majority of the frame and photon tracing below splatting, from the passes.
- Memory: the plan of the LDMs (mem_planned_by_structure "ldm") against the paper's MB within 25%.
- The thesis' 20 MB list pool; Table 2's Claims (lrsm_tables.table2_claims): every one has a
  kind, a planned VCT row that matches is reproduced, a Table 2 frame time is an absolute time.

usage: test_ldm_claims.py WORK_DIR (GIBENCH_SCHEMA names `gibench schema`'s output)
"""
import os
import shutil
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "harness"))
from reporting import claims  # noqa: E402
from reporting.claim import NOT_MEASURABLE, NOT_REPRODUCED, REPRODUCED  # noqa: E402
from reporting import ldm_claims  # noqa: E402
from reporting import lrsm_tables  # noqa: E402
from reporting import schema  # noqa: E402
from reporting import thesis_tables  # noqa: E402

failures = []
PAPER = [
    {"figure": "8", "scene": "Crytek Sponza", "effect": "ao_attenuated", "method": "LDM", "ldm_count": "512",
     "ldm_res": "200", "image_res": "800", "dmax_m": "1280", "ms": "512.4", "mb": "805.5", "gpu": "G", "note": ""},
    {"figure": "9", "scene": "Crytek Sponza", "effect": "ao_unattenuated", "method": "LDM", "ldm_count": "512",
     "ldm_res": "50", "image_res": "800", "dmax_m": "", "ms": "373.0", "mb": "204.1", "gpu": "G", "note": ""},
    {"figure": "10", "scene": "Crytek Sponza", "effect": "indirect_single_bounce", "method": "LDM photon tracing",
     "ldm_count": "512", "ldm_res": "200", "image_res": "800", "dmax_m": "", "ms": "2062", "mb": "805.5",
     "gpu": "G", "note": "view (a); lost"},
]


def check(cond, what):
    print(("ok    " if cond else "FAIL  ") + what)
    if not cond:
        failures.append(what)


def run_row(matrix, scene, tech, prm, **kw):
    r = {c: "" for c in schema.columns("runs")}
    r.update({"matrix": matrix, "profile": "quick", "scene": scene, "camera": "0", "technique": tech,
              "component": "ao", "width": "64", "height": "64", "time": "0", "params": prm, "status": "ok",
              "renderer": "test"})
    r.update(kw)
    return r


def err(rmse, half=0.001):
    return {"rmse": str(rmse), "rmse_lo": str(rmse - half), "rmse_denoised": str(rmse),
            "rmse_hi": str(rmse + half), "gpu_ms_median": "100"}


def fresh(work, tables):
    results = os.path.join(work, "results")
    shutil.rmtree(results, ignore_errors=True)
    os.makedirs(results)
    with open(os.path.join(results, "timing_resolution.csv"), "w") as f:
        f.write("kind,resolution_rel\ntotal,0.2\npass,0.4\n")
    for name, (rows, table) in tables.items():
        schema.write_csv(os.path.join(results, name + ".csv"), rows, schema.columns(table))
    return results


def test_fig8(work):
    rows = [run_row("ldm_fig8", "sponza", "ldm_ao", "directions=32;ldm_res=100;dmax=1280", **err(0.05)),
            run_row("ldm_fig8", "sponza", "hbao", "dmax=1280", **err(0.5)),
            run_row("ldm_fig8", "sponza", "ldm_ao", "directions=32;ldm_res=100;dmax=5120", **err(0.100)),
            run_row("ldm_fig8", "sponza", "hbao", "dmax=5120", **err(0.1015)),
            run_row("ldm_fig8", "sponza", "ldm_ao", "directions=32;ldm_res=100;dmax=20", **err(0.3)),
            run_row("ldm_fig8", "sponza", "hbao", "dmax=20", **err(0.1))]
    out = ldm_claims.fig8_accuracy(fresh(work, {"ldm_fig8": (rows, "runs")}))
    check(len(out) == 2, f"Fig. 8: the two large dmax judged, not dmax=20 ({len(out)} claims)")
    check(out[0].verdict == REPRODUCED, "Fig. 8 dmax=1280: LDM's interval below HBAO's is reproduced")
    check(out[1].verdict == NOT_REPRODUCED and "tie" in out[1].reason,
          f"Fig. 8 dmax=5120: overlapping intervals are a tie, not a win ({out[1].reason})")


def test_fig9(work):
    def r(n, res, ms, rmse):
        return run_row("ldm_fig9", "hairball", "ldm_ao", f"directions={n};ldm_res={res};dmax=inf",
                       **dict(err(rmse), gpu_ms_median=str(ms)))
    rows = [r(8, 50, 100, 0.3), r(8, 100, 200, 0.2), r(32, 50, 380, 0.25), r(32, 100, 400, 0.15)]
    out = {c.claim: c for c in ldm_claims.fig9_trade(fresh(work, {"ldm_fig9": (rows, "runs")}))}
    res, dirs = out["Figure 9: lower-resolution LDMs are faster and less accurate (hairball)"], \
        out["Figure 9: fewer LDMs are faster and less accurate (hairball)"]
    check(res.verdict == NOT_REPRODUCED and "1 of 2" in res.our_value,
          f"Fig. 9 ldm_res: 380 vs 400 ms is a tie at 20% ({res.our_value})")
    check(dirs.verdict == REPRODUCED, f"Fig. 9 directions: both pairs trade ({dirs.reason})")


def pass_rows(run, ms):
    out = []
    for name, v in ms.items():
        p = {c: "" for c in schema.columns("passes")}
        p.update({k: run[k] for k in p if k in run})
        p.update({"pass": name, "ms_median": str(v)})
        out.append(p)
    return out


def test_fig10(work):
    run = run_row("ldm_fig10", "sponza", "ldm_indirect", "directions=64;ldm_res=64;photon_res=64",
                  component="indirect", **err(0.01))
    for ms, majority in (({"ldm_build": 900, "splat": 60, "photon_trace": 10, "gbuffer": 30}, NOT_REPRODUCED),
                         ({"ldm_build": 100, "splat": 800, "photon_trace": 50, "gbuffer": 50}, REPRODUCED)):
        results = fresh(work, {"ldm_fig10": ([run], "runs"), "ldm_fig10_passes": (pass_rows(run, ms), "passes")})
        out = ldm_claims.fig10_passes(results, PAPER)
        check(out[0].verdict == majority, f"Fig. 10 splat {ms['splat']} of {sum(ms.values())} ms: "
              f"majority {out[0].verdict} ({out[0].reason})")
        check(out[1].verdict == REPRODUCED, "Fig. 10 photon tracing below splatting")
        check(out[2].verdict == NOT_MEASURABLE, "Fig. 10 caption share: not measurable (no totals)")


def test_memory(work):
    def plan(res, total, frags):
        return run_row("ldm_memory", "sponza", "ldm_ao", f"directions=512;ldm_res={res};memory_budget_mb=1",
                       status="out_of_memory", mem_planned_by_structure=f"ldm={total}", mem_bytes="26640",
                       message=f"ldm: out of memory: 512 LDMs of {res}x{res} plan {total} bytes (heads 1, "
                               f"nodes 2 for {frags} fragments), over the 1000000 bytes")
    rows = [plan(200, 700000000, 77000000), plan(50, 34600000, 3700000)]
    out = ldm_claims.memory_claims(fresh(work, {"ldm_memory": (rows, "runs")}), PAPER)
    check(len(out) == 3, f"memory: Figs. 8, 9 and 10, one claim each ({len(out)})")
    check(out[0].verdict == REPRODUCED and out[0].our_value == "700.0 MB",
          f"memory 200^2: 700 MB within 25% of 805.5 ({out[0].our_value})")
    check(out[1].verdict == NOT_REPRODUCED and "16x the pixels" in out[1].reason,
          f"memory 50^2: 34.6 MB against 204.1, with the pixels' ratio ({out[1].reason})")
    check(out[2].our_value == "700.0 MB", "Fig. 10: ldm_ao's plan where ldm_indirect has none")


def test_thesis_pool(work):
    def r(ray, lists, status="ok", capacity=8):
        return run_row("thesis_t41_ring", "ring", "ispm_caustics",
                       f"ray_res={ray};list_capacity={capacity};layers=0",
                       component="caustic", status=status, mem_by_structure=f"gbuffer=1;lists={lists};splat=2")
    good = [r(128, 1703952), r(256, 6815760)]
    c = thesis_tables.claim_list_pool(fresh(work, {"thesis_t41_ring": (good, "runs")}))
    check(c.verdict == REPRODUCED and "6.82" in c.our_value, f"thesis list pool: {c.our_value}")
    c = thesis_tables.claim_list_pool(fresh(work, {"thesis_t41_ring": (good + [r(128, 300000, "overflow", 1)],
                                                                       "runs")}))
    check(c.verdict == NOT_REPRODUCED, f"thesis list pool with an overflow: {c.reason}")


def test_claims_kinds(work):
    cols = ["paper_scene", "technique", "structure", "setting", "paper_mb", "formula_mb", "ours_mb", "matches",
            "ours_vs_formula", "paper_vs_formula", "ours_bytes", "formula_bytes", "status", "measured", "note"]
    t2 = [dict(zip(cols, ["SPONZA (Sec. 6 text)", "vct", "vct_total", "512^3", "about 3000 (3 GB)", "3067.83",
                          "3067.83", "yes", "exact", "agrees", "1", "1", "out_of_memory", "x",
                          "planned, not allocated"])),
          dict(zip(cols, ["SPONZA", "lrsm", "frame_ms", "1280x720 in the paper", "", "", "", "", "", "", "", "",
                          "ok", "x", "paper: GTX770 58.5 ms, Iris Pro 197.4 ms; ours 527.4 ms GPU median"]))]
    t2[1].update(_paper_time="GTX770 58.5 ms", _our_time="527.4 ms")
    rows = lrsm_tables.table2_claims(t2)
    check(all(r.kind in (claims.MACHINE_INDEPENDENT, claims.ABSOLUTE_TIME, claims.TIME_ORDER) for r in rows),
          "every claim has a kind")
    vct = next(r for r in rows if "vct_total" in r.claim)
    check(vct.verdict == claims.REPRODUCED and vct.kind == claims.MACHINE_INDEPENDENT,
          f"a planned VCT total that matches is reproduced ({vct.verdict}: {vct.reason})")
    t = next(r for r in rows if "frame time" in r.claim)
    check(t.kind == claims.ABSOLUTE_TIME and t.verdict == claims.NOT_MEASURABLE,
          "Table 2's frame time is an absolute time, not measurable here")
    ldm = ldm_claims.claim("ldm_fig8.csv", "8", "x", "a", "b", True, "why")
    check(ldm.verdict == claims.REPRODUCED and ldm.kind == claims.MACHINE_INDEPENDENT,
          "an LDM claim judged true is reproduced, machine independent by default")
    missing = ldm_claims.claim("ldm_fig8.csv", "8", "x", "a", "", "no run of ours", "")
    check(missing.verdict == claims.NOT_MEASURABLE and missing.reason == "no run of ours",
          f"an LDM claim with no run is not measurable here, saying why ({missing.reason})")


def main():
    work = sys.argv[1]
    for t in (test_fig8, test_fig9, test_fig10, test_memory, test_thesis_pool, test_claims_kinds):
        t(work)
    print(f"{'FAIL' if failures else 'PASS'}: {len(failures)} failure(s)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
