#!/usr/bin/env python3
"""harness/answers.py on constructed rows with known answers: the Pareto set over error and time,
ties at the machine's time resolution and where error intervals overlap, rows worse than a black
image set apart, memory ties only on equal bytes, and groups split by renderer and image size."""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "harness"))
import answers  # noqa: E402

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
check(keys == [("indirect", "cornell", "0", "64", "64", "llvmpipe")],
      f"only the group two techniques estimate ({keys})")

print("FAIL" if failures else "PASS", f"{len(failures)} failure(s)")
sys.exit(1 if failures else 0)
