"""What the Python tests that drive gibench share: their command line (the gibench under test and a
work folder made empty), the check that prints and counts a failure, and the verdict."""
import argparse
import shutil
import subprocess

failures = []


def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what)
    if not cond:
        failures.append(what)


# What LeakSanitizer prints when it cannot stop the process's threads to scan them (ptrace refused
# or a thread gone mid-attach, seen under load with Mesa's worker threads exiting): a failure of the
# sanitizer's environment, not a finding. A finding reads "ERROR: LeakSanitizer: detected memory
# leaks" and is never retried.
LSAN_ENVIRONMENT_FAILURE = "LeakSanitizer has encountered a fatal error"
LSAN_RETRIES = 2


def run(cmd, **kwargs):
    """subprocess.run(cmd, capture_output=True, text=True, **kwargs), run again (at most twice) when
    LeakSanitizer failed to run rather than found something; each retry is printed, and a command
    that fails so every time returns that last result, which the caller's check then reports."""
    for attempt in range(LSAN_RETRIES + 1):
        p = subprocess.run(cmd, capture_output=True, text=True, **kwargs)
        if LSAN_ENVIRONMENT_FAILURE not in (p.stderr or "") or attempt == LSAN_RETRIES:
            if LSAN_ENVIRONMENT_FAILURE in (p.stderr or ""):
                print(f"note {LSAN_RETRIES + 1} tries: LeakSanitizer could not stop the world "
                      f"(its environment, not a leak): {' '.join(map(str, cmd[:4]))} ...")
            return p
        print(f"note retried: LeakSanitizer could not stop the world (its environment, not a "
              f"leak), try {attempt + 1}: {' '.join(map(str, cmd[:4]))} ...")
    return p


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
