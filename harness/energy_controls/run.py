#!/usr/bin/env python3
"""Measured controls for the energy audit's cells (make energy-controls).

A control is a patch to the techniques' sources that removes one suspected cause of an energy
gap (cones_end_opaque.patch: the light the voxel cones let through thin surfaces; a+b applies
both), or "param K=V ...": the technique as it is with other parameters. A patch is applied to a
copy of the committed sources, never to the tree, and built beside the main build;
each cell of cells.csv is then rendered by both builds at the committed row's parameters and
scored against the same cached reference (gibench render --ref-spp --cache). Writes
results/energy_controls.csv:

  technique, scene, component, size, voxel_res, params, control, mean_ratio, mean_ratio_control,
  rmse_over_black, rmse_over_black_control, renderer, cores, git_revision, technique_hash,
  technique_hash_control

energy_causes.csv cites these rows; harness/reporting/energy_audit.py shows them beside their cells.

Usage: harness/energy_controls/run.py [--cells harness/energy_controls/cells.csv]
       [--out results/energy_controls.csv] [--gibench build/gibench]
       [--control-build build-control] [--cache results/cache] [--only TECHNIQUE:SCENE,...]
"""
import argparse
import csv
import os
import re
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
from reporting import source_hash  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(HERE))
COLUMNS = ["technique", "scene", "component", "size", "voxel_res", "params", "control",
           "mean_ratio", "mean_ratio_control", "rmse_over_black", "rmse_over_black_control",
           "renderer", "cores", "git_revision", "technique_hash", "technique_hash_control"]


def run(cmd, **kw):
    env = dict(os.environ)
    # the copy lies elsewhere: scene data stays where the project's own default finds it
    env.setdefault("GIBENCH_SCENES",
                   os.path.normpath(os.path.join(ROOT, "..", "shared", "scenes")))
    r = subprocess.run(cmd, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, **kw)
    if r.returncode != 0:
        sys.exit("energy_controls: %s failed (%d):\n%s" % (" ".join(cmd), r.returncode,
                                                           r.stdout[-3000:]))
    return r.stdout


def control_sources(patch, dest):
    """The tracked sources as the tree holds them (results/ left out), copied into dest, with the
    control's patches (a+b: both) applied."""
    if os.path.isdir(dest):
        shutil.rmtree(dest)
    os.makedirs(dest)
    files = run(["git", "-C", ROOT, "ls-files", "--", ".", ":(exclude)results"]).split("\n")
    for f in filter(None, files):
        src = os.path.join(ROOT, f)
        if os.path.isfile(src):
            os.makedirs(os.path.dirname(os.path.join(dest, f)), exist_ok=True)
            shutil.copy2(src, os.path.join(dest, f))
    # `patch`, not `git apply`: inside the project's work tree git apply skips the copy's files
    for one in patch.split("+"):
        run(["patch", "-p1", "--forward", "-d", dest, "-i", os.path.join(HERE, one)])


def build_control(patch, build):
    """gibench built from the patched copy (build/src, build/bin); its path."""
    src, out = os.path.join(build, "src"), os.path.join(build, "bin")
    control_sources(patch, src)
    run(["cmake", "-S", src, "-B", out, "-DCMAKE_BUILD_TYPE=RelWithDebInfo"])
    run(["cmake", "--build", out, "--target", "gibench", "-j%d" % (os.cpu_count() or 2)])
    return os.path.join(out, "gibench"), source_hash.Tree(src)


LINE = re.compile(r"^  (\w+): rmse \S+ rel_rmse \S+ mean (\S+) of the reference's")
BLACK = re.compile(r"^  (\w+): a black image scores rmse \S+ \(this image (\S+) of it\)")


RENDERS = {}  # one render scores every component it outputs


def render(gibench, cell, params, cache):
    """gibench render's report of the cell's view with params (rendered once per key)."""
    key = (gibench, cell["scene"], cell["technique"], cell["size"], cell["ref_spp"], params)
    if key not in RENDERS:
        out_dir = tempfile.mkdtemp(prefix="gib_control_")
        try:
            cmd = [gibench, "render", "--scene", cell["scene"], "--technique", cell["technique"],
                   "--size", cell["size"], "--ref-spp", cell["ref_spp"], "--cache", cache,
                   "--out", out_dir]
            for p in filter(None, params.split(";")):
                cmd += ["--param", p]
            RENDERS[key] = run(cmd)
        finally:
            shutil.rmtree(out_dir, ignore_errors=True)
    return RENDERS[key]


def score(gibench, cell, cache, params=None):
    """(mean ratio, RMSE over black's, renderer) of the cell's component, rendered by gibench."""
    text = render(gibench, cell, cell["params"] if params is None else params, cache)
    mean = black = renderer = None
    for line in text.splitlines():
        m, b = LINE.match(line), BLACK.match(line)
        if m and m.group(1) == cell["component"]:
            mean = m.group(2)
        if b and b.group(1) == cell["component"]:
            black = b.group(2)
        if line.startswith("renderer: "):
            renderer = line.split(" | ")[1]
    if mean is None or black is None:
        sys.exit("energy_controls: no %s score in:\n%s" % (cell["component"], text[-2000:]))
    return mean, black, renderer


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--cells", default=os.path.join(HERE, "cells.csv"))
    ap.add_argument("--out", default=os.path.join(ROOT, "results", "energy_controls.csv"))
    ap.add_argument("--gibench", default=os.path.join(ROOT, "build", "gibench"))
    ap.add_argument("--control-build", default=os.path.join(ROOT, "build-control"))
    ap.add_argument("--cache", default=os.path.join(ROOT, "results", "cache"))
    ap.add_argument("--only", help="TECHNIQUE:SCENE[,...]: re-measure only these cells' rows and "
                    "keep the other rows of --out as they are")
    a = ap.parse_args()
    cells = list(csv.DictReader(open(a.cells)))
    only = set(a.only.split(",")) if a.only else None
    if only:
        cells = [c for c in cells if "%s:%s" % (c["technique"], c["scene"]) in only]
    builds, rows = {}, []
    ours = source_hash.Tree(ROOT)
    # at the start: what the build measured, whatever changes in the tree while it runs
    rev = source_hash.git_revision(ROOT)
    for cell in cells:
        mean, black, renderer = score(a.gibench, cell, a.cache)
        if cell["control"].startswith("param "):  # a parameter of the technique as it is
            control_tree = ours
            mean_c, black_c, _ = score(a.gibench, cell, a.cache, cell["params"] + ";" +
                                       cell["control"][len("param "):].replace(" ", ";"))
        else:
            if cell["control"] not in builds:
                builds[cell["control"]] = build_control(
                    cell["control"],
                    os.path.join(a.control_build, cell["control"].replace(".patch", "")))
            control_bin, control_tree = builds[cell["control"]]
            mean_c, black_c, _ = score(control_bin, cell, a.cache)
        vres = re.search(r"voxel_res=(\d+)", cell["params"])
        rows.append({"technique": cell["technique"], "scene": cell["scene"],
                     "component": cell["component"], "size": cell["size"],
                     "voxel_res": vres.group(1) if vres else "", "params": cell["params"],
                     "control": cell["control"], "mean_ratio": mean, "mean_ratio_control": mean_c,
                     "rmse_over_black": black, "rmse_over_black_control": black_c,
                     "renderer": renderer, "cores": str(os.cpu_count()),
                     "git_revision": rev,
                     "technique_hash": source_hash.technique_hash(ours, cell["technique"]),
                     "technique_hash_control": source_hash.technique_hash(control_tree,
                                                                          cell["technique"])})
        print("%s %s %s %s: mean %s -> %s, RMSE/black %s -> %s" % (
            cell["technique"], cell["scene"], cell["component"], cell["params"], mean, mean_c,
            black, black_c), flush=True)
    if only and os.path.exists(a.out):
        with open(a.out, newline="") as f:
            kept = [r for r in csv.DictReader(f)
                    if "%s:%s" % (r["technique"], r["scene"]) not in only]
        rows = kept + rows
    with open(a.out, "w", newline="") as f:
        w = csv.DictWriter(f, COLUMNS, lineterminator="\n")
        w.writeheader()
        w.writerows(rows)


if __name__ == "__main__":
    main()
