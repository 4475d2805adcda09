#!/usr/bin/env python3
"""What the report's Python knows of the C side comes from gibench's export, not from copies: a
fresh `gibench schema` (the binary under test) against what the modules use: the diffuse cone
set's weights (cone_study.py), the parameters that set a component's reference (answers.py), the
software-renderer rule (report.py, history.c's list), each value compared.

usage: test_describe.py GIBENCH WORK"""
import json
import math
import os
import subprocess
import sys

gibench, work = sys.argv[1], sys.argv[2]
os.makedirs(work, exist_ok=True)
fresh = os.path.join(work, "schema.json")
subprocess.run([gibench, "schema", "--out", fresh], check=True)
os.environ["GIBENCH_SCHEMA"] = fresh
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "harness"))
import answers  # noqa: E402
import cone_study  # noqa: E402
import report  # noqa: E402

with open(fresh) as f:
    exported = json.load(f)
failures = []


def check(ok, what):
    print(("PASS " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)


w = exported["cone_set"]["weights"]
check(len(w) == 6 and abs(sum(w) - 1) < 1e-6 and cone_study.WEIGHTS == w,
      f"cone weights: the study's {cone_study.WEIGHTS} are the export's {w}")
ref = {c: [(b["param"], math.inf if b["default"] == "inf" else b["default"]) for b in bs]
       for c, bs in exported["reference_params"].items()}
used = {c: list(v) for c, v in answers.REFERENCE_PARAMS.items()}
check(used == ref and ("dmax", math.inf) in ref.get("ao", []),
      f"reference parameters: answers' {used} are the export's {ref}")
names = exported["software_renderers"]
check("llvmpipe" in names and all(report.is_software(f"Mesa {n} (x)") for n in names)
      and not report.is_software("NVIDIA H200/PCIe/SSE2"),
      f"software renderers: report.is_software follows the export's {names}")
print("FAIL" if failures else "PASS", f"{len(failures)} failure(s)")
sys.exit(1 if failures else 0)
