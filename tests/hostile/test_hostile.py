#!/usr/bin/env python3
"""Inputs that are legal but hostile: a generated suite of scene files at the
edges of what the format allows, each rendered by every technique and by the reference. Each run
must either render finite output (`nonfinite 0` against the reference) or refuse with a clear error
(exit 1 or 2 and a message naming the scene, technique, parameter or size) before rendering — never
crash (a signal), hang (the timeout), or print NaN/Inf.

Scenes (written into --work; the one-triangle OBJ beside them, found through GIBENCH_SCENES):
  million_tiny     1,008,000 triangles about 0.5 mm across (a hairball of 2,000 tubes of radius
                   0.5 mm, 42 steps, 6 sides) in a room
  one_triangle     a single triangle (an OBJ with one face) under a spot light
  light_inside     a point light inside a closed box, the camera outside: nothing lit in view
  albedo_edges     a room of albedo 0 walls, floor and ceiling of albedo 1, a box of albedo 1
  camera_in_wall   the Cornell box seen from a camera inside its back wall's thickness (a box)
  huge             the Cornell box scaled by 1e6 (lights by 1e12), a 1e6 m room
  tiny             the Cornell box scaled by 1e-4 (lights by 1e-8)
Sizes: 32x24 for all, and 1x1 and 16384x2 (the widest image the GL and the format allow) on the
Cornell box."""
import argparse
import os
import re
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
import script_checks  # noqa: E402
from script_checks import check, failures  # noqa: E402

TECHNIQUES = ["direct", "hbao", "ldm_ao", "ldm_indirect", "ldm_env", "lrsm", "vct", "rsm_gather",
              "multires_ir", "ispm_caustics"]
# Small settings so that a million triangles stay seconds on llvmpipe; the edges are the scenes.
PARAMS = {"ldm_ao": ["directions=8", "ldm_res=32", "dmax=0.5"], "ldm_indirect": ["directions=8", "ldm_res=32"],
          "ldm_env": ["directions=8", "ldm_res=32"], "lrsm": ["voxel_res=64", "rsm_res=128"],
          "vct": ["voxel_res=64"], "rsm_gather": ["rsm_res=128", "vpl_count=64"],
          "multires_ir": ["rsm_res=128", "vpl_count=64"], "ispm_caustics": ["rsm_res=128", "ray_res=64"],
          "hbao": ["dmax=0.5"], "direct": ["shadow_res=256"]}
ROOM_LIGHT = """
[light.spot]
type = spot
position = 0 2.5 0
direction = 0 -1 0
intensity = 5 5 5
exponent = 1
outer_angle = 60

[camera.view]
eye = 0 1.5 1.9
target = 0 0.5 0
up = 0 1 0
fov = 60
"""
SCENES = {
    "million_tiny": """[scene]
description = hostile: a million 0.7 mm triangles
[mesh.room]
procedural = room
size = 4 3 4
[mesh.hair]
procedural = hairball
radius = 0.25
thickness = 0.0005
tubes = 2000
segments = 42
sides = 6
translate = 0 0.5 0
""" + ROOM_LIGHT,
    "one_triangle": """[scene]
description = hostile: one triangle
[mesh.tri]
file = one_triangle.obj
""" + ROOM_LIGHT,
    "light_inside": """[scene]
description = hostile: a point light inside a closed box
[mesh.box]
procedural = box
size = 1 1 1
[light.in]
type = point
position = 0 0.5 0
intensity = 10 10 10
[camera.view]
eye = 0 1.5 3
target = 0 0.5 0
up = 0 1 0
fov = 50
""",
    "albedo_edges": """[scene]
description = hostile: albedo 0 and albedo 1
[mesh.room]
procedural = room
size = 4 3 4
[material.room_wall_xneg]
albedo = 0 0 0
[material.room_wall_xpos]
albedo = 0 0 0
[material.room_wall_zneg]
albedo = 0 0 0
[material.room_wall_zpos]
albedo = 0 0 0
[material.room_floor]
albedo = 1 1 1
[material.room_ceiling]
albedo = 1 1 1
[mesh.box]
procedural = box
size = 1 1 1
material = white
[material.white]
albedo = 1 1 1
""" + ROOM_LIGHT,
    "camera_in_wall": """[scene]
description = hostile: the camera inside a wall
[mesh.box]
procedural = cornell_box
[mesh.wall]
procedural = box
size = 0.6 0.6 0.1
translate = 0.278 0 -0.05
[light.ceiling_spot]
type = spot
position = 0.278 0.5388 0.2795
direction = 0 -1 0
intensity = 0.5 0.5 0.5
exponent = 1
outer_angle = 90
[camera.inside]
eye = 0.278 0.273 -0.05
target = 0.278 0.273 0.5
up = 0 1 0
fov = 40
""",
}


def cornell_scaled(s):
    return f"""[scene]
description = hostile: the Cornell box scaled by {s:g}
[mesh.box]
procedural = cornell_box
scale = {s:g} {s:g} {s:g}
[light.ceiling_spot]
type = spot
position = {0.278 * s:g} {0.5388 * s:g} {0.2795 * s:g}
direction = 0 -1 0
intensity = {0.5 * s * s:g} {0.5 * s * s:g} {0.5 * s * s:g}
exponent = 1
outer_angle = 90
[camera.published]
eye = {0.278 * s:g} {0.273 * s:g} {-0.8 * s:g}
target = {0.278 * s:g} {0.273 * s:g} 0
up = 0 1 0
fov = 39.3077
"""


SCENES["huge"] = cornell_scaled(1e6)
SCENES["tiny"] = cornell_scaled(1e-4)

def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--gibench", required=True)
    ap.add_argument("--root", required=True)
    ap.add_argument("--work", required=True)
    ap.add_argument("--only", help="comma-separated scene names")
    a = ap.parse_args()
    shutil.rmtree(a.work, ignore_errors=True)
    os.makedirs(a.work)
    with open(os.path.join(a.work, "one_triangle.obj"), "w") as f:
        f.write("v -1 0 -1\nv 1 0 -1\nv 0 0 1\nvn 0 1 0\nf 1//1 3//1 2//1\n")
    env = dict(os.environ, GIBENCH_SCENES=a.work)
    cases = []
    names = a.only.split(",") if a.only else list(SCENES)
    for name in names:
        path = os.path.join(a.work, name + ".scene")
        with open(path, "w") as f:
            f.write(SCENES[name])
        cases += [(path, t, "32x24") for t in TECHNIQUES]
    if not a.only:
        cornell = os.path.join(a.root, "scenes", "cornell.scene")
        cases += [(cornell, t, s) for s in ("1x1", "16384x2") for t in TECHNIQUES]
    for scene, tech, size in cases:
        out = os.path.join(a.work, "out", os.path.basename(scene)[:-6] + "_" + tech + "_" + size)
        cmd = [a.gibench, "render", "--scene", scene, "--technique", tech, "--size", size,
               "--ref-spp", "4", "--frames", "1", "--warmup", "0", "--out", out,
               "--cache", os.path.join(a.work, "cache")]
        for p in PARAMS.get(tech, []):
            cmd += ["--param", p]
        what = f"{os.path.basename(scene)[:-6]} {tech} {size}"
        try:
            p = script_checks.run(cmd, env=env, timeout=300)
        except subprocess.TimeoutExpired:
            check(False, f"{what}: hung (300 s)")
            continue
        text = p.stdout + p.stderr
        if p.returncode < 0:
            check(False, f"{what}: killed by signal {-p.returncode}: {text[-300:]}")
            continue
        if p.returncode == 0:
            nf = [int(x) for x in re.findall(r"nonfinite (\d+)", text)]
            # The absolute RMSE must be finite; relative RMSE and PSNR are inf by definition against
            # an all-black reference (light_inside), which harness/imaging/metrics.h documents.
            bad = re.search(r"\b(nan|inf)\b", " ".join(re.findall(r": rmse (\S+)", text)), re.I)
            check(nf and all(x == 0 for x in nf) and not bad,
                  f"{what}: rendered, nonfinite {nf}" + (f", metric {bad.group(0)}" if bad else ""))
        else:
            msg = text.strip().splitlines()[-1] if text.strip() else ""
            clear = p.returncode in (1, 2) and ("gibench" in msg) and len(msg) > 20
            check(clear, f"{what}: refused (exit {p.returncode}): {msg[:160]}")
    print("PASS" if not failures else f"FAIL: {len(failures)} of {len(cases)}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
