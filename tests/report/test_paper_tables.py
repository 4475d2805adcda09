#!/usr/bin/env python3
"""harness/reporting/lrsm_tables.py's Table 2 on constructed runner tables (no GL): a dense VCT run that ran
out of memory is measured by what it planned, from its mem_planned_by_structure column
("structure=bytes;..."); a table written before that column gives its plan in the message only
("plans N bytes (radiance a, normal b, ...)"), which is read then. Both give the same row, and the
column wins over the message where both are there.

usage: test_paper_tables.py WORK_DIR (GIBENCH_SCHEMA names `gibench schema`'s output)
"""
import os
import shutil
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "harness"))
from reporting import lrsm_tables  # noqa: E402
from reporting import schema  # noqa: E402

failures = []
PLAN = {"radiance": 1073741824, "normal": 1073741824, "aniso": 920350128, "voxels": 153391897}
MESSAGE = ("vct: out of memory: voxel_res 512 plans 3221225673 bytes (radiance 1073741824, normal "
           "1073741824, aniso 920350128, voxels 153391897), over the 2048000000 bytes available")


def check(cond, what):
    print(("ok    " if cond else "FAIL  ") + what)
    if not cond:
        failures.append(what)


def vct_row(planned, message):
    r = {c: "" for c in schema.columns("runs")}
    r.update({"matrix": "lrsm_memory", "profile": "quick", "scene": "thin_wall_leak", "camera": "0",
              "technique": "vct", "component": "indirect", "width": "64", "height": "36", "time": "0",
              "params": "voxel_res=512;memory_budget_mb=2048", "mem_bytes": "0",
              "status": "out_of_memory", "message": message, "mem_planned_by_structure": planned})
    return r


def vct_total(work, rows):
    results = os.path.join(work, "results")
    shutil.rmtree(results, ignore_errors=True)
    os.makedirs(results)
    schema.write_csv(os.path.join(results, "lrsm_memory.csv"), rows, schema.columns("runs"))
    out = lrsm_tables.table2(results, os.path.join(results, "paper"))
    return next(r for r in out if r["structure"] == "vct_total" and "512" in r["setting"])


def main():
    work = sys.argv[1]
    planned = ";".join(f"{k}.texture={v}" for k, v in PLAN.items())
    own = PLAN["radiance"] + PLAN["normal"] + PLAN["aniso"]
    a = vct_total(work, [vct_row(planned, "vct: out of memory")])
    check(a["ours_bytes"] == str(own), f"from mem_planned_by_structure: its own structures {a['ours_bytes']}")
    check("voxels 153.39 MB" in a["note"] and "planned, not allocated" in a["note"],
          f"the rest of the plan and 'planned' in the note ({a['note']})")
    b = vct_total(work, [vct_row("", MESSAGE)])
    check(b == a, "a table without the column: the same row from the message's plan")
    c = vct_total(work, [vct_row("radiance=1;normal=2;aniso=3", MESSAGE)])
    check(c["ours_bytes"] == "6", f"the column wins over the message ({c['ours_bytes']})")
    print(f"{len(failures)} failed" if failures else "all passed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
