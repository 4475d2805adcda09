#!/usr/bin/env python3
"""The committed report's gallery as a fresh clone shows it (HEAD's REPORT.md and files): every gallery group of
results/REPORT.md has its reference and at least two techniques, each an image that links a
committed file under results/gallery/ (no placeholder), and the folder holds no file the report
does not show. A report written from a results folder whose headline groups were timed on a GPU
once showed only placeholders (the gallery looked the group's rows up under the GPU's renderer,
where only llvmpipe rows exist): this reads what is committed, so that cannot ship again.

usage: test_committed_gallery.py ROOT"""
import re
import subprocess
import sys

root = sys.argv[1] if len(sys.argv) > 1 else "."
failures = []


def check(ok, what):
    print(("ok    " if ok else "FAIL  ") + what)
    if not ok:
        failures.append(what)


def git(*args):
    return subprocess.run(["git", "-C", root] + list(args), capture_output=True, text=True,
                          check=True).stdout


# HEAD's files, not the working tree's: a local `make reproduce` rewrites both
tracked = set(git("ls-tree", "-r", "--name-only", "HEAD", "results/gallery").split())
md = git("show", "HEAD:results/REPORT.md")
gallery = md[md.index("## Gallery"):]
gallery = gallery[:gallery.index("\n## ", 4)]
groups = re.split(r"\n### ", gallery)[1:]
check(len(groups) > 0, f"REPORT.md has gallery groups ({len(groups)})")
linked = set()
for g in groups:
    title = g.splitlines()[0]
    images = re.findall(r"!\[([^\]]*)\]\(([^)]*)\)", g)
    missing = re.findall(r"\*([^*]*): not written here\*", g)
    pictures = [(what, path) for what, path in images if what != "error map"]
    linked |= {"results/" + path for _, path in images}
    check(not missing and len(pictures) >= 3 and pictures[0][0] == "reference",
          f"{title}: the reference and {len(pictures) - 1} techniques, no placeholder ({missing[:2]})")
    check(all(("results/" + p) in tracked for _, p in images),
          f"{title}: every image a committed file under results/gallery "
          f"({[p for _, p in images if ('results/' + p) not in tracked][:2]})")
check(tracked <= linked, f"results/gallery holds only what the report shows ({sorted(tracked - linked)[:3]})")
print("FAIL" if failures else "PASS", f"{len(failures)} failure(s)")
sys.exit(1 if failures else 0)
