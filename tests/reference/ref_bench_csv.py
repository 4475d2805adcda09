#!/usr/bin/env python3
"""gibench bench reference: the CSV's structure and the consistency of its statistics.

Runs the benchmark on the Cornell box at a tiny size (a second or two) and checks what every
reader of results/bench_reference.csv relies on: the header, one world_build, path_tracer,
path_tracer_embree, raw_random and raw_diffuse row, one raw_replay row per ray API and the lean
tracer's rows (lean_tracer and one lean_replay per API, paired with its own rays; component full
only), every
time and rate positive and finite, the best <= median <= worst time, least <= median <= greatest paired
ratio, mrays_per_s equal to rays / seconds (to the printed digits), the fastest replay at
exactly 1.0 of itself and every replay's paired ratio at most 1. No timing is asserted: only
that the numbers written are consistent with each other. Also: --repeat beyond 100 is refused
with the parameter named, a camera that sees no surface (hard_empty) is an error naming
the camera and scene, not a diffuse-ray figure of nothing, and a list of scenes writes one CSV
(a failing scene keeps the others' rows; a run that measures nothing keeps an earlier file).
--efficiency: its CSV's header and rows, and the reported noise within [0.75, 1.33] of the
actual error for both samplers.
Usage: ref_bench_csv.py GIBENCH WORKDIR."""
import csv
import math
import os
import re
import subprocess
import sys

HEADER = ("scene,triangles,component,width,height,spp,cores,machine,embree,measure,api,rays,"
          "seconds,mrays_per_s,vs_raw_random,vs_raw_diffuse,vs_raw_replay_best,repeats,"
          "seconds_median,seconds_max,vs_replay_paired_median,vs_replay_paired_min,"
          "vs_replay_paired_max")
APIS = ["rtcIntersect1", "rtcIntersect1M", "rtcIntersect4", "rtcIntersect8", "rtcIntersect16"]
fails = []


def check(what, ok):
    print(("ok: " if ok else "FAIL: ") + what)
    if not ok:
        fails.append(what)


gib, work = sys.argv[1], sys.argv[2]
os.makedirs(work, exist_ok=True)
out = os.path.join(work, "bench_reference.csv")
run = subprocess.run([gib, "bench", "reference", "--scene", "cornell", "--size", "24x16",
                      "--spp", "4", "--repeat", "3", "--threads", "2", "--out", out],
                     capture_output=True, text=True)
check("bench exits 0 (%s)" % run.stderr.strip()[-200:], run.returncode == 0)
with open(out) as f:
    text = f.read()
check("header", text.splitlines()[0] == HEADER)
rows = list(csv.DictReader(text.splitlines()))
measures = [(r["measure"], r["api"]) for r in rows]
check("rows: build, path tracer, Embree inside it, random, diffuse, one replay per API, the "
      "lean tracer and its replays",
      measures == [("world_build", "rtcCommitScene"), ("path_tracer", "rtcIntersect1"),
                   ("path_tracer_embree", "rtcIntersect1"), ("raw_random", "rtcIntersect1"),
                   ("raw_diffuse", "rtcIntersect1")] + [("raw_replay", a) for a in APIS]
      + [("lean_tracer", "rtcIntersect1")] + [("lean_replay", a) for a in APIS])
for r in rows[1:]:
    name = r["measure"] + "/" + r["api"]
    rays, best = int(r["rays"]), float(r["seconds"])
    med, worst = float(r["seconds_median"]), float(r["seconds_max"])
    pmed, pmin, pmax = (float(r["vs_replay_paired_" + k]) for k in ("median", "min", "max"))
    check(name + ": 3 repeats", r["repeats"] == "3")
    check(name + ": rays and times positive and finite",
          rays > 0 and all(math.isfinite(x) and x > 0 for x in (best, med, worst)))
    check(name + ": best <= median <= worst", best <= med <= worst)
    # seconds is printed to 1e-6 s and the rate to 1e-4 Mrays/s: the tolerance is their rounding
    rate = rays / best * 1e-6
    check(name + ": rate %s is rays over the best time (%.4f)" % (r["mrays_per_s"], rate),
          abs(float(r["mrays_per_s"]) - rate) <= 5e-5 + rate * 5e-7 / best * 1.01)
    check(name + ": paired least <= median <= greatest", 0 < pmin <= pmed <= pmax)
replays = [r for r in rows if r["measure"] == "raw_replay"]
fastest = max(replays, key=lambda r: float(r["mrays_per_s"]))
check("fastest replay is 1.0 of itself (best-of)", float(fastest["vs_raw_replay_best"]) == 1.0)
check("raw rows are 1.0 of themselves",
      float(rows[3]["vs_raw_random"]) == 1.0 and float(rows[4]["vs_raw_diffuse"]) == 1.0)
# Each group of replays (the path tracer's rays, the lean tracer's) is paired with its own fastest.
lean_replays = [r for r in rows if r["measure"] == "lean_replay"]
for group, reps in (("replay", replays), ("lean replay", lean_replays)):
    check("every %s's paired ratio is at most 1 (the fastest of each repeat is the reference)"
          % group, all(float(r["vs_replay_paired_max"]) <= 1.0 for r in reps))
    check("some %s is the fastest in some repeat (paired max exactly 1)" % group,
          any(float(r["vs_replay_paired_max"]) == 1.0 for r in reps))
pt = rows[1]
check("path tracer counts the same rays as the replay at this size (recorded at full size)",
      int(pt["rays"]) == int(replays[0]["rays"]))
lean = [r for r in rows if r["measure"] == "lean_tracer"][0]
check("lean tracer counts the same rays as its replay at this size (recorded at full size): "
      "%s and %s" % (lean["rays"], lean_replays[0]["rays"]),
      int(lean["rays"]) == int(lean_replays[0]["rays"]) > 0)
# The lean tracer's row is paired with its own replay: each repeat's ratio, printed to stderr,
# is one of the row's least, median and greatest (3 repeats: exactly those three, sorted).
per_rep = sorted(float(x) for x in re.findall(r"lean tracer's ([0-9.]+)", run.stderr))
row_pairs = [float(lean["vs_replay_paired_" + k]) for k in ("min", "median", "max")]
check("lean tracer's paired ratios %s are its repeats' own %s" % (row_pairs, per_rep),
      len(per_rep) == 3 and all(abs(a - b) <= 1.5e-4 for a, b in zip(per_rep, row_pairs)))
# Its paths are as long as the path tracer's (mean reflectances, the same roulette): on the
# Cornell box (no texture) the two cast the same number of rays to within the roulette's noise
# (~3,800 rays here: a few percent; 0.1% at 256x256 16 spp).
pt_rays = int(rows[1]["rays"])
check("lean tracer's rays (%s) within 5%% of the path tracer's (%d)" % (lean["rays"], pt_rays),
      abs(int(lean["rays"]) - pt_rays) <= 0.05 * pt_rays)
check("the lean tracer's summary line", "lean tracer (the same kind of paths" in run.stdout
      and "the path tracer reaches" in run.stdout)
pte = rows[2]
check("Embree inside the path tracer: the same rays as the path tracer",
      int(pte["rays"]) == int(pt["rays"]))
# At 24x16 and 4 spp a render is mostly its fixed costs (threads, buffers), so the time inside
# Embree's calls is a small part of it (~1/6 here): clock ticks left unconverted (x1e9) or a
# conversion at the wrong rate would not stay below the render's time.
check("Embree inside the path tracer: less time than the path tracer's render (%s < %s)"
      % (pte["seconds"], pt["seconds_median"]),
      0 < float(pte["seconds"]) < float(pt["seconds_median"]))
# Another component: the lean tracer traces `full`'s paths only, so it is not run (no rows).
other = os.path.join(work, "bench_direct.csv")
run = subprocess.run([gib, "bench", "reference", "--scene", "cornell", "--component", "direct",
                      "--size", "16x8", "--spp", "2", "--repeat", "1", "--out", other],
                     capture_output=True, text=True)
with open(other) as f:
    drows = list(csv.DictReader(f))
check("component direct: no lean rows, and says so (%s)" % run.stderr.strip()[-120:],
      run.returncode == 0 and len(drows) == 10
      and not any(r["measure"].startswith("lean") for r in drows)
      and "lean tracer: not run" in run.stdout)
# A scene with a sky: the lean tracer leaves out the sky's rays, so it is not run there either.
run = subprocess.run([gib, "bench", "reference", "--scene", "plane_box_sky", "--size", "16x8",
                      "--spp", "2", "--repeat", "1", "--out", other], capture_output=True, text=True)
with open(other) as f:
    srows = list(csv.DictReader(f))
check("a scene with a sky: no lean rows, and says so",
      run.returncode == 0 and len(srows) == 10 and "lean tracer: not run" in run.stdout)
# On a textured scene the lean tracer's paths must be as long as the path tracer's: it weights
# them by each material's mean reflectance (albedo x the texture's mean). Its first version used
# the untextured albedo and cast 40% more rays on Sibenik; the fix gives 15,367 against 15,508
# here. Needs the Sibenik data (../shared/scenes): skipped without it (exit status 3).
sib = os.path.join(work, "bench_sibenik.csv")
run = subprocess.run([gib, "bench", "reference", "--scene", "sibenik", "--size", "32x32", "--spp",
                      "4", "--repeat", "1", "--out", sib], capture_output=True, text=True)
if run.returncode == 3:
    print("skip: Sibenik data absent: the textured path-length check did not run")
else:
    with open(sib) as f:
        by = {r["measure"]: int(r["rays"]) for r in csv.DictReader(f)
              if r["measure"] in ("path_tracer", "lean_tracer")}
    check("Sibenik (textured): lean tracer's rays %s within 5%% of the path tracer's" % by,
          run.returncode == 0 and len(by) == 2
          and abs(by["lean_tracer"] - by["path_tracer"]) <= 0.05 * by["path_tracer"])
bad = subprocess.run([gib, "bench", "reference", "--scene", "cornell", "--repeat", "101"],
                     capture_output=True, text=True)
check("--repeat 101 refused naming the parameter",
      bad.returncode != 0 and "--repeat" in bad.stderr)
empty = subprocess.run([gib, "bench", "reference", "--scene", "hard_empty", "--size", "8x8",
                        "--spp", "2", "--repeat", "1"], capture_output=True, text=True)
check("empty view refused: " + empty.stderr.strip()[-160:],
      empty.returncode != 0 and "sees (almost) no surface" in empty.stderr
      and "hard_empty" in empty.stderr)

# A list of scenes: one CSV, each scene's rows in the order given; a scene that fails keeps the
# rows already measured; a run that measures nothing leaves an earlier file as it was.
multi = os.path.join(work, "bench_multi.csv")
run = subprocess.run([gib, "bench", "reference", "--scene", "cornell,plane_box", "--size", "16x8",
                      "--spp", "2", "--repeat", "1", "--out", multi],
                     capture_output=True, text=True)
check("two scenes exit 0 (%s)" % run.stderr.strip()[-200:], run.returncode == 0)
with open(multi) as f:
    mrows = list(csv.DictReader(f))
check("two scenes: 16 rows each, cornell's first",
      [r["scene"] for r in mrows] == ["cornell"] * 16 + ["plane_box"] * 16)
check("two scenes: a summary line per scene",
      "by scene" in run.stdout and run.stdout.count(" triangles  ") == 2)
run = subprocess.run([gib, "bench", "reference", "--scene", "cornell,no_such_scene", "--size",
                      "16x8", "--spp", "2", "--repeat", "1", "--out", multi],
                     capture_output=True, text=True)
with open(multi) as f:
    kept = [r["scene"] for r in csv.DictReader(f)]
check("an unknown scene in a list fails naming it, the other's rows kept",
      run.returncode != 0 and "no_such_scene" in run.stderr and kept == ["cornell"] * 16)
with open(multi, "w") as f:
    f.write("earlier\n")
run = subprocess.run([gib, "bench", "reference", "--scene", "no_such_scene", "--out", multi],
                     capture_output=True, text=True)
with open(multi) as f:
    check("nothing measured: the earlier file is untouched and no .part is left",
          run.returncode != 0 and f.read() == "earlier\n" and not os.path.exists(multi + ".part"))
bad = subprocess.run([gib, "bench", "reference", "--scene", ",,"], capture_output=True, text=True)
check("a --scene list of no names refused naming the parameter",
      bad.returncode == 2 and "--scene" in bad.stderr)

# --efficiency: the CSV's structure, and the renderer's own noise against the actual error
# (reported_over_actual). Cornell box indirect, 16x16, 64 spp against a 1024-spp truth, 4
# repeats: the actual MSE averages 4 x 768 squared errors (~3% spread) and the prediction as
# many variance estimates, so an honest estimate lands within [0.75, 1.33] (the truth's own
# noise, 1/16 of the tests' variance, is removed by the command). No timing is asserted.
EFF_HEADER = ("scene,triangles,component,width,height,spp,truth_spp,cores,machine,sampler,"
              "repeats,seconds_median,seconds_max,truth_mean,rel_rmse_actual,"
              "rel_noise_reported,reported_over_actual,efficiency,efficiency_reported,"
              "efficiency_vs_random")
eff = os.path.join(work, "bench_efficiency.csv")
run = subprocess.run([gib, "bench", "reference", "--efficiency", "--scene", "cornell",
                      "--component", "indirect", "--size", "16x16", "--spp", "64",
                      "--truth-spp", "1024", "--repeat", "4", "--out", eff],
                     capture_output=True, text=True)
check("--efficiency exits 0 (%s)" % run.stderr.strip()[-200:], run.returncode == 0)
with open(eff) as f:
    check("--efficiency header", f.readline().strip() == EFF_HEADER)
with open(eff) as f:
    erows = list(csv.DictReader(f))
check("--efficiency: one row per sampler, random first",
      [r["sampler"] for r in erows] == ["random", "sobol"])
for r in erows:
    ratio = float(r["reported_over_actual"])
    check("%s: reported noise / actual error %.3f within [0.75, 1.33]" % (r["sampler"], ratio),
          0.75 <= ratio <= 1.33)
    check("%s: efficiency positive and finite, spp 64, truth 1024" % r["sampler"],
          math.isfinite(float(r["efficiency"])) and float(r["efficiency"]) > 0 and
          r["spp"] == "64" and r["truth_spp"] == "1024")
check("random's efficiency_vs_random is 1", erows[0]["efficiency_vs_random"] == "1.0000")
bad = subprocess.run([gib, "bench", "reference", "--efficiency", "--sampler", "halton"],
                     capture_output=True, text=True)
check("an unknown sampler refused naming the parameter",
      bad.returncode == 2 and "--sampler" in bad.stderr and "halton" in bad.stderr)
sys.exit(1 if fails else 0)
