#!/usr/bin/env python3
"""gibench's reference (`full`) against Blender Cycles on the same closed room: time, noise and
efficiency of each, written as CSV rows (reference/PERFORMANCE.md, "Against Blender Cycles").

    python3 harness/bench_cycles/bench_cycles.py --gibench build/gibench \\
        [--also before=OTHER/gibench] [--blender blender] [--size 128x128] [--spp 256] \\
        [--scene harness/bench_cycles/closed_room.scene] [--seeds 8] [--max-depth 8] \\
        [--threads 2] [--label after] [--gibench-arg=--sampler --gibench-arg=random] \\
        [--cycles-set sampling_pattern=SOBOL] [--out results/bench_cycles.csv]

Both renderers draw the scene with K independent seeds at the same spp; each pixel's variance is
the unbiased variance of its K values (the variance of one spp-sample pixel estimate), averaged
over pixels and channels. The renders go seed by seed, each gibench binary (--also adds one, e.g.
the build before a change) then Cycles, so that a change in the machine's load (the load average
at the start is in the rows) falls on all alike. Rows per renderer:

  seconds          median render time over the seeds (gibench: its EXR header's `seconds`, the
                   BVH build included; Cycles: bpy.ops.render.render() around one render, after
                   an untimed warm-up in the same process; process start-up left out of both)
  sigma            sqrt of the mean pixel variance at spp; sigma_per_sample = sigma sqrt(spp)
  rel_variance     mean pixel variance / image mean^2 (scale-free: the two means agree within
                   the noise, mean_vs_cycles says by how much)
  efficiency       1 / (rel_variance x seconds); efficiency_vs_cycles: gibench's over Cycles'
  z_rms_vs_cycles  RMS over pixels of (mean_a - mean_b) / standard error of that difference:
                   about 1 when both converge to the same image
  direct_check     Cycles' direct light (max_bounces 0) over gibench's `direct` (exact), image
                   means: the light's power and the geometry matched

Cycles' settings (cycles_scene.py's docstring: no clamping, no denoising, no adaptive sampling,
its own sampler and Russian roulette) are in each Cycles row's `settings`. Needs Blender with
Cycles (Debian: apt-get install blender, 3.4.1); no numpy (exr_read.py reads the EXRs)."""
import argparse
import csv
import datetime
import json
import math
import os
import platform
import statistics
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from exr_read import read_exr  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
COLUMNS = ["timestamp", "label", "renderer", "version", "revision", "machine", "cores",
           "load_avg", "threads", "scene", "width", "height", "spp", "max_depth", "seeds",
           "seconds", "seconds_min", "seconds_max", "image_mean", "sigma", "sigma_per_sample",
           "rel_variance", "efficiency", "efficiency_vs_cycles", "mean_vs_cycles",
           "z_rms_vs_cycles", "direct_check", "settings"]


def machine():
    model = platform.processor() or platform.machine()
    try:
        with open("/proc/cpuinfo") as f:
            model = next(l.split(":", 1)[1].strip() for l in f if l.startswith("model name"))
    except (OSError, StopIteration):
        pass
    return model, os.cpu_count()


def git_revision():
    def git(*a):
        return subprocess.run(["git", "-C", ROOT] + list(a), capture_output=True,
                              text=True).stdout.strip()
    rev = git("rev-parse", "--short=12", "HEAD") or "unknown"
    return rev + ("-dirty" if git("status", "--porcelain", "reference") else "")


def binary_revision(binary):
    """The revision a gibench binary reports (gibench describe), else the checkout's."""
    r = subprocess.run([binary, "describe"], capture_output=True, text=True, cwd=ROOT)
    try:
        rev = json.loads(r.stdout).get("revision", "unknown")
    except ValueError:
        rev = "unknown"
    return rev if rev != "unknown" else git_revision()


def run_gibench(a, work, seed, component="full", spp=None, binary=None, tag="gibench"):
    """One render: its image, its EXR header's seconds and its strategies (full's)."""
    out = os.path.join(work, "%s_%s_%d.exr" % (tag, component, seed))
    cmd = [binary or a.gibench, "reference", "--scene", a.scene, "--component", component,
           "--spp", str(spp or a.spp), "--size", a.size, "--threads", str(a.threads), "--seed",
           str(seed), "--max-depth", str(a.max_depth), "--out", out, "--quiet"] + a.gibench_arg
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    w, h, ch, attrs = read_exr(out)
    return ch, float(attrs["seconds"]), attrs.get("strategies", "camera paths (before light "
                                                                "vertices)")


def run_cycles(a, work, seeds, max_depth, spp, tag):
    d = os.path.join(work, "cycles_" + tag)
    os.makedirs(d, exist_ok=True)
    w, h = (int(v) for v in a.size.split("x"))
    job = {"scene": a.scene, "width": w, "height": h, "spp": spp, "max_depth": max_depth,
           "seeds": seeds, "threads": a.threads, "dir": d,
           "cycles": dict(kv.split("=", 1) for kv in a.cycles_set)}
    with open(os.path.join(d, "job.json"), "w") as f:
        json.dump(job, f)
    subprocess.run([a.blender, "-b", "--factory-startup", "-P",
                    os.path.join(HERE, "cycles_scene.py"), "--", os.path.join(d, "job.json")],
                   check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    with open(os.path.join(d, "result.json")) as f:
        res = json.load(f)
    images = [read_exr(r["exr"])[2] for r in res["runs"]]
    return images, [r["seconds"] for r in res["runs"]], res


def pixel_stats(images):
    """Per value (pixel, channel): mean and unbiased variance over the images."""
    k = len(images)
    flat = [[v for c in "RGB" for v in img[c]] for img in images]
    means, vars_ = [], []
    for vals in zip(*flat):
        m = sum(vals) / k
        means.append(m)
        vars_.append(sum((v - m) ** 2 for v in vals) / (k - 1))
    return means, vars_


def summarise(images, seconds, spp):
    means, vars_ = pixel_stats(images)
    mean = sum(means) / len(means)
    var = sum(vars_) / len(vars_)
    rel = var / (mean * mean)
    t = statistics.median(seconds)
    return {"means": means, "vars": vars_, "k": len(images), "image_mean": mean,
            "sigma": math.sqrt(var), "sigma_per_sample": math.sqrt(var * spp),
            "rel_variance": rel, "efficiency": 1.0 / (rel * t), "seconds": t,
            "seconds_min": min(seconds), "seconds_max": max(seconds)}


def z_rms(sa, sb):
    zs = []
    for ma, va, mb, vb in zip(sa["means"], sa["vars"], sb["means"], sb["vars"]):
        se2 = va / sa["k"] + vb / sb["k"]
        if se2 > 0.0:
            zs.append((ma - mb) ** 2 / se2)
    return math.sqrt(sum(zs) / len(zs)) if zs else float("nan")


def image_mean(img):
    return sum(sum(img[c]) for c in "RGB") / (3 * len(img["R"]))


def direct_check(a, work):
    """Cycles' direct light over gibench's exact `direct`: 1 when light and geometry match."""
    gib = run_gibench(a, work, 1, "direct", 1)[0]
    cyc, _, _ = run_cycles(a, work, [1], 1, 16, "direct")
    return image_mean(cyc[0]) / image_mean(gib)


def measure(a, work):
    """Seed by seed, every gibench binary then Cycles (one Blender process a seed, its start-up
    untimed), so that a change in the machine's load falls on all of them alike."""
    seeds = list(range(1, a.seeds + 1))
    gibs = [("gibench", a.gibench)] + [tuple(kv.split("=", 1)) for kv in a.also]
    gibs = [(name, path.split("@")[0]) for name, path in gibs]
    runs = {name: [] for name, _ in gibs}
    cyc_imgs, cyc_secs, res = [], [], None
    for s in seeds:
        for name, binary in gibs:
            runs[name].append(run_gibench(a, work, s, binary=binary, tag=name))
        imgs, secs, res = run_cycles(a, work, [s], a.max_depth, a.spp, "full_%d" % s)
        cyc_imgs += imgs
        cyc_secs += secs
    c = summarise(cyc_imgs, cyc_secs, a.spp)
    c["efficiency_vs_cycles"] = c["mean_vs_cycles"] = 1.0
    out = []
    for name, binary in gibs:
        g = summarise([x[0] for x in runs[name]], [x[1] for x in runs[name]], a.spp)
        g["efficiency_vs_cycles"] = g["efficiency"] / c["efficiency"]
        g["mean_vs_cycles"] = g["image_mean"] / c["image_mean"]
        g["z_rms_vs_cycles"] = z_rms(g, c)
        g["name"], g["binary"], g["strategies"] = name, binary, runs[name][0][2]
        out.append(g)
    c["z_rms_vs_cycles"] = out[0]["z_rms_vs_cycles"]
    return out, c, res


def blender_version(res):
    deb = subprocess.run(["dpkg-query", "-W", "-f", "${Version}", "blender"],
                         capture_output=True, text=True).stdout.strip()
    return "blender %s (%s)" % (res["blender"], deb or "build " + res["build_hash"])


def rows(a, gs, c, res, check, load):
    model, cores = machine()
    now = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ")
    w, h = a.size.split("x")
    common = {"timestamp": now, "label": a.label, "machine": model, "cores": cores,
              "load_avg": "%.2f" % load, "threads": a.threads,
              "scene": os.path.relpath(a.scene, ROOT), "width": w, "height": h, "spp": a.spp,
              "max_depth": a.max_depth, "seeds": a.seeds, "direct_check": "%.6f" % check}
    revs = {kv.split("=", 1)[0]: kv.split("@", 1)[1] for kv in a.also if "@" in kv}
    entries = [(g["name"], g, "gibench reference full (%s)" % g["binary"],
                revs.get(g["name"]) or binary_revision(g["binary"]), "strategies: %s; %s" % (
                    g["strategies"], " ".join(a.gibench_arg) or "defaults")) for g in gs]
    entries.append(("cycles", c, blender_version(res), res["build_hash"],
                    ";".join("%s=%s" % kv for kv in res["settings"].items())))
    out = []
    for name, s, ver, rev, settings in entries:
        r = dict(common, renderer=name, version=ver, revision=rev, settings=settings)
        for k in ("seconds", "seconds_min", "seconds_max", "image_mean", "sigma",
                  "sigma_per_sample", "rel_variance", "efficiency", "efficiency_vs_cycles",
                  "mean_vs_cycles", "z_rms_vs_cycles"):
            r[k] = "%.6g" % s[k]
        out.append(r)
    return out


def write_csv(path, new_rows):
    fresh = not os.path.exists(path) or os.path.getsize(path) == 0
    with open(path, "a", newline="") as f:
        wr = csv.DictWriter(f, fieldnames=COLUMNS)
        if fresh:
            wr.writeheader()
        wr.writerows(new_rows)


def parse_args():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--gibench", default=os.path.join(ROOT, "build", "gibench"))
    ap.add_argument("--blender", default="blender")
    ap.add_argument("--scene", default=os.path.join(HERE, "closed_room.scene"))
    ap.add_argument("--size", default="128x128")
    ap.add_argument("--spp", type=int, default=256)
    ap.add_argument("--seeds", type=int, default=8, help="independent renders per renderer")
    ap.add_argument("--max-depth", type=int, default=8, help="gibench's surface vertices")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--cycles-set", action="append", default=[], metavar="KEY=VALUE",
                    help="a Cycles setting (scene.cycles.KEY) other than its default "
                         "(repeatable), e.g. sampling_pattern=SOBOL")
    ap.add_argument("--gibench-arg", action="append", default=[],
                    help="an extra argument for `gibench reference` (repeatable)")
    ap.add_argument("--also", action="append", default=[], metavar="NAME=GIBENCH[@REVISION]",
                    help="another gibench binary measured in the same run (repeatable), e.g. "
                         "before=/tmp/head/build/gibench@c10f35c: its own rows, NAME as "
                         "renderer; REVISION where the binary cannot say its own")
    ap.add_argument("--label", default="")
    ap.add_argument("--work", default=None, help="keep the images here (default: a temp dir)")
    ap.add_argument("--out", default=os.path.join(ROOT, "results", "bench_cycles.csv"))
    a = ap.parse_args()
    if a.seeds < 2:
        ap.error("--seeds must be at least 2 (a variance needs two renders)")
    a.scene = os.path.abspath(a.scene)
    return a


def main():
    a = parse_args()
    with tempfile.TemporaryDirectory(prefix="bench_cycles_") as tmp:
        work = a.work or tmp
        os.makedirs(work, exist_ok=True)
        load = os.getloadavg()[0]
        check = direct_check(a, work)
        gs, c, res = measure(a, work)
    new = rows(a, gs, c, res, check, load)
    write_csv(a.out, new)
    for r in new:
        print("%-8s %8ss  sigma %s (per sample %s)  efficiency %s  x%s of Cycles' (means %s, "
              "z_rms %s)" % (r["renderer"], r["seconds"], r["sigma"], r["sigma_per_sample"],
                             r["efficiency"], r["efficiency_vs_cycles"], r["mean_vs_cycles"],
                             r["z_rms_vs_cycles"]))
    print("load average at the start: %s (a loaded machine's timings scatter)" %
          new[0]["load_avg"])
    print("direct light check (Cycles / gibench): %s -> %s" % (new[0]["direct_check"], a.out))


if __name__ == "__main__":
    main()
