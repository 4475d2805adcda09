#!/usr/bin/env python3
"""An external renderer's rows in the report (harness/reporting/external.py; README.md "Bring your own
renderer"): a results folder of built-in and external rows becomes REPORT.md and the page, and

- the external ranks beside the built-in in the answer (the same group: it ran on the same machine),
  named as `ext:example (external, render.py 1.0)`, its time and memory "reported by the program";
- it is not judged stale by a source hash (it has no sources in the tree: no crash either), but a row
  of an older version of it in the same table is stale and left out of the answer;
- each failed external row (external_failed, timeout, readback_failed, nonfinite) shows its status
  and message and no number, in REPORT.md and on the page, and is listed as not ranked;
- the gallery, the energy audit, the reading guide and the answer plot's data name it alike.

The fixture tests/report/external_results/ is tests/external's matrix (the example renderer beside the
built-in `direct` in the furnace, and its failing externals) as `gibench run` wrote it, trimmed to six
rows, paths made /opt/gibench, plus one row of the example at an older version (0.9, run earlier)
made from its 1.0 row. The built-in row's technique_hash is set to its sources' hash now, so that an
edit of techniques/direct does not make it stale here. No GL, no images; about a second."""
import csv
import os
import re
import shutil
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
HARNESS = os.path.join(HERE, "..", "..", "harness")
sys.path.insert(0, HARNESS)
sys.path.insert(0, os.path.join(HERE, "..", "common"))
from reporting import answers, external, gpu_rows, plot, schema, source_hash  # noqa: E402
from reporting.claims import COLUMNS as CLAIM_COLUMNS  # noqa: E402
from reporting.schema import matrices  # noqa: E402
from script_checks import check, verdict  # noqa: E402

FIXTURE = os.path.join(HERE, "external_results")
LABEL = "ext:example (external, render.py 1.0)"
FAILED = {"ext:exit1": ("external_failed", "exit1.sh says no"),
          "ext:wrongsize": ("readback_failed", "direct.exr is 32x24, the job asked for 64x48"),
          "ext:nan": ("nonfinite", "30 NaN/Inf values in the image"),
          "ext:sleeper": ("timeout", "no result after its timeout_s 2 s, killed")}


def make_results(work):
    """The fixture in a fresh folder, the built-in row current, an empty claims.csv."""
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    shutil.copy(os.path.join(FIXTURE, "ext_passes.csv"), work)
    with open(os.path.join(FIXTURE, "ext.csv"), newline="") as f:
        rows = list(csv.DictReader(f))
    tree = source_hash.Tree()
    for r in rows:
        if not r["technique"].startswith("ext:"):
            r["technique_hash"] = source_hash.technique_hash(tree, r["technique"])
    with open(os.path.join(work, "ext.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]), lineterminator="\n")
        w.writeheader()
        w.writerows(rows)
    with open(os.path.join(work, "claims.csv"), "w") as f:
        f.write(",".join(CLAIM_COLUMNS) + "\n")
    return rows


def md_table_rows(md, heading):
    """{first cells joined: {column: cell}} of the table under a Markdown heading."""
    part = md.split(heading + "\n", 1)[1]
    lines = [ln for ln in part.split("\n## ")[0].splitlines() if ln.startswith("|")]
    head = [c.strip() for c in lines[0].strip("|").split(" | ")]
    out = []
    for ln in lines[2:]:
        cells = [c.strip() for c in re.split(r"(?<!\\)\|", ln.strip())[1:-1]]
        out.append(dict(zip(head, cells)))
    return out


def check_rows_module(work):
    """external.py and the staleness judgment on the rows as read."""
    rows = matrices(work)["ext"]
    by = {(r["technique"], external.version(r)): r for r in rows}
    e = by[("ext:example", "1.0")]
    check(external.is_external(e) and not external.is_external(by[("direct", "")]),
          "ext:NAME rows are external, the built-in's not")
    check(external.label(e) == LABEL, f"label: {external.label(e)}")
    check(external.label(by[("ext:wrongsize", "unversioned")]) == "ext:wrongsize (external, version unversioned)",
          "a failure whose message names no command, nor any row of its external: its version alone: "
          + external.label(by[("ext:wrongsize", "unversioned")]))
    pair = external.annotate([dict(by[("ext:wrongsize", "unversioned")]),
                              dict(by[("ext:wrongsize", "unversioned")], status="ok",
                                   message="external command: ./bin/wrong --size 32")])
    check(external.label(pair[0]) == "ext:wrongsize (external, wrong unversioned)",
          f"such a failure takes the command from its external's other rows: {external.label(pair[0])}")
    check(external.group_renderer(e) == by[("direct", "")]["renderer"] != e["renderer"],
          f"ranked on its run's renderer ({external.group_renderer(e)}), its own kept ({e['renderer']})")
    check(all(schema.status(s) == s for s in external.FAILURES),
          f"the failures the report names are statuses gibench declares ({', '.join(external.FAILURES)})")
    check(source_hash.technique_hash(source_hash.Tree(), "ext:example") == "",
          "an external has no technique source hash in the tree")
    check(gpu_rows.Hashes().is_current(e), "an external row is current by hash (no sources): not stale")
    old = external.superseded(rows)
    check(list(old.values()) == ["1.0"] and id(by[("ext:example", "0.9")]) in old,
          "its version 0.9 row, older than 1.0 in the table, is superseded")
    check(answers.memory_cost(dict(e, mem_bytes="0")) is None and answers.memory_cost(e) is not None,
          "an external's memory 0 (none reported) is no memory cost")


def check_report_md(md, rows):
    head = md_table_rows(md, "## Which technique for which effect")
    check(len(head) == 1 and head[0]["component"] == "direct" and head[0]["scene"] == "furnace",
          f"one answer row, direct in the furnace ({len(head)})")
    front = head[0].get("least error for its time: the Pareto front, cheapest first (ms, error: RMSE over the "
                        "reference's mean, for glossy and caustics over a black image's; mean: the image's "
                        "mean over the reference's)", "") if head else ""
    check(f"{LABEL} 156 ms (reported by the program) 1.28e-07" in front,
          f"the external on the front, its program and version named, its time the program's: {front[:200]}")
    check("beaten: direct" in front, "ranked against the built-in in one group (direct beaten)")
    check("version=0.9" not in md.split("## Findings per paper")[0] and "0.9)" not in front,
          "the superseded version is not in the answer")
    for tech, (status, _) in FAILED.items():
        check(re.search(re.escape(tech) + r" \(external, [^)]*\) " + status, front) is not None,
              f"{tech} listed as not ranked with its status {status}")
    mem = head[0].get("for its memory (MB, the same)", "") if head else ""
    check(f"{LABEL} 3.1 MB (reported by the program)" in mem, f"memory the program's: {mem}")
    check("are reported by the program in its timings.json, not gibench's GL timer queries" in md,
          "the answer says where an external's times come from")
    cards = md_table_rows(md, "### ext")
    by = {(c["technique"], c["status"]): c for c in cards}
    numbers = ["GPU ms (warm median)", "first frame ms", "CPU ms", "memory MB", "RMSE",
               "RMSE without the noise [95%]", "RMSE / black image's", "rank: error, time", "rel RMSE", "SSIM",
               "FLIP", "HDR-FLIP", "ref spp"]
    ok = by.get((LABEL, "ok"))
    check(ok is not None and ok["GPU ms (warm median)"] == "155.6 (IQR 0) (reported by the program)"
          and ok["CPU ms"] == "not reported by the program" and ok["rank: error, time"] == "1, 1",
          "the external's matrix row: status ok (not stale), time the program's, ranked "
          f"({ok and ok['GPU ms (warm median)']})")
    stale = by.get(("ext:example (external, render.py 0.9)", "stale"))
    check(stale is not None and "superseded by version 1.0" in stale["settings"],
          f"the 0.9 row is stale by its version ({stale and stale['settings']})")
    for tech, (status, message) in FAILED.items():
        card = next((c for c in cards if c["technique"].startswith(tech + " (external, ")), None)
        check(card is not None and card["status"] == status and message in card["settings"],
              f"{tech}: status {card and card['status']}, its message shown")
        check(card is not None and all(card.get(k, "") == "" for k in numbers),
              f"{tech}: no number ({[card.get(k) for k in numbers if card.get(k)] if card else ''})")
    nan = next(r for r in rows if r["technique"] == "ext:nan")
    check(f"{float(nan['rmse']):.4g}" not in md, "the nonfinite row's RMSE of its finite pixels is nowhere")
    audit = md_table_rows(md, "## Energy audit")
    names = [a["technique"] for a in audit]
    check(names == ["direct", LABEL], f"the energy audit names it, its older version left out: {names}")
    check(f"| reference | {LABEL} | direct |" in md and "156 ms (reported by the program) · rel. error" in md,
          "the gallery names it and says whose time it is")
    check("6 rows are external renderers' (" in md and "a table's rows of an older version of it are stale" in md,
          "the reading guide says what an external row is")


def check_page(page):
    for tech, (status, message) in FAILED.items():
        m = re.search(r'<div class="row status-' + status + r'"><h4>furnace · ' + re.escape(tech)
                      + r' \(external, [^)]*\)[^<]*<span class="status">' + status + r"</span></h4>(.*?)<dl>(.*?)</dl>",
                      page, re.S)
        check(m is not None and message in m.group(1) and m.group(2) == "",
              f"page: {tech}'s block shows {status} and its message, no number")
    check(f'<span class="step" title="version=1.0">{LABEL} 156 ms (reported by the program)' in page,
          "page: the front's step names the external")


def check_plot_data(work):
    rows = [r for rs in matrices(work).values() for r in rs]
    for r in rows:  # as the report reads them: the older version's row stale
        if external.version(r) == "0.9":
            r["status"] = "stale"
    (key, t, _), = answers.answers(rows)
    names, _ = plot.answer_data(os.path.join(work, "answer.dat"), t, None)
    with open(os.path.join(work, "answer.dat")) as f:
        data = f.read()
    check(names == ["direct", LABEL], f"the answer plot's legend: {names}")
    check(plot.axis_note(t["rows"]) == "; ext: times reported by the program"
          and plot.axis_note([r for r in rows if not external.is_external(r)]) == "",
          "the answer plot's time axis says whose times the external's are")
    check(f'"{LABEL}"' in data, "the answer plot labels its front step")


def main():
    work = sys.argv[1]
    t0 = time.time()
    rows = make_results(work)
    check_rows_module(work)
    env = dict(os.environ, PYTHONPATH=HARNESS)
    p = subprocess.run([sys.executable, "-m", "reporting.report", work], capture_output=True, text=True, env=env)
    check(p.returncode == 0, f"the report is written ({p.stderr.strip()[-500:]})")
    if p.returncode == 0:
        with open(os.path.join(work, "REPORT.md")) as f:
            check_report_md(f.read(), rows)
        with open(os.path.join(work, "report", "index.html")) as f:
            check_page(f.read())
    check_plot_data(work)
    print(f"took {time.time() - t0:.1f} s")
    return verdict()


if __name__ == "__main__":
    sys.exit(main())
