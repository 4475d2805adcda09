#!/usr/bin/env python3
"""The energy audit's controls (harness/energy_controls/run.py) stay runnable as the sources change:
every patch that cells.csv names applies to a copy of the current sources and touches only the
techniques; every "param K=V" control names a parameter its technique has; and a render's report is
read back as the component's mean ratio and RMSE over black's (a tiny procedural view, so no shared
scenes are needed). A patch that no longer applies fails here, not an hour into make
energy-controls."""
import csv
import functools
import importlib.util
import math
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "tests", "common"))
from script_checks import args, check, verdict  # noqa: E402

spec = importlib.util.spec_from_file_location(
    "energy_controls", os.path.join(ROOT, "harness", "energy_controls", "run.py"))
controls = importlib.util.module_from_spec(spec)
spec.loader.exec_module(controls)


def changed_files(copy):
    """The copy's files whose bytes differ from the tree's."""
    out = []
    for dirpath, _, files in os.walk(copy):
        for name in files:
            path = os.path.join(dirpath, name)
            rel = os.path.relpath(path, copy)
            mine = os.path.join(ROOT, rel)
            if name.endswith(".orig") or not os.path.exists(mine):
                continue
            with open(path, "rb") as a, open(mine, "rb") as b:
                if a.read() != b.read():
                    out.append(rel)
    return out


@functools.lru_cache(maxsize=None)
def listing(gibench):
    """`gibench list`'s text, read once: it loads every scene (7 s with the shared scenes here)."""
    return subprocess.run([gibench, "list"], capture_output=True, text=True).stdout


def parameters(gibench, technique):
    """The parameter names `gibench list` prints for technique."""
    text = listing(gibench)
    names, inside = set(), False
    for line in text.splitlines():
        words = line.split()
        if line.startswith("  ") and not line.startswith("    ") and words:
            inside = words[0] == technique
        elif inside and line.startswith("      ") and words:
            names.add(words[0].split("=")[0])
    return names


def main():
    a = args()
    os.makedirs(a.work)
    cells = list(csv.DictReader(open(os.path.join(ROOT, "harness", "energy_controls", "cells.csv"))))
    check(len(cells) > 0, "cells.csv lists cells")
    patches = sorted({p for c in cells if not c["control"].startswith("param ")
                      for p in c["control"].split("+")})
    for patch in patches:
        copy = os.path.join(a.work, "copy_" + patch.replace(".patch", ""))
        controls.control_sources(patch, copy)
        changed = changed_files(copy)
        check(changed and all(f.startswith("techniques" + os.sep) for f in changed),
              f"{patch} applies to the current sources and changes only techniques/ ({changed})")
    for technique, control in sorted({(c["technique"], c["control"]) for c in cells
                                      if c["control"].startswith("param ")}):
        names = [kv.split("=")[0] for kv in control[len("param "):].split()]
        check(all(n in parameters(a.gibench, technique) for n in names),
              f"{technique} has the parameters of control '{control}'")
    cell = {"technique": "vct", "scene": "cornell", "component": "indirect", "size": "32x32",
            "ref_spp": "4", "params": "voxel_res=64", "control": "param fill=0"}
    cache = os.path.join(a.work, "cache")
    mean, black, renderer = controls.score(a.gibench, cell, cache)
    check(0.2 < float(mean) < 5 and math.isfinite(float(black)) and float(black) > 0,
          f"a render's report read back: vct indirect on the Cornell box, mean {mean} of the "
          f"reference's, RMSE {black} of black's")
    check(bool(renderer), f"the renderer named ({renderer})")
    mean_c, _, _ = controls.score(a.gibench, cell, cache, "voxel_res=64;fill=0")
    check(mean_c != mean, f"a parameter control renders anew (fill=0: mean {mean_c})")
    try:
        controls.score(a.gibench, dict(cell, component="caustic"), cache)
        check(False, "a component the technique does not output is an error")
    except SystemExit as e:
        check("no caustic score" in str(e), "a component the technique does not output is an "
              "error naming it")
    return verdict()


if __name__ == "__main__":
    sys.exit(main())
