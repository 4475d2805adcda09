#!/usr/bin/env python3
"""The report's browser test (issue 18, section 1): builds a small results folder (the tiny matrix
run by the built gibench, plus the committed paper-table CSVs that hold the claims), writes claims.csv,
the plots and the report with harness/, then opens the page from the file system in headless
Chromium and checks
- every <img> loaded (the page's own ?check script writes the count into <pre id="image-check">,
  read back with --dump-dom; --virtual-time-budget lets the loads finish first);
- every row of the tiny matrix shows its reference, its image and its error map;
- the claims table has one row per claims.csv row;
- the check itself catches a broken image (a copy of the page with one missing file must say so);
and saves a screenshot (printed path). Exit 77 (ctest SKIP) only where no Chromium is installed.

usage: test_report.py --gibench PATH --work DIR
"""
import argparse
import csv
import os
import re
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
CLAIM_SOURCES = ["thesis_tables.csv", "lrsm_table2.csv", "lrsm_table3.csv", "lrsm_fig7.csv",
                 "lrsm_dynamic.csv", "ldm_figures_vs_ours.csv"]
failures = []


def check(cond, what):
    print(("ok    " if cond else "FAIL  ") + what)
    if not cond:
        failures.append(what)


def chromium():
    for name in ("chromium", "chromium-browser", "google-chrome"):
        path = shutil.which(name)
        if path:
            return path
    return None


def browser(exe, *args):
    cmd = [exe, "--headless", "--no-sandbox", "--disable-gpu", "--hide-scrollbars",
           "--allow-file-access-from-files", "--virtual-time-budget=20000"] + list(args)
    return subprocess.run(cmd, capture_output=True, text=True, timeout=120).stdout


def image_check(exe, page):
    """(images, loaded, broken, broken srcs) as the page's ?check script reports them."""
    dom = browser(exe, "--dump-dom", "file://" + page + "?check")
    m = re.search(r'<pre id="image-check">images (\d+) loaded (\d+) broken (\d+)\n?([^<]*)</pre>', dom)
    if not m:
        return None, dom
    return (int(m.group(1)), int(m.group(2)), int(m.group(3)), m.group(4).strip()), dom


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--gibench", required=True)
    ap.add_argument("--work", required=True)
    a = ap.parse_args()
    exe = chromium()
    if not exe:
        print("SKIP: no Chromium installed (Debian package `chromium`): the report's browser test "
              "cannot run here")
        return 77
    work = os.path.abspath(a.work)
    shutil.rmtree(work, ignore_errors=True)
    results = os.path.join(work, "results")
    os.makedirs(results)
    for name in CLAIM_SOURCES:
        src = os.path.join(ROOT, "results", name)
        if os.path.exists(src):
            shutil.copy(src, results)
    subprocess.run([a.gibench, "run", os.path.join(HERE, "report_tiny.matrix"), "--out", results,
                    "--cache", os.path.join(work, "cache")], check=True)
    py = sys.executable
    subprocess.run([py, os.path.join(ROOT, "harness", "plot.py"), results, "--out",
                    os.path.join(results, "plots")], check=True)
    subprocess.run([py, os.path.join(ROOT, "harness", "claims.py"), results], check=True)
    subprocess.run([py, os.path.join(ROOT, "harness", "report.py"), results], check=True)
    page = os.path.join(results, "report", "index.html")
    check(os.path.exists(page) and os.path.exists(os.path.join(results, "REPORT.md")),
          "report.py wrote report/index.html and REPORT.md")
    with open(page) as f:
        src = f.read()
    check("http://" not in src and "https://" not in src, "the page links nothing outside the file system")

    with open(os.path.join(results, "report_tiny.csv"), newline="") as f:
        rows = list(csv.DictReader(f))
    check(len(rows) == 3 and all(r["status"] == "ok" for r in rows), "the tiny matrix ran: 3 rows ok")
    figures = re.findall(r'<div class="row[^"]*">(.*?)</div></div>', src, re.S)
    check(len(figures) == len(rows), f"one row block per CSV row ({len(figures)} for {len(rows)})")
    for r, block in zip(rows, figures):
        caps = re.findall(r"<figcaption>([^<]*)</figcaption>", block)
        check(caps[:3] == ["reference", "technique", "error map"],
              f"{r['technique']} {r['params']}: reference, image and error map side by side ({caps})")
        check("ref noise" in block, f"{r['technique']}: the reference's noise beside the error")
        if "flip" in r:  # rows with FLIP columns also have the FLIP map (harness/app/util.c)
            check("FLIP map" in caps and "FLIP" in block, f"{r['technique']}: the FLIP map and mean shown")

    n_img = len(re.findall(r"<img ", src))
    got, dom = image_check(exe, page)
    check(got is not None, "the page's image check ran in Chromium")
    if got:
        images, loaded, broken, which = got
        check(images == n_img and images >= 3 * 3 + 1,
              f"Chromium saw every image of the page ({images} of {n_img}; 3 rows x 3 and a plot at least)")
        check(loaded == images and broken == 0, f"every image loaded ({loaded} of {images}) {which}")
        with open(os.path.join(results, "claims.csv"), newline="") as f:
            n_claims = len(list(csv.DictReader(f)))
        with open(os.path.join(results, "claims.csv"), newline="") as f:
            same = [c for c in csv.DictReader(f) if c["renderer"] == rows[0]["renderer"]]
        if same:  # the tiny run recorded this renderer's machine in results/history.sqlite
            check(all(c["cores"].isdigit() for c in same),
                  f"claims on {rows[0]['renderer']} name the cores the history recorded ({same[0]['cores']})")
        in_dom = len(re.findall(r'<tr class="claim ', dom))
        check(n_claims > 0 and in_dom == n_claims,
              f"claims table: {in_dom} rows for {n_claims} rows of claims.csv")

    # The check must be able to fail: the same page with one image whose file is absent.
    bad = os.path.join(results, "report", "broken_check.html")
    with open(bad, "w") as f:
        f.write(src.replace("<pre id=\"image-check\"></pre>",
                            "<pre id=\"image-check\"></pre><img src=\"../images/absent.png\" alt=\"x\">"))
    got, _ = image_check(exe, bad)
    check(got is not None and got[2] == 1 and "absent.png" in got[3],
          f"the image check reports a missing image as broken ({got and got[:3]})")
    os.remove(bad)

    shot = os.path.join(work, "report_screenshot.png")
    browser(exe, "--window-size=1280,2600", "--screenshot=" + shot, "file://" + page + "?open=report_tiny")
    with open(shot, "rb") as f:
        check(f.read(8) == b"\x89PNG\r\n\x1a\n", f"screenshot saved: {shot}")
    print(f"{len(failures)} failed" if failures else "all passed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
