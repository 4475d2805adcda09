"""What the fault tests share: the matrix they run (faults.matrix), and from tests/common/
script_checks.py their command line, the check that prints and counts a failure, and the verdict."""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from script_checks import args, check, failures, verdict, run as run_gibench  # noqa: E402,F401

MATRIX = os.path.join(os.path.dirname(os.path.abspath(__file__)), "faults.matrix")
