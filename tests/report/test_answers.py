#!/usr/bin/env python3
"""harness/reporting/answers.py on constructed rows with known answers: the Pareto set over error and time,
ties at the machine's time resolution and where error intervals overlap, rows worse than a black
image set apart, memory ties only on equal bytes, and groups split by renderer and image size; the
front's technique segments, the headline group per component and scene, each technique's row at a
common cost (the gallery's), and the claims: kind (absolute GPU time or not), findings per paper,
a claim tested at several settings counted once, and what a front shows (report.shown_error)."""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "harness"))
from reporting import answers  # noqa: E402
from reporting import claims  # noqa: E402
from reporting import claim as claim_mod  # noqa: E402
from reporting.claim import Claim  # noqa: E402
from reporting import report  # noqa: E402

failures = []


def check(ok, what):
    print(("PASS " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)


def row(tech, ms, err, half=0.01, mem=1000, black=2.0, params="", **kw):
    """A row with relative error `err` +- half (reference mean 1), time ms, black RMSE `black`."""
    r = {"component": "indirect", "scene": "cornell", "camera": "0", "width": "64", "height": "64",
         "renderer": "llvmpipe", "technique": tech, "params": params, "status": "ok",
         "gpu_ms_median": str(ms), "mem_bytes": str(mem), "rmse": str(err), "rel_rmse": str(err),
         "rmse_denoised": str(err), "rmse_lo": str(err - half), "rmse_hi": str(err + half),
         "black_rmse": str(black), "rmse_over_black": str(err / black)}
    r.update(kw)
    return r


def names(ans):
    return [c[0]["technique"] for c in ans["front"]]


# fast/high error and slow/low error are both on the front; slow/high error is beaten by both.
a = answers.answer([row("fast", 1, 0.8), row("slow", 10, 0.2), row("bad", 12, 0.9)])
check(names(a) == ["fast", "slow"], f"front is fast then slow, bad beaten ({names(a)})")
check(a["least_error"] == "slow", "least error: slow")

# Times within the machine's resolution tie: 10 ms and 10.4 ms at 10% resolution; the slower row
# with overlapping error is not beaten (neither is clearly better), so both stay on the front.
a = answers.answer([row("p", 10.0, 0.50), row("q", 10.4, 0.505)], resolution=0.1)
check(names(a) == ["p", "q"] and a["ties"][0] == [1], f"time tie and error tie kept ({names(a)})")
# Without a resolution the same 4% is a difference, but the errors still overlap: q is beaten.
a = answers.answer([row("p", 10.0, 0.50), row("q", 10.4, 0.505)], resolution=None)
check(names(a) == ["p"], f"no resolution: q beaten on time at a tied error ({names(a)})")

# A row worse than a black image never enters the front, however cheap.
a = answers.answer([row("dark", 0.1, 3.0, black=2.0), row("ok", 5, 0.5)])
check(names(a) == ["ok"] and [r["technique"] for r in a["black"]] == ["dark"],
      "worse than black is set apart")

# Failed rows are left out.
a = answers.answer([row("oom", 1, 0.1, status="out_of_memory"), row("ok", 5, 0.5)])
check(names(a) == ["ok"], "a failed row is not a candidate")

# Memory: exact bytes, so 1000 and 1001 differ; equal bytes and overlapping errors tie.
a = answers.answer([row("m1", 1, 0.5, mem=1000), row("m2", 1, 0.5, mem=1001)], answers.memory_cost)
check(names(a) == ["m1"], f"memory: one byte more at the same error is beaten ({names(a)})")
a = answers.answer([row("m1", 1, 0.5, mem=1000), row("m2", 1, 0.5, mem=1000)], answers.memory_cost)
check(names(a) == ["m1", "m2"], "memory: equal bytes and error tie")

# The same setting from two matrices is one candidate.
a = answers.answer([row("x", 1, 0.5), row("x", 1.2, 0.5), row("y", 2, 0.3)])
check(names(a) == ["x", "y"], f"duplicate settings counted once ({names(a)})")

# Groups: renderers and sizes apart; a group with one technique is no question.
rows = [row("a", 1, 0.5), row("b", 2, 0.4), row("a", 1, 0.5, renderer="NVIDIA H100"),
        row("c", 1, 0.5, width="128", height="128")]
keys = [k for k, _, _ in answers.answers(rows)]
check(keys == [("indirect", "cornell", "0", "64", "64", "llvmpipe", "0", "")],
      f"only the group two techniques estimate ({keys})")

# Segments: the front cut where the technique changes.
a = answers.answer([row("a", 1, 0.9), row("a", 2, 0.7, params="x=2"), row("b", 5, 0.3), row("a", 9, 0.1, params="x=3")])
segs = [(t, len(c)) for t, c in answers.segments(a["front"])]
check(segs == [("a", 2), ("b", 1), ("a", 1)], f"segments cut where the technique changes ({segs})")

# Headline: per component and scene, the group with the most techniques, the other sizes named.
rows = [row("a", 1, 0.5), row("b", 2, 0.4), row("a", 1, 0.5, width="128", height="128"),
        row("b", 2, 0.4, width="128", height="128"), row("c", 3, 0.3, width="128", height="128")]
heads = answers.headline(answers.answers(rows))
check(len(heads) == 1 and heads[0][0][3] == "128" and [k[3] for k in heads[0][3]] == ["64"],
      f"headline: the 128 group (3 techniques), 64 named as another size ({[(h[0], h[3]) for h in heads]})")

# Headline for AO: the paper's point (dmax >= 1280) heads it, even beside a group that a GPU timed
# and more techniques estimate.
ao = dict(component="ao", scene="sponza")
rows = [row("a", 1, 0.5, params="dmax=20", time_source="gpu", **ao),
        row("b", 2, 0.4, params="dmax=20", time_source="gpu", **ao),
        row("c", 3, 0.3, params="dmax=20", time_source="gpu", **ao),
        row("a", 1, 0.5, params="dmax=1280", **ao), row("b", 2, 0.4, params="dmax=1280", **ao)]
heads = answers.headline(answers.answers(rows))
check(len(heads) == 1 and heads[0][0][7] == "dmax=1280",
      f"headline: AO at the paper's dmax 1280, not dmax 20 ({[h[0][7] for h in heads]})")

# What a front shows: glossy and caustics over a black image's RMSE, the rest relative; the mean.
g = row("a", 1, 0.6, black=3.0, component="glossy", mean_ratio="0.8")
check(abs(report.shown_error(g) - 0.2) < 1e-9, f"glossy: RMSE over black's ({report.shown_error(g)})")
check(abs(report.shown_error(row("a", 1, 0.6, black=3.0)) - 0.6) < 1e-9, "indirect: the relative RMSE")
check(report.mean_text([(g,), (dict(g, mean_ratio="0.95"),)]) == "mean 0.80–0.95", "the mean beside it")

# A common cost: each technique's row nearest the group's median time (log scale).
picked = answers.at_common_cost([row("a", 1, 0.5), row("a", 10, 0.4, params="x=2"), row("b", 8, 0.3),
                                 row("b", 100, 0.2, params="y=2")])
check([(r["technique"], r["gpu_ms_median"]) for r in picked] == [("b", "8"), ("a", "10")],
      f"at a common cost: a at 10 ms and b at 8 ms ({[(r['technique'], r['gpu_ms_median']) for r in picked]})")

# Claims: `kind` where present; else absolute times from the reason; findings count and name.
def claim(verdict, reason, kind=None, claim="Table 1 x: frame time", paper="P"):
    c = {"paper": paper, "source": "s.csv", "claim": claim, "paper_value": "1 ms", "our_value": "2 ms",
         "renderer": "llvmpipe", "cores": "2", "verdict": verdict, "reason": reason}
    if kind:
        c["kind"] = kind
    return c


check(answers.claim_kind(claim("not measurable here", "absolute time on the paper's GPU")) == "absolute_time",
      "absolute time from the reason")
check(answers.claim_kind(claim("not measurable here", "our run ended out_of_memory", claim="Table 2 memory"))
      == "machine_independent", "out of memory is not an absolute time")
check(answers.claim_kind(claim("not measurable here", "absolute", kind="machine_independent"))
      == "machine_independent", "the kind column wins")
check(answers.claim_kind(claim("not reproduced", "memory differs", claim="Table 2 memory (a)"))
      == "machine_independent", "a verdict is machine independent")
cl = [claim("reproduced", "ok", claim="order (a)"), claim("not reproduced", "differs; more", claim="leak (x=1)"),
      claim("not reproduced", "differs; more", claim="leak (x=2)"),
      claim("not measurable here", "absolute time on the paper's GPU"),
      claim("not measurable here", "not run here: no such view", claim="Table 1 y: frame time")]
f = answers.findings(cl)[0]
check(f["counts"] == {"reproduced": 1, "not reproduced": 2, "not measurable here": 2},
      f"findings count the verdicts ({f['counts']})")
check([(x[0], x[1]) for x in f["not_reproduced"]] == [("leak", 2)], f"one claim at two settings named once ({f['not_reproduced']})")
check(sorted(x[0] for x in f["unmeasured"]) == ["absolute GPU times", "not run here"],
      f"what would measure the rest ({f['unmeasured']})")

# A claim tested at several settings is counted once (claims.counted_once): it holds where every
# measured setting holds, fails where one fails, and is not measurable where none was measured;
# claims of another stem, source or kind stay apart.
def crow(verdict, text, reason="why", source="s.csv", kind="machine_independent"):
    return Claim("P", source, text, kind, "1 ms", "2 ms", "llvmpipe", "2", verdict, reason)


once = claims.counted_once([
    crow("reproduced", "leak (x=1)"), crow("not reproduced", "leak (x=2)"),
    crow("not measurable here", "leak (x=3)"), crow("reproduced", "order (a)"),
    crow("reproduced", "order (b)"), crow("not measurable here", "time [t=0]"),
    crow("not measurable here", "time [t=1]"), crow("reproduced", "leak (x=4)", source="t.csv")])
by = {(c.source, c.claim): c.row() for c in once}
check(len(once) == 4, f"eight rows, four claims ({sorted(by)})")
leak = by.get(("s.csv", "leak"), {})
check(leak.get("verdict") == "not reproduced" and
      leak.get("our_value") == "holds at 1 of 2 settings measured (1 not measurable here)",
      f"one measured setting fails: not reproduced, 1 of 2 ({leak.get('verdict')}, {leak.get('our_value')})")
check(leak.get("reason", "").count(" || ") == 2 and "(x=2) not reproduced: why" in leak.get("reason", ""),
      "each setting's verdict and reason is the evidence")
check(by.get(("s.csv", "order"), {}).get("verdict") == "reproduced", "every setting holds: reproduced")
check(by.get(("s.csv", "time"), {}).get("verdict") == "not measurable here", "none measured: not measurable")
check(by.get(("t.csv", "leak (x=4)"), {}).get("verdict") == "reproduced", "another source stays apart, as it was")
check([len(c.settings) for c in once if c.claim == "leak"] == [3], "the three settings lie beneath the one claim")

# One tolerance for memory: within 25% of the paper's figure holds (Table 2's 153.39 against 156.4
# MB), 0.69x does not (LDM's 552.6 against 805.5 MB); a figure in words is read by its number.
check(claim_mod.memory_verdict(153.39, 156.4)[0] == "reproduced", "memory 2% under the paper's holds")
check(claim_mod.memory_verdict(552.6, 805.5)[0] == "not reproduced", "memory 31% under does not")
check(claim_mod.paper_number("about 3000 (3 GB)") == 3000.0, "a figure in words read as its number")

# Ambient occlusion at two dmax estimates two images (two references): two groups, not one; so do
# two instants of an animation.
rows = [row("a", 1, 0.5, component="ao", params="dmax=1"), row("b", 2, 0.4, component="ao", params="dmax=1"),
        row("a", 1, 0.5, component="ao", params="dmax=2"), row("b", 2, 0.4, component="ao", params="dmax=2"),
        row("a", 1, 0.5, time="0.5"), row("b", 2, 0.4, time="0.5")]
keys = sorted(k[6:] for k, _, _ in answers.answers(rows))
check(keys == [("0", "dmax=1"), ("0", "dmax=2"), ("0.5", "")], f"groups split by reference parameters and time ({keys})")

print("FAIL" if failures else "PASS", f"{len(failures)} failure(s)")
sys.exit(1 if failures else 0)
