#!/usr/bin/env python3
"""The claims' one path (harness/reporting/claim.py, claims.py), on the committed results (read,
never written) and on an empty folder, no GL: every paper's module returns its claims as Claim
objects; claims.csv is written from them, once, and is the only file claims.py writes; no claim's
text appears twice (a claim tested at several settings is one Claim, its settings beneath it); the
counts per verdict of the Claims are those of claims.csv.

usage: test_claims.py WORK_DIR [RESULTS_DIR] (GIBENCH_SCHEMA names `gibench schema`'s output;
RESULTS_DIR defaults to the checkout's results/)
"""
import csv
import os
import shutil
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "harness"))
from reporting import claims, ldm_tables, lrsm_tables, temporal_tables, thesis_tables  # noqa: E402
from reporting.claim import COLUMNS, KINDS, VERDICTS, Claim  # noqa: E402

failures = []


def check(cond, what):
    print(("ok    " if cond else "FAIL  ") + what)
    if not cond:
        failures.append(what)


def counts(verdicts):
    verdicts = list(verdicts)
    return {v: verdicts.count(v) for v in VERDICTS}


def written(work, runs):
    """Writes claims.csv into an empty work folder from `runs`' results; returns (the Claims, the
    CSV's rows, the files the folder holds after)."""
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    calls = []
    real = claims.write_csv

    def counting(path, rows, cols):
        calls.append(path)
        return real(path, rows, cols)
    claims.write_csv = counting
    try:
        path, found = claims.write(work, runs)
    finally:
        claims.write_csv = real
    check(calls == [path] and os.path.basename(path) == "claims.csv", f"claims.csv written once ({calls})")
    with open(path, newline="") as f:
        reader = csv.DictReader(f)
        check(reader.fieldnames == COLUMNS, f"claims.csv's columns are a Claim's fields ({reader.fieldnames})")
        rows = list(reader)
    return found, rows, sorted(os.listdir(work))


def check_claims(found, rows, files, where):
    check(files == ["claims.csv"], f"{where}: claims.py writes claims.csv alone ({files})")
    check(all(isinstance(c, Claim) for c in found), f"{where}: claims.py gathers Claims")
    check(rows == [{k: str(v) for k, v in c.row().items()} for c in found],
          f"{where}: claims.csv is the Claims, a row each, in order ({len(rows)} rows, {len(found)} Claims)")
    texts = [(r["paper"], r["claim"]) for r in rows]
    twice = sorted({t for t in texts if texts.count(t) > 1})
    check(not twice, f"{where}: no claim's text appears twice ({twice})")
    stems = [(c.paper, c.source, c.kind, claims.stem(c.claim)) for c in found]
    check(len(set(stems)) == len(stems), f"{where}: a claim tested at several settings is counted once")
    check(all(len(c.settings) != 1 and all(isinstance(s, Claim) for s in c.settings) for c in found),
          f"{where}: the settings beneath a claim are Claims, two or more where there are any")
    check(all(r["verdict"] in VERDICTS and r["kind"] in KINDS for r in rows), f"{where}: verdicts and kinds are claim.py's")
    check(counts(c.verdict for c in found) == counts(r["verdict"] for r in rows),
          f"{where}: counts per verdict of the Claims and claims.csv agree ({counts(r['verdict'] for r in rows)})")


def main():
    work = os.path.abspath(sys.argv[1])
    results = os.path.abspath(sys.argv[2] if len(sys.argv) > 2 else os.path.join(HERE, "..", "..", "results"))
    paper = os.path.join(results, "paper")
    per_module = {"thesis_tables": thesis_tables.claims(results, paper), "lrsm_tables": lrsm_tables.claims(results, paper),
                  "ldm_tables": ldm_tables.claims(results, paper), "temporal_tables": temporal_tables.claims(results)}
    for name, found in per_module.items():
        check(bool(found) and all(isinstance(c, Claim) for c in found),
              f"{name}.claims returns Claims ({len(found)})")
    found, rows, files = written(os.path.join(work, "committed"), results)
    check_claims(found, rows, files, "committed results")
    settings = sum(max(1, len(c.settings)) for c in found)
    check(settings == sum(len(v) for v in per_module.values()),
          f"every module's claim is in claims.csv once, alone or beneath its claim ({settings} settings)")
    empty = os.path.join(work, "empty")
    os.makedirs(empty, exist_ok=True)
    found, rows, files = written(os.path.join(work, "from_empty"), empty)
    check_claims(found, rows, files, "an empty results folder")
    check(all(c.verdict == "not measurable here" for c in found),
          f"no runs: nothing judged ({counts(c.verdict for c in found)})")
    print(f"{len(failures)} failed" if failures else "all passed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
