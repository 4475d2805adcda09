#!/usr/bin/env python3
"""A matrix's table has the schema's base columns plus only the parameters its file names: a
parameter a technique gains (or has) that the matrix does not name is in the `params` column and
changes no header, so an existing table keeps its rows and its resume (harness/app/schema.h).

The test runs a one-row matrix naming one parameter of `direct` and checks
- the header is `gibench schema`'s base columns, then that parameter, nothing else, with
  mem_planned_by_structure right after mem_by_structure;
- `params` holds every parameter of the run, the unnamed ones included (no column for them);
- a matrix naming no parameter has the base columns alone, whatever its techniques' parameters;
- a rerun resumes: nothing moved aside, nothing written again;
- the image name harness/reporting/schema.py derives equals the one `gibench run` wrote;
- naming a further parameter in the matrix file is what restarts its table (moved aside).
"""
import json
import os
import subprocess
import sys

from fault_checks import args, check, verdict

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "harness"))

MATRIX = """[matrix]
description = header test: direct on the procedural Cornell box
scenes = cornell
techniques = direct
sizes = 32x32
frames = 1
warmup = 0
ref_spp_direct = 1
{params}
[profile.quick]
sizes = 32x32
"""


def write_matrix(work, name, params):
    path = os.path.join(work, name + ".matrix")
    with open(path, "w") as f:
        f.write(MATRIX.format(params=params))
    return path


def run(gibench, matrix, out, cache, images=True):
    cmd = [gibench, "run", matrix, "--out", out, "--cache", cache, "--no-history"]
    return subprocess.run(cmd + ([] if images else ["--no-images"]), capture_output=True, text=True)


def header(path):
    with open(path) as f:
        return f.readline().rstrip("\n").split(",")


def main():
    a = args()
    out, cache = os.path.join(a.work, "out"), os.path.join(a.work, "cache")
    os.makedirs(out)
    schema_path = os.path.join(a.work, "schema.json")
    subprocess.run([a.gibench, "schema", "--out", schema_path], check=True)
    os.environ["GIBENCH_SCHEMA"] = schema_path
    from reporting import schema
    with open(schema_path) as f:
        base = [c["name"] for c in json.load(f)["runs"]["columns"]]

    named = write_matrix(a.work, "named", "[params.direct]\nshadow_res = 256\n")
    r = run(a.gibench, named, out, cache)
    check(r.returncode == 0, f"the matrix runs (exit {r.returncode}) {r.stderr[-300:]}")
    table = os.path.join(out, "named.csv")
    h = header(table)
    check(h == base + ["shadow_res"], f"header: the base columns, then shadow_res alone ({h[len(base):]})")
    check(h.index("mem_planned_by_structure") == h.index("mem_by_structure") + 1,
          "mem_planned_by_structure follows mem_by_structure")
    rows = schema.read_csv(table)
    p = schema.params(rows[0]) if rows else {}
    check(len(rows) == 1 and {"shadow_res", "pcf", "normal_offset"} <= set(p),
          f"params holds every parameter, the unnamed ones too ({rows[0]['params'] if rows else 'no row'})")
    check(rows and schema.param(rows[0], "pcf") == p.get("pcf") and schema.param(rows[0], "shadow_res") == 256,
          "schema.param reads a wide column and, without one, params")
    check(rows and schema.image_name(rows[0]) == rows[0]["image"],
          f"harness/reporting/schema.py names the row's images as gibench run did ({rows[0]['image'] if rows else ''})")

    none = write_matrix(a.work, "none", "")
    r = run(a.gibench, none, out, cache, images=False)
    check(r.returncode == 0 and header(os.path.join(out, "none.csv")) == base,
          "a matrix naming no parameter has the base columns alone")

    r = run(a.gibench, named, out, cache)
    check(r.returncode == 0 and "every run already in" in r.stdout and "0 rows written" in r.stdout,
          "a rerun resumes: every run already in the table, no row written")
    check(not os.path.exists(table + ".old") and len(schema.read_csv(table)) == 1,
          "the table kept its row and was not moved aside")

    write_matrix(a.work, "named", "[params.direct]\nshadow_res = 256\npcf = 1\n")
    r = run(a.gibench, named, out, cache, images=False)
    check(r.returncode == 0 and header(table) == base + ["shadow_res", "pcf"] and os.path.exists(table + ".old"),
          "naming a further parameter in the matrix file adds its column and restarts the table")
    return verdict("PASS: a table's header is its matrix's, not every technique's")


if __name__ == "__main__":
    sys.exit(main())
