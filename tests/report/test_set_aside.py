#!/usr/bin/env python3
"""harness/reporting/set_aside.py, which `make reproduce` runs before a profile's fresh run: the rows of that
profile move to RESULTS/previous/ (runs and passes tables alike), every other profile's rows stay
where they are, byte for byte (a quoted field stays quoted), and a table without the profile's rows
is left untouched. No GL.

usage: test_set_aside.py WORK_DIR"""
import os
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "common"))
from script_checks import check, verdict  # noqa: E402

work = sys.argv[1]
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
runs = ("matrix,profile,scene,renderer\n"
        "m,quick,cornell,\"llvmpipe (LLVM 15.0.6, 256 bits)\"\n"
        "m,paper,cornell,\"llvmpipe (LLVM 15.0.6, 256 bits)\"\n"
        "m,quick,sponza,x\n")
passes = "matrix,profile,pass\nm,paper,gbuffer\nm,quick,gbuffer\n"
other = "matrix,profile,scene\nn,paper,ring\n"
for name, text in (("m.csv", runs), ("m_passes.csv", passes), ("n.csv", other)):
    with open(os.path.join(work, name), "w") as f:
        f.write(text)
p = subprocess.run([sys.executable, "-m", "reporting.set_aside", work,
                    "quick", "harness/matrices/m.matrix", "harness/matrices/n.matrix"],
                   capture_output=True, text=True,
                   env=dict(os.environ, PYTHONPATH=os.path.join(HERE, "..", "..", "harness")))
check(p.returncode == 0 and "3 rows of profile quick" in p.stdout, f"ran and counted 3 rows ({p.stdout.strip()})")


def read(*path):
    with open(os.path.join(work, *path)) as f:
        return f.read()


check(read("m.csv") == "matrix,profile,scene,renderer\nm,paper,cornell,\"llvmpipe (LLVM 15.0.6, 256 bits)\"\n",
      "the paper row stays, as it was written")
check(read("previous", "m.csv") == "matrix,profile,scene,renderer\n"
      "m,quick,cornell,\"llvmpipe (LLVM 15.0.6, 256 bits)\"\nm,quick,sponza,x\n",
      "the quick rows are set aside, in their order")
check(read("m_passes.csv") == "matrix,profile,pass\nm,paper,gbuffer\n"
      and read("previous", "m_passes.csv") == "matrix,profile,pass\nm,quick,gbuffer\n",
      "the passes table is split alike")
check(read("n.csv") == other and not os.path.exists(os.path.join(work, "previous", "n.csv")),
      "a table without quick rows is left untouched")
sys.exit(verdict())
