#!/usr/bin/env python3
"""The report's browser test: builds a small results folder (the tiny matrix run by the built
gibench), writes claims.csv judged on the committed results' runs (claims --runs), the plots and the
report with harness/, then opens the page from the file system in headless
Chromium and checks
- every <img> loaded (the page's own ?check script writes the count into <pre id="image-check">,
  read back with --dump-dom; --virtual-time-budget lets the loads finish first);
- every row of the tiny matrix shows its reference, its image and its error map;
- the answer table comes first and has one row per component and scene that two techniques estimate
  in the CSVs (counted here from the CSVs, not by harness/reporting/answers.py), in the HTML and in REPORT.md;
- the gallery: every cell is an image that loaded or, where its file is absent, the labelled
  placeholder (one image's PNG and shipped copy removed must turn into a placeholder, not a broken
  image); every cell links its shipped WebP copy under gallery/, and with images/ moved away (as on
  a fresh clone) the gallery shows the same cells, none broken;
- the gallery's comparison: driven by keys (split, pick A and B, zoom, exposure), its images decode
  and its numbers are the CSV's;
- the claims are grouped: machine-independent ones first, the orders of times next (as many as
  claims.csv's kind time_order), then the papers' absolute GPU times in
  collapsed sections (the HTML) and a section at the end (REPORT.md), every claims.csv row once;
- the check itself catches a broken image (a copy of the page with one missing file must say so);
- the Sequences section: a sequence (report_tiny_sequence.matrix) has its row and its animation, an
  animated WebP with one frame per frame of the sequence (its ANMF chunks counted), which Chromium
  loads at its stated size and plays (the page's ?check script decodes it with the browser's own
  ImageDecoder: animated, 4 frames, not all alike; headless Chromium's virtual time does not advance
  an <img>'s animation, so looking at it twice would not tell; the decoding is awaited off the main
  thread, so this answer is read over the DevTools pipe in real time, devtools_pipe.py); a still
  image in its place must fail that check;
and saves screenshots of the first screen and of an opened matrix (printed paths). Exit 77 (ctest
SKIP) only where no Chromium is installed.

usage: test_report.py --gibench PATH --work DIR
"""
import argparse
import csv
import os
import re
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "harness"))
from devtools_pipe import element_text  # noqa: E402
from reporting.report_screenshot import find_chromium  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
failures = []


def check(cond, what):
    print(("ok    " if cond else "FAIL  ") + what)
    if not cond:
        failures.append(what)


BROWSER_FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--hide-scrollbars",
                 "--allow-file-access-from-files"]


def browser(exe, *args):
    cmd = [exe] + BROWSER_FLAGS + ["--virtual-time-budget=20000"] + list(args)
    return subprocess.run(cmd, capture_output=True, text=True, timeout=120).stdout


def image_check(exe, page):
    """(images, loaded, broken, broken srcs, placeholders) as the page's ?check script reports them."""
    dom = browser(exe, "--dump-dom", "file://" + page + "?check")
    m = re.search(r'<pre id="image-check">images (\d+) loaded (\d+) broken (\d+) placeholders (\d+)'
                  r'\n?([^<]*)</pre>', dom)
    if not m:
        return None, dom
    return (int(m.group(1)), int(m.group(2)), int(m.group(3)), m.group(5).strip(), int(m.group(4))), dom


def expected_answers(results):
    """{(component, scene)} that two or more techniques estimate in the runs tables: rows ok, with a
    finite error, against a reference that is not black (what the answer table must show)."""
    techs, black = {}, {}
    for name in os.listdir(results):
        if not name.endswith(".csv") or name.endswith("_passes.csv"):
            continue
        with open(os.path.join(results, name), newline="") as f:
            rows = list(csv.DictReader(f))
        if not rows or "component" not in rows[0] or "black_rmse" not in rows[0]:
            continue
        for r in rows:
            k = (r["component"], r["scene"])
            try:
                ok = r["status"] == "ok" and float(r["rmse"]) == float(r["rmse"])
            except ValueError:
                ok = False
            if ok:
                techs.setdefault(k, set()).add(r["technique"])
                black.setdefault(k, []).append(float(r["black_rmse"] or "nan") == 0)
    return {k for k, t in techs.items() if len(t) >= 2 and not all(black[k])}


def check_answer(src, md, results):
    """The answer table: first on the page and in REPORT.md, a row per expected (component, scene)."""
    want = expected_answers(results)
    table = re.search(r'<table class="answers">(.*?)</table>', src, re.S)
    got = set(re.findall(r'<tr class="answer[^"]*" data-component="([^"]*)" data-scene="([^"]*)"',
                         table.group(1) if table else ""))
    check(bool(want) and got == want, f"answer table: a row per component and scene two techniques "
          f"estimate ({sorted(got)} for {sorted(want)})")
    check(table is not None and src.index('class="answers"') < src.index('id="claims-h"')
          and src.index('id="findings"') < src.index('id="claims-h"'),
          "the answer and the findings per paper come before everything else on the page")
    lines = md.splitlines()
    heads = [l for l in lines if l.startswith("## ")]
    check(heads[:2] == ["## Which technique for which effect", "## Findings per paper"],
          f"REPORT.md opens with the answer, then the findings ({heads[:2]})")
    rows = [l for l in lines[:lines.index("## Findings per paper")] if l.startswith("| ") and " --- " not in l]
    md_keys = {tuple(c.strip() for c in l.split("|")[1:3]) for l in rows[1:]}
    check(md_keys == want, f"REPORT.md's answer table: a row per expected group ({sorted(md_keys)})")


def check_claims(src, md, claims):
    """The claims that do not depend on the machine first, then the orders of times, then the
    absolute GPU times, collapsed; each once."""
    mi = re.search(r'<table id="claims">(.*?)</table>', src, re.S)
    orders = re.search(r'<table id="claims-orders-table">(.*?)</table>', src, re.S)
    # each paper's absolute times: its <details> up to its table's end (a long reason is a nested
    # <details class="more">, so the first </details> is not the paper's)
    absolute = re.findall(r'<details class="absolute"( open)?>(.*?)</table>', src, re.S)
    in_mi = len(re.findall(r'<tr class="claim ', mi.group(1))) if mi else 0
    in_orders = len(re.findall(r'<tr class="claim ', orders.group(1))) if orders else 0
    in_abs = sum(len(re.findall(r'<tr class="claim ', body)) for _, body in absolute)
    kinds = [c.get("kind") for c in claims]
    check(mi is not None and in_mi + in_orders + in_abs == len(claims) and in_abs > 0 and
          in_orders == kinds.count("time_order") > 0,
          f"claims grouped: {in_mi} machine-independent + {in_orders} orders of times + {in_abs} absolute "
          f"times = {len(claims)} rows")
    check(orders is not None and src.index('<table id="claims">') < src.index('<table id="claims-orders-table">')
          < src.index('<details class="absolute"'), "the orders of times come between the two")
    check(all(not opened for opened, _ in absolute), "the absolute GPU times are collapsed")
    check(mi is not None and absolute and src.index('<table id="claims">') < src.index('<details class="absolute"'),
          "machine-independent claims come first")
    heads = [l for l in md.splitlines() if l.startswith("## ")]
    check(heads[-1] == "## The papers' absolute GPU times", f"REPORT.md ends with the absolute times ({heads[-1]})")


def gallery_cells(src):
    """Per gallery cell: ('img', src) or ('placeholder', the missing file)."""
    out = []
    for sec in re.findall(r'<section class="gallery".*?</section>', src, re.S):
        for cell in re.findall(r"<td>(.*?)</td>", sec, re.S):
            img = re.search(r'<img src="([^"]*)"', cell)
            hold = re.search(r'<div class="placeholder" data-missing="([^"]*)"', cell)
            if img or hold:
                out.append(("img", img.group(1)) if img else ("placeholder", hold.group(1)))
    return out


def reporting(module, *args, **kw):
    """`python3 -m reporting.<module> ARGS` from the repository's harness/, as the Makefile runs it."""
    env = dict(os.environ, PYTHONPATH=os.path.join(ROOT, "harness"))
    subprocess.run([sys.executable, "-m", "reporting." + module] + list(args), check=True, env=env, **kw)


def regenerate(results):
    reporting("report", results, stdout=subprocess.DEVNULL)


def source_png(results, shipped):
    """The run's PNG under images/ that a shipped gallery copy (gallery/...webp) was made from."""
    rel_path = os.path.relpath(shipped, os.path.join(results, "gallery"))
    return os.path.join(results, "images", os.path.splitext(rel_path)[0] + ".png")


def check_placeholder(exe, results, page, cells):
    """A gallery image whose files are absent (the run's PNG and the shipped copy) becomes the
    labelled placeholder naming the PNG, not a broken image: both moved away, the report written
    again, then put back."""
    page_dir = os.path.dirname(page)
    victim = next((os.path.normpath(os.path.join(page_dir, src)) for _, src in cells[1:2]), None)
    if not victim or not os.path.exists(victim):
        check(False, f"a gallery image to remove ({victim})")
        return
    png = source_png(results, victim)
    moved = [p for p in (victim, png) if os.path.exists(p)]
    aside = tempfile.mkdtemp(prefix="aside_", dir=os.path.dirname(os.path.abspath(results)))
    for i, p in enumerate(moved):  # outside results/: the report prunes what it does not show
        os.rename(p, os.path.join(aside, str(i)))
    try:
        regenerate(results)
        with open(page) as f:
            holders = [m for k, m in gallery_cells(f.read()) if k == "placeholder"]
        got, _ = image_check(exe, page)
    finally:
        for i, p in enumerate(moved):
            os.rename(os.path.join(aside, str(i)), p)
        os.rmdir(aside)
        regenerate(results)
    want = os.path.relpath(png, results)
    check(holders == [want], f"an absent gallery image is a placeholder naming its file ({holders})")
    check(got is not None and got[2] == 0 and got[4] >= 1,
          f"the placeholder is no broken image (broken {got and got[2]}, placeholders {got and got[4]})")


def check_compare(exe, results, page, src):
    """The gallery's comparison, driven by keys in Chromium (the page's ?check script presses them
    on the first group and writes what it sees into <pre id="compare-check">): one per group, an
    option per image of the group, the split moved by Left (50 -> 45, the clip follows), 2 and
    Shift+1 pick A and B, + zooms, e raises the exposure, both images decode, and A's numbers are
    its CSV row's (the time as the report prints it)."""
    text = element_text(exe, BROWSER_FLAGS, "file://" + page + "?check", "compare-check") or ""
    got = dict(line.split(" ", 1) for line in text.splitlines() if " " in line)
    sections = re.findall(r'<section class="gallery".*?</section>', src, re.S)
    first = sections[0] if sections else ""
    options = re.findall(r'<select class="cmp-pick-a">(.*?)</select>', first, re.S)
    n_options = len(re.findall(r"<option ", options[0])) if options else 0
    check(got.get("compares", "").split() == ["%d" % len(sections), "options", "%d" % n_options]
          and n_options == 5, f"a comparison per gallery group, an option per image ({got.get('compares')})")
    check(got.get("split") == "45 clip inset(0px 55% 0px 0px)", f"Left moves the split ({got.get('split')})")
    check(got.get("A") == "1 B 0", f"2 picks A, Shift+1 picks B ({got.get('A')})")
    check(got.get("zoom") == "2 ev 1 filter brightness(2)", f"+ zooms, e adds a stop ({got.get('zoom')})")
    check((got.get("decoded") or "").startswith("1 widths 32 32"), f"A and B decode ({got.get('decoded')})")
    tech = re.search(r'<option value="[^"]*" data-nums="[^"]*"(?: selected)?>2 ([^<]*)</option>',
                     options[0] if options else "")
    with open(os.path.join(results, "report_tiny.csv"), newline="") as f:
        rows = [r for r in csv.DictReader(f) if tech and r["technique"] == tech.group(1)]
    ms = float(rows[0]["gpu_ms_median"]) if rows else None
    want = (f"{ms:.2g}" if ms < 10 else f"{ms:.0f}") + " ms" if ms is not None else "?"
    check(len(rows) == 1 and (got.get("nums") or "").startswith(want),
          f"A's numbers are its row's ({got.get('nums')}; the CSV: {want})")


def check_shipped_gallery(exe, results, page, cells):
    """The gallery as a fresh clone has it: every cell links its shipped WebP copy under gallery/,
    and with the run's images/ folder moved away the page still shows every cell (none a
    placeholder, none broken)."""
    page_dir = os.path.dirname(page)
    files = [os.path.normpath(os.path.join(page_dir, src)) for k, src in cells if k == "img"]
    shipped = [f for f in files if f.startswith(os.path.join(results, "gallery") + os.sep)
               and f.endswith(".webp") and os.path.exists(f)]
    check(files and shipped == files, f"every gallery cell links its shipped WebP copy ({len(shipped)} "
          f"of {len(files)})")
    images = os.path.join(results, "images")
    os.rename(images, images + ".aside")
    try:
        regenerate(results)
        with open(page) as f:
            fresh = gallery_cells(f.read())
        got, _ = image_check(exe, page)
    finally:
        os.rename(images + ".aside", images)
        regenerate(results)
    check(fresh == cells, f"without images/ (a fresh clone) the gallery shows the same cells "
          f"({sum(k == 'img' for k, _ in fresh)} images of {len(cells)})")
    check(got is not None and got[2] == 0, f"and none is broken ({got and got[:3]})")


def webp_frames(path):
    """The frames of an animated WebP: its ANMF chunks (RIFF, little-endian sizes, even-padded)."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:4] != b"RIFF" or data[8:12] != b"WEBP":
        return 0
    n, pos = 0, 12
    while pos + 8 <= len(data):
        size = int.from_bytes(data[pos + 4:pos + 8], "little")
        n += data[pos:pos + 4] == b"ANMF"
        pos += 8 + size + (size & 1)
    return n


def animation_check(exe, page):
    """(animations, sized, playing) as the page's ?check script reports them, read once the script
    wrote its line (the decoding is asynchronous work that --dump-dom's virtual time does not wait
    for, so the page is read over the DevTools pipe, in real time, for up to 120 s)."""
    text = element_text(exe, BROWSER_FLAGS, "file://" + page + "?check", "animation-check")
    m = re.fullmatch(r"animations (\d+) sized (\d+) playing (\d+)", text or "")
    return tuple(int(x) for x in m.groups()) if m else None


def check_sequences(exe, results, page, src):
    with open(os.path.join(results, "report_tiny_sequence.csv"), newline="") as f:
        rows = list(csv.DictReader(f))
    check(len(rows) == 1 and rows[0]["status"] == "ok" and rows[0]["sequence"] == "4",
          "the tiny sequence ran: 1 row ok with 4 frames")
    table = re.search(r'<table id="sequences-table">(.*?)</table>', src, re.S)
    check(table is not None and table.group(1).count("<tr>") == 2,
          "the Sequences section has a row for the sequence")
    anims = re.findall(r'<img class="animation"[^>]* src="([^"]+)"', src)
    check(len(anims) == 1, f"the sequence's animation is on the page ({anims})")
    if not anims:
        return
    path = os.path.normpath(os.path.join(os.path.dirname(page), anims[0]))
    check(os.path.exists(path) and webp_frames(path) == 4,
          f"the animation is an animated WebP of 4 frames ({webp_frames(path) if os.path.exists(path) else 'absent'})")
    got = animation_check(exe, page)
    check(got == (1, 1, 1), f"Chromium loads the animation at its size and it plays ({got})")
    still = os.path.join(os.path.dirname(page), "still_check.html")
    ref = rows[0]["image"] + "_f00.png"
    with open(still, "w") as f:
        f.write(src.replace(anims[0], "../images/report_tiny_sequence/seq/" + ref))
    got = animation_check(exe, still)
    check(got is not None and got[2] == 0, f"a still image in its place does not play ({got})")
    os.remove(still)


def check_cones(results, src, md):
    """The cone study's section: one row per gathered scene, technique and voxel_res, each beside
    its scene's ideal gather."""
    path = os.path.join(results, "cone_study.csv")
    if not os.path.exists(path):
        check("Each cone against" not in md, "no cone study, no cone section")
        return
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    gathers = [r for r in rows if r["cone"] == "gather" and r["technique"] != "ideal"]
    table = re.search(r'<table class="cones">(.*?)</table>', src, re.S)
    check(table is not None and table.group(1).count("<tr>") == len(gathers) + 1,
          f"the cone section has a row per gather of cone_study.csv ({len(gathers)})")
    ideal = {r["scene"]: r for r in rows if r["technique"] == "ideal"}
    for g in gathers[:1]:
        i = ideal.get(g["scene"])
        line = f'| {g["scene"]} | {g["technique"]} | {g["voxel_res"]} | {g["mean_ratio"]} |'
        check(line in md and (i is None or f'{i["mean_ratio"]}, {i["rel_rmse"]}' in md),
              f"REPORT.md sets {g['technique']}'s gather on {g['scene']} beside the ideal gather")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--gibench", required=True)
    ap.add_argument("--work", required=True)
    a = ap.parse_args()
    exe = find_chromium()
    if not exe:
        print("SKIP: no Chromium installed (Debian package `chromium`): the report's browser test "
              "cannot run here")
        return 77
    work = os.path.abspath(a.work)
    shutil.rmtree(work, ignore_errors=True)
    results = os.path.join(work, "results")
    os.makedirs(results)
    cones = os.path.join(ROOT, "results", "cone_study.csv")
    if os.path.exists(cones):
        shutil.copy(cones, results)
    for matrix in ("report_tiny.matrix", "report_tiny_sequence.matrix"):
        subprocess.run([a.gibench, "run", os.path.join(HERE, matrix), "--out", results,
                        "--cache", os.path.join(work, "cache")], check=True)
    reporting("plot", results, "--out", os.path.join(results, "plots"))
    # The papers' claims, judged on the committed results' runs (read, not copied: the report would
    # show their matrices), written into this folder's claims.csv, its cores from this folder's history.
    reporting("claims", results, "--runs", os.path.join(ROOT, "results"))
    reporting("report", results)
    page = os.path.join(results, "report", "index.html")
    check(os.path.exists(page) and os.path.exists(os.path.join(results, "REPORT.md")),
          "report.py wrote report/index.html and REPORT.md")
    with open(page) as f:
        src = f.read()
    check("http://" not in src and "https://" not in src, "the page links nothing outside the file system")

    with open(os.path.join(results, "report_tiny.csv"), newline="") as f:
        rows = list(csv.DictReader(f))
    check(len(rows) == 4 and all(r["status"] == "ok" for r in rows), "the tiny matrix ran: 4 rows ok")
    tiny = re.search(r'<details class="matrix" id="m-report_tiny">(.*?)</details>\n', src, re.S)
    figures = re.findall(r'<div class="row[^"]*">(.*?)</div></div>', tiny.group(1) if tiny else "", re.S)
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
    with open(os.path.join(results, "claims.csv"), newline="") as f:
        claims = list(csv.DictReader(f))
    with open(os.path.join(results, "REPORT.md")) as f:
        md = f.read()
    if got:
        images, loaded, broken, which, holders = got
        check(images == n_img and images >= 4 * 3 + 1,
              f"Chromium saw every image of the page ({images} of {n_img}; 4 rows x 3 and a plot at least)")
        check(loaded == images and broken == 0, f"every image loaded ({loaded} of {images}) {which}")
        same = [c for c in claims if c["renderer"] == rows[0]["renderer"]]
        if same:  # the tiny run recorded this renderer's machine in results/history.sqlite
            check(all(c["cores"].isdigit() for c in same),
                  f"claims on {rows[0]['renderer']} name the cores the history recorded ({same[0]['cores']})")
        in_dom = len(re.findall(r'<tr class="claim ', dom))
        check(len(claims) > 0 and in_dom == len(claims),
              f"claims tables: {in_dom} rows for {len(claims)} rows of claims.csv")
    check_answer(src, md, results)
    check_claims(src, md, claims)
    cells = gallery_cells(src)
    check(len(cells) == 3 + 2 and all(k == "img" for k, _ in cells),
          f"gallery: the reference and both ao techniques, their error maps beneath, every file present "
          f"({len(cells)} cells)")

    # The check must be able to fail: the same page with one image whose file is absent.
    bad = os.path.join(results, "report", "broken_check.html")
    with open(bad, "w") as f:
        f.write(src.replace("<pre id=\"image-check\"></pre>",
                            "<pre id=\"image-check\"></pre><img src=\"../images/absent.png\" alt=\"x\">"))
    got, _ = image_check(exe, bad)
    check(got is not None and got[2] == 1 and "absent.png" in got[3],
          f"the image check reports a missing image as broken ({got and got[:3]})")
    os.remove(bad)

    check_cones(results, src, md)
    check_placeholder(exe, results, page, cells)
    check_shipped_gallery(exe, results, page, cells)
    check_compare(exe, results, page, src)
    check_sequences(exe, results, page, src)

    first = os.path.join(work, "report_first_screen.png")
    browser(exe, "--window-size=1280,900", "--screenshot=" + first, "file://" + page)
    shot = os.path.join(work, "report_screenshot.png")
    browser(exe, "--window-size=1280,2600", "--screenshot=" + shot, "file://" + page + "?open=report_tiny")
    for path in (first, shot):
        with open(path, "rb") as f:
            check(f.read(8) == b"\x89PNG\r\n\x1a\n", f"screenshot saved: {path}")
    print(f"{len(failures)} failed" if failures else "all passed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
