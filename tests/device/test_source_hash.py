#!/usr/bin/env python3
"""A technique's source hash (harness/reporting/source_hash.py), on a copy of techniques/: it changes when a
file of its folder, of a folder it uses (ldm_ao uses techniques/ldm) or of techniques/common changes,
and not when another technique's file or a non-source file changes; the C table the build compiles
names every technique of the registry with its hash; and a git revision's hash equals the working
tree's for a file tree the revision holds unchanged. No GL."""
import os
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "harness"))
sys.path.insert(0, os.path.join(ROOT, "tests", "common"))
from reporting import source_hash as sh  # noqa: E402
from script_checks import check, verdict  # noqa: E402



def hashes(root):
    tree = sh.Tree(root)
    return {n: sh.technique_hash(tree, n) for n in ("lrsm", "ldm_ao", "ldm_indirect", "rsm_gather")}


def append(root, path, text):
    with open(os.path.join(root, path), "a") as f:
        f.write(text)


def main():
    work = tempfile.mkdtemp()
    try:
        shutil.copytree(os.path.join(ROOT, "techniques"), os.path.join(work, "techniques"))
        os.makedirs(os.path.join(work, "harness", "gl"))
        shutil.copy(os.path.join(ROOT, "harness", "gl", "bindings.h"), os.path.join(work, "harness", "gl"))
        h0 = hashes(work)
        check(h0 == hashes(ROOT), "a copy hashes as the tree it was copied from")
        check(all(len(v) == 12 for v in h0.values()), "12 hex digits each")
        append(work, "techniques/ldm/ldm.c", "\n/* changed */\n")
        h1 = hashes(work)
        check(h1["ldm_ao"] != h0["ldm_ao"] and h1["ldm_indirect"] != h0["ldm_indirect"],
              "a change in techniques/ldm changes ldm_ao's and ldm_indirect's hashes")
        check(h1["lrsm"] == h0["lrsm"] and h1["rsm_gather"] == h0["rsm_gather"],
              "and not lrsm's or rsm_gather's")
        with open(os.path.join(work, "techniques", "lrsm", "NOTES.md"), "w") as f:
            f.write("not a source\n")
        check(hashes(work)["lrsm"] == h0["lrsm"], "a non-source file in a folder changes nothing")
        append(work, "techniques/common/shader.h", "\n")
        h2 = hashes(work)
        check(all(h2[n] != h1[n] for n in h2), "a change in techniques/common changes every hash")
        table = sh.c_table(sh.Tree())
        names = sh.technique_names(sh.Tree())
        check({"lrsm", "vct", "ldm_ao", "direct"} <= set(names) and "ldm" not in names and "common" not in names,
              "the registry's techniques are found, the shared folders are not techniques")
        check(all(f'{{"{n}", "{sh.technique_hash(sh.Tree(), n)}"}}' in table for n in names),
              "the C table holds every technique's hash")
        head = subprocess.run(["git", "-C", ROOT, "rev-parse", "HEAD"], capture_output=True, text=True)
        dirty = subprocess.run(["git", "-C", ROOT, "status", "--porcelain", "--", "techniques",
                                "harness/gl/bindings.h"], capture_output=True, text=True)
        if head.returncode == 0 and not dirty.stdout.strip():
            rev = sh.Tree(ROOT, head.stdout.strip())
            check(all(sh.technique_hash(rev, n) == sh.technique_hash(sh.Tree(), n) for n in names),
                  "HEAD's files hash as the working tree's (the report's fallback for older rows)")
        else:
            print("skip HEAD comparison: not a git checkout, or techniques/ has local changes")
    finally:
        shutil.rmtree(work)
    return verdict("PASS: technique source hashes")


if __name__ == "__main__":
    sys.exit(main())
