"""What the Python tests that drive gibench share: their command line (the gibench under test and a
work folder made empty), the check that prints and counts a failure, and the verdict."""
import argparse
import shutil

failures = []


def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what)
    if not cond:
        failures.append(what)


def args():
    """--gibench and --work; the work folder is emptied."""
    ap = argparse.ArgumentParser()
    ap.add_argument("--gibench", required=True)
    ap.add_argument("--work", required=True)
    a = ap.parse_args()
    shutil.rmtree(a.work, ignore_errors=True)
    return a


def verdict(passed_text="PASS"):
    """Prints the verdict line; the exit status."""
    print(passed_text if not failures else f"FAIL: {len(failures)} checks")
    return 1 if failures else 0
