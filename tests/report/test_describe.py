#!/usr/bin/env python3
"""What the report's Python knows of the C side comes from gibench's export, not from copies: a
fresh `gibench describe` (the binary under test) against what the modules use: the diffuse cone
set's weights (cone_study.py), the parameters that set a component's reference (answers.py), the
software-renderer rule (report.py, history.c's list), the pass names the tables read
(thesis_tables.py, lrsm_tables.py, gpu_claims.py: each one a pass its technique declares), the row
statuses (schema.status refuses a word the binary does not declare) and the revision (the one
source_hash.py stamps the study CSVs with), each value compared.

usage: test_describe.py GIBENCH WORK"""
import json
import math
import os
import subprocess
import sys

gibench, work = sys.argv[1], sys.argv[2]
os.makedirs(work, exist_ok=True)
fresh = os.path.join(work, "schema.json")
subprocess.run([gibench, "describe", "--out", fresh], check=True)
os.environ["GIBENCH_SCHEMA"] = fresh
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "harness"))
from reporting import answers  # noqa: E402
from reporting import cone_study  # noqa: E402
from reporting import lrsm_tables  # noqa: E402
from reporting import report  # noqa: E402
from reporting import schema  # noqa: E402
from reporting import source_hash  # noqa: E402
from reporting import thesis_tables  # noqa: E402

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
declared = {t["name"]: set(t["passes"]) for t in exported["techniques"]}
check(len(declared) >= 10 and all(declared.values()),
      f"every technique declares its passes: {sorted(declared)}")
used = [("multires_ir", p) for p in thesis_tables.MULTIRES_SCREEN_PASSES] + \
    [("rsm_gather", thesis_tables.RSM_GATHERING), ("ispm_caustics", thesis_tables.PHOTON_TRACING),
     ("ispm_caustics", thesis_tables.SPLATTING)] + \
    [("lrsm", p) for p in lrsm_tables.TABLE3_STAGES] + \
    [stage for _, *stages in lrsm_tables.TABLE3_CLAIMS for stage in stages]
missing = [(t, p) for t, p in used if p not in declared.get(t, ())]
check(not missing, f"the {len(used)} passes the tables read are declared by their techniques "
      f"(missing: {missing})")
statuses = [x["name"] for x in exported["statuses"]]
check(statuses[0] == "ok" and "out_of_memory" in statuses and all(x["doc"] for x in exported["statuses"]),
      f"the statuses, each with what it means: {statuses}")
try:
    schema.status("no_such_status")
    refused = False
except SystemExit:
    refused = True
check(refused, "schema.status refuses a word the binary does not declare")
try:
    schema.pass_name("multires_ir", "no_such_pass")
    refused = False
except SystemExit:
    refused = True
check(refused, "schema.pass_name refuses a pass the technique does not declare")
check(exported["revision"] == source_hash.git_revision(),
      f"revision: gibench's {exported['revision']} is source_hash.py's {source_hash.git_revision()}")
print("FAIL" if failures else "PASS", f"{len(failures)} failure(s)")
sys.exit(1 if failures else 0)
