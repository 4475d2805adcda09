"""External renderers (harness/app/external.h): the example renderer (examples/external_renderer)
beside the built-in `direct` in the furnace, and every failure an external can have, each a row's
status and message, the other rows unaffected; matrices that name externals wrongly refused.

Why the band: in the furnace (a point light at the centre of a closed sphere) nothing casts a
shadow, so the example's unshadowed Lambertian direct light at each pixel centre is what the
reference computes there (next-event estimation to the point light, no variance): they differ by
float rounding only (2e-8 measured), far inside 1e-4 (0.06 % of the wall's 0.159). The reference's
own RMS over the image (black_rmse) is the closed form (a / pi) I / R^2 = 0.159155 within the
tessellation's 0.06 % (scenes/furnace.scene)."""
import csv
import glob
import os
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from script_checks import args, check, verdict, run  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
RENDER = os.path.join(HERE, "..", "..", "examples", "external_renderer", "render.py")

MATRIX = """[matrix]
description = external renderers beside a built-in, and their failures
scenes = furnace
techniques = direct, example, exit1, nothing, wrongsize, nan, sleeper, aoext
sizes = 64x48
frames = 2
warmup = 1
ref_spp_direct = 4
ref_spp_ao = 4

[external.example]
command = python3 {render}
version = 1.0
components = direct
timeout_s = 120

; relative to the matrix's folder, where the command runs
[external.exit1]
command = sh exit1.sh
version = 2
components = direct

[external.nothing]
command = python3 {render} --mode nothing
components = direct

[external.wrongsize]
command = python3 {render} --mode wrongsize
components = direct

[external.nan]
command = python3 {render} --mode nan
components = direct

[external.sleeper]
command = python3 {render} --mode sleep
components = direct
timeout_s = 2

[external.aoext]
command = python3 {render}
version = 0.1
components = ao

[params.aoext]
dmax = 0.5

[profile.quick]
frames = 2
"""

BAD = {
    "builtin_name": ("[external.direct]\ncommand = true\ncomponents = direct\n",
                     "built-in technique's name"),
    "no_command": ("[external.x]\ncomponents = direct\n", "needs command and components"),
    "bad_component": ("[external.x]\ncommand = true\ncomponents = light\n", "unknown component"),
    "bad_key": ("[external.x]\ncommand = true\ncomponents = direct\ncolour = red\n",
                "unknown key 'colour'"),
}


def rows_by_technique(path):
    with open(path, newline="") as f:
        return {r["technique"]: r for r in csv.DictReader(f)}


def check_ok_rows(rows):
    d, e = rows.get("direct"), rows.get("ext:example")
    check(d is not None and d["status"] == "ok", "built-in direct: status ok")
    check(e is not None and e["status"] == "ok", f"ext:example: status ok ({e and e['message']})")
    if not e or e["status"] != "ok":
        return
    check(float(e["rmse"]) < 1e-4, f"ext:example: rmse {e['rmse']} < 1e-4 (float rounding only)")
    check(abs(float(e["mean_ratio"]) - 1) < 1e-4, f"ext:example: mean ratio {e['mean_ratio']}")
    check(abs(float(e["black_rmse"]) - 0.159155) < 0.159155 * 0.001,
          f"reference RMS {e['black_rmse']} is the closed form 0.159155 within 0.1 %")
    check(e["params"] == "version=1.0", f"version in params: {e['params']}")
    check(e["backend"] == "external" and e["gl_version"] == "1.0", "backend external, version 1.0")
    check(e["renderer"].startswith("example_renderer.py"), f"renderer reported: {e['renderer']}")
    check("render.py" in e["message"], f"command recorded: {e['message']}")
    check(e["counters"].startswith("ray_triangle_tests="), f"counters: {e['counters']}")
    check(float(e["gpu_ms_median"]) > 0 and int(e["mem_bytes"]) > 0, "times and memory read back")


def check_failures(rows):
    expect = {
        "ext:exit1": ("external_failed", ["exited with status 1", "exit1.sh says no"]),
        "ext:nothing": ("readback_failed", ["wrote no direct.exr"]),
        "ext:wrongsize": ("readback_failed", ["32x24", "64x48"]),
        "ext:nan": ("nonfinite", ["NaN/Inf"]),
        "ext:sleeper": ("timeout", ["timeout_s 2 s", "killed"]),
        "ext:aoext": ("external_failed", ["exited with status 2", "'ao' is not supported"]),
    }
    for tech, (status, words) in expect.items():
        r = rows.get(tech)
        check(r is not None and r["status"] == status,
              f"{tech}: status {r and r['status']} (want {status})")
        for w in words:
            check(r is not None and w in r["message"], f"{tech}: message has '{w}'")
        check(r is not None and r["rmse"] in ("", "nan") if status != "nonfinite" else True,
              f"{tech}: no metrics")
    a = rows.get("ext:aoext")
    check(a is not None and a["params"] == "dmax=0.5;obscurance=0;version=0.1",
          f"ext:aoext: params {a and a['params']}")


def check_bad_matrices(a):
    for name, (text, words) in BAD.items():
        path = os.path.join(a.work, f"bad_{name}.matrix")
        with open(path, "w") as f:
            f.write("[matrix]\nscenes = furnace\ntechniques = direct\nsizes = 8x8\n" + text)
        p = run([a.gibench, "run", path, "--profile", "default", "--out",
                 os.path.join(a.work, "bad"), "--no-history"])
        check(p.returncode == 2 and words in p.stderr, f"matrix refused ({name}): {p.stderr.strip()}")


def main():
    a = args()
    os.makedirs(a.work)
    with open(os.path.join(a.work, "exit1.sh"), "w") as f:
        f.write("echo 'exit1.sh says no' >&2\nexit 1\n")
    matrix = os.path.join(a.work, "ext.matrix")
    with open(matrix, "w") as f:
        f.write(MATRIX.format(render=os.path.abspath(RENDER)))
    tmp = os.path.join(a.work, "tmp")
    os.makedirs(tmp)
    t0 = time.time()
    p = run([a.gibench, "run", matrix, "--out", os.path.join(a.work, "out"), "--cache",
             os.path.join(a.work, "cache"), "--no-history"],
            env=dict(os.environ, TMPDIR=tmp))
    took = time.time() - t0
    print(p.stdout[-3000:], p.stderr[-3000:])
    check(p.returncode == 1, f"gibench run exits 1 (rows not ok): {p.returncode}")
    check(took < 90, f"the run took {took:.1f} s (the sleeper is killed at 2 s)")
    rows = rows_by_technique(os.path.join(a.work, "out", "ext.csv"))
    check(len(rows) == 8, f"8 rows: {sorted(rows)}")
    check_ok_rows(rows)
    check_failures(rows)
    check(not glob.glob(os.path.join(tmp, "gibench-ext-*")), "job folders removed")
    passes = open(os.path.join(a.work, "out", "ext_passes.csv")).read()
    check("ext:example" in passes and ",cast," in passes, "the example's passes in the passes table")
    # A rerun skips every row already written: the externals' too.
    p = run([a.gibench, "run", matrix, "--out", os.path.join(a.work, "out"), "--cache",
             os.path.join(a.work, "cache"), "--no-history"], env=dict(os.environ, TMPDIR=tmp))
    check("every run already in" in p.stdout, "a rerun resumes: nothing left to run")
    check_bad_matrices(a)
    return verdict()


if __name__ == "__main__":
    sys.exit(main())
