#!/usr/bin/env python3
"""The hash of a technique's sources: what a results row records (column technique_hash) so that the
report can tell whether the row still describes the code.

A technique's sources are the files of its folder (techniques/NAME/) and every file those name,
followed from file to file: C includes ("techniques/X/f.h", and the f.c beside a header: its
implementation), shader names in C ("X/f.frag") and shader includes ("common/f.glsl", "gl/bindings.h":
harness/gl/bindings.h; "f.h" beside the including file). Only sources count (.c .h .glsl .vert .frag .geom .comp): notes and tests in
a folder do not change a row; nor does techniques/technique.h, the interface, which a change that
matters to a technique's output also changes the technique's files for. The hash is SHA-256 over the
sorted paths and their bytes, 12 hex digits.

    python3 harness/reporting/source_hash.py --c OUT.c            the C table gibench is built with
    python3 harness/reporting/source_hash.py [--rev REV] NAME...  the hashes now (or at git revision REV)

The build and the report both call this file, so a row's hash and the current one are computed alike;
a row written before the column existed is judged by hashing its git_revision's files."""
import hashlib
import os
import re
import subprocess
import sys

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
EXTS = (".c", ".h", ".glsl", ".vert", ".frag", ".geom", ".comp")
BINDINGS = "harness/gl/bindings.h"
# "techniques/X/f.h" in a C include, "X/f.ext" in a shader name or a shader include.
REFERENCE = re.compile(r'"(?:techniques/)?([a-z_0-9]+)/([A-Za-z_0-9.]+)"')
# "f.h" in an include of a file of the same folder.
LOCAL = re.compile(r'#include\s+"([A-Za-z_0-9.]+)"')


def git_revision(root=ROOT):
    """The commit of root's checkout, marked -dirty when tracked files outside results/ differ (as
    gibench's git_revision); "unknown" outside a git checkout."""
    def git(*args):
        r = subprocess.run(["git", "-C", root] + list(args), stdout=subprocess.PIPE,
                           stderr=subprocess.DEVNULL, text=True)
        return r.stdout.strip() if r.returncode == 0 else ""
    rev = git("rev-parse", "--short=12", "HEAD") or "unknown"
    dirty = git("status", "--porcelain", "--untracked-files=no", "--", ".", ":(exclude)results")
    return rev + ("-dirty" if dirty and rev != "unknown" else "")


class Tree:
    """The project's files: the working tree (rev None) or those of a git revision."""

    def __init__(self, root=ROOT, rev=None):
        self.root, self.rev, self._blobs = root, rev, {}
        if rev is None:
            self.paths = []
            for d, _, files in os.walk(os.path.join(root, "techniques")):
                self.paths += [os.path.relpath(os.path.join(d, f), root) for f in files]
            self.paths += [BINDINGS] if os.path.exists(os.path.join(root, BINDINGS)) else []
        else:
            out = subprocess.run(["git", "-C", root, "ls-tree", "-r", "--name-only", rev, "--",
                                  "techniques", BINDINGS], capture_output=True, text=True, check=True)
            self.paths = out.stdout.split()

    def read(self, path):
        if self.rev is None:
            with open(os.path.join(self.root, path), "rb") as f:
                return f.read()
        if path not in self._blobs:
            self._blobs[path] = subprocess.run(["git", "-C", self.root, "show", f"{self.rev}:{path}"],
                                               capture_output=True, check=True).stdout
        return self._blobs[path]

    def folder_files(self, folder):
        prefix = f"techniques/{folder}/"
        return sorted(p for p in self.paths if p.startswith(prefix) and p.endswith(EXTS))


def referenced(tree, path, known):
    """The source files file PATH names (see the module's text), of those in `known`."""
    out, text = set(), tree.read(path).decode("utf-8", "replace")
    targets = [BINDINGS if (folder, name) == ("gl", "bindings.h") else f"techniques/{folder}/{name}"
               for folder, name in REFERENCE.findall(text)]
    targets += [f"{os.path.dirname(path)}/{name}" for name in LOCAL.findall(text)]
    for target in targets:
        if target in known:
            out.add(target)
            sibling = target[:-2] + ".c" if target.endswith(".h") else None
            if sibling in known:
                out.add(sibling)
    return out


def technique_files(tree, name):
    """The source files of technique NAME in tree, sorted (empty when it has no folder)."""
    known = {p for p in tree.paths if p.endswith(EXTS)}
    files = set(tree.folder_files(name))
    todo = list(files)
    while todo:
        for ref in referenced(tree, todo.pop(), known):
            if ref not in files:
                files.add(ref)
                todo.append(ref)
    return sorted(files)


def technique_hash(tree, name):
    """12 hex digits of SHA-256 over the paths and bytes of NAME's sources; "" without a folder."""
    files = technique_files(tree, name)
    if not files:
        return ""
    h = hashlib.sha256()
    for path in files:
        data = tree.read(path)
        h.update(path.encode() + b"\0" + str(len(data)).encode() + b"\0" + data)
    return h.hexdigest()[:12]


def technique_names(tree):
    """The techniques of the registry: the folders whose C files declare `.name = "FOLDER"`."""
    names = []
    for path in tree.paths:
        parts = path.split("/")
        if len(parts) == 3 and path.endswith(".c"):
            if re.search(r'\.name\s*=\s*"%s"' % re.escape(parts[1]), tree.read(path).decode()):
                names.append(parts[1])
    return sorted(set(names))


def c_table(tree):
    lines = ["/* Generated by harness/reporting/source_hash.py at build time: each technique's source hash. */",
             "#include <string.h>", "", "const char *gib_technique_source_hash(const char *name)", "{",
             "    static const char *const table[][2] = {"]
    lines += [f'        {{"{n}", "{technique_hash(tree, n)}"}},' for n in technique_names(tree)]
    lines += ["    };", "    for (size_t i = 0; i < sizeof table / sizeof table[0]; i++)",
              "        if (!strcmp(table[i][0], name))", "            return table[i][1];",
              '    return "";', "}", ""]
    return "\n".join(lines)


def main(argv):
    if len(argv) >= 3 and argv[1] == "--c":
        text = c_table(Tree())
        old = open(argv[2]).read() if os.path.exists(argv[2]) else None
        if text != old:  # unchanged: the file keeps its time, nothing recompiles
            with open(argv[2], "w") as f:
                f.write(text)
        return 0
    rev = None
    if len(argv) >= 3 and argv[1] == "--rev":
        rev, argv = argv[2], argv[2:]
    tree = Tree(rev=rev)
    for name in argv[1:] or technique_names(tree):
        print(name, technique_hash(tree, name))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
