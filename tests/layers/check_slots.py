#!/usr/bin/python3
"""Every GL slot under techniques/ has a name (ARCHITECTURE.md, "GL bindings").

Fails, naming file:line, on
  - a C call that takes a uniform location, buffer binding, texture unit or image unit whose slot
    argument starts with a literal integer (glUniform*(9, ...), glProgramUniform*(p, 9, ...),
    glBindBufferBase/Range(target, 8, ...), glBindTextureUnit(10, ...), glBindImageTexture(0, ...),
    and their multi-bind and sampler forms);
  - a GLSL layout(location = N) or layout(binding = N) with a literal N on a uniform, a sampler, an
    image or a buffer block (the locations of vertex inputs and fragment outputs are not slots);
  - a slots header (techniques/<name>/<name>_slots.h) or a shared-constants header (*_shared.h)
    with a line that is not a #define, a // comment, its include guard or an #include: the headers
    are read by C and GLSL alike.
The names live in harness/gl/bindings.h (shared slots) and the slots headers.

Usage: check_slots.py TECHNIQUES_DIR      check the tree
       check_slots.py --self-test         check that planted bare numbers are found
"""
import os
import re
import sys
import tempfile

C_EXT = (".c", ".h")
GLSL_EXT = (".glsl", ".vert", ".frag", ".geom", ".comp")
HEADER_SUFFIXES = ("_slots.h", "_shared.h")  # headers C and GLSL both include

# Call name -> index of the slot argument.
SLOT_ARG = [
    (re.compile(r"\bglProgramUniform\w*$"), 1),
    (re.compile(r"\bglUniform\w*$"), 0),
    (re.compile(r"\bglBindBuffers?(Base|Range)$"), 1),
    (re.compile(r"\bglBindTextureUnit$"), 0),
    (re.compile(r"\bglBindTextures$"), 0),
    (re.compile(r"\bglBindImageTextures?$"), 0),
    (re.compile(r"\bglBindSamplers?$"), 0),
]
CALL = re.compile(r"\b(gl\w+)\s*\(")
CAST = re.compile(r"^\(\s*(GLuint|GLint|unsigned|int|unsigned\s+int)\s*\)\s*")
LAYOUT = re.compile(r"\blayout\s*\(([^)]*)\)([^;{]*)")
LITERAL_SLOT = re.compile(r"\b(location|binding)\s*=\s*\d")
HEADER_LINE = re.compile(r"^\s*($|//|#define\s|#ifndef\s|#endif\b|#include\s)")


def blank_comments(text):
    """Comments replaced by spaces, newlines kept, so offsets still give line numbers; string
    literals are skipped over whole (a "/*" in a path is not a comment)."""
    def blank(m):
        s = m.group(0)
        return s if s[0] in "\"'" else re.sub(r"[^\n]", " ", s)
    return re.sub(r'"(?:\\.|[^"\\\n])*"|\'(?:\\.|[^\'\\\n])*\'|//[^\n]*|/\*.*?\*/', blank, text,
                  flags=re.S)


def arguments(text, start):
    """The top-level arguments of the call whose '(' is at text[start - 1]."""
    args, depth, cur, i = [], 0, "", start
    while i < len(text):
        ch = text[i]
        if ch in "([{":
            depth += 1
        elif ch in ")]}":
            if depth == 0:
                args.append(cur.strip())
                return args
            depth -= 1
        elif ch == "," and depth == 0:
            args.append(cur.strip())
            cur = ""
            i += 1
            continue
        cur += ch
        i += 1
    return args


def line_of(text, offset):
    return text.count("\n", 0, offset) + 1


def check_c(path, text):
    code = blank_comments(text)
    found = []
    for m in CALL.finditer(code):
        for name_re, index in SLOT_ARG:
            if not name_re.search(m.group(1)):
                continue
            args = arguments(code, m.end())
            if len(args) > index:
                slot = args[index]
                while CAST.match(slot):
                    slot = CAST.sub("", slot, count=1)
                if re.match(r"\d", slot):
                    found.append((line_of(code, m.start()),
                                  "%s(...) slot %s is a bare number" % (m.group(1), args[index])))
            break
    return found


def check_glsl(path, text):
    code = blank_comments(text)
    found = []
    for m in LAYOUT.finditer(code):
        qualifiers, declaration = m.group(1), m.group(2)
        words = declaration.split()
        if ("in" in words or "out" in words) and not ("uniform" in words or "buffer" in words):
            continue  # a vertex input or fragment output: its location is not a slot
        if LITERAL_SLOT.search(qualifiers):
            found.append((line_of(code, m.start()),
                          "layout(%s) is a bare number" % qualifiers.strip()))
    return found


def check_header(path, text):
    return [(n, "C/GLSL header line is not a #define or // comment: %s" % line.strip())
            for n, line in enumerate(text.split("\n"), 1) if not HEADER_LINE.match(line)]


def check_tree(root):
    problems, files = [], 0
    for dirpath, _, names in sorted(os.walk(root)):
        for name in sorted(names):
            path = os.path.join(dirpath, name)
            if name.endswith(C_EXT):
                checks = [check_c] + ([check_header] if name.endswith(HEADER_SUFFIXES) else [])
            elif name.endswith(GLSL_EXT):
                checks = [check_glsl]
            else:
                continue
            with open(path, encoding="utf-8") as f:
                text = f.read()
            files += 1
            for check in checks:
                for line, what in check(path, text):
                    problems.append("%s:%d: %s" % (path, line, what))
    return problems, files


# A scratch tree with bare numbers to find (file, line) and named slots to pass over.
PLANTED = {
    "t/t.c": [
        "void f(void)",
        "{",
        "    glUniform1f(9, 1.0f);",
        "    glBindBufferBase(GL_SHADER_STORAGE_BUFFER,",
        "                     8, b);",
        "    glBindTextureUnit(T_UNIT, t); /* glBindTextureUnit(3, t) */",
        "    glBindImageTexture((GLuint)0, t, 0, GL_TRUE, 0, GL_READ_ONLY, GL_R8);",
        "    glProgramUniform1i(p, 4, 1);",
        "    glUniform1i(T_LOC + 1, 2);",
        "    load(\"a/*.glsl\"); glUniform1i(5, 0); /* */",
        "}",
    ],
    "t/t.frag": [
        "layout(location = 0) out vec4 o;",
        "layout(location = 2) in vec2 uv;",
        "layout(location = 3) uniform float u_a;",
        "layout(std430, binding = 8) buffer B { uint b[]; };",
        "layout(binding = T_UNIT) uniform sampler2D s; // layout(binding = 1)",
        "layout(r8, binding = 1) writeonly uniform image3D img;",
    ],
    "t/t_slots.h": ["// ok", "#ifndef T", "#define T", "#define T_UNIT 10", "int x;", "#endif"],
    "t/t_shared.h": ["#define T_SIZE 64 // ok", "const int t = 1;"],
}
EXPECTED = {("t.c", 3), ("t.c", 4), ("t.c", 7), ("t.c", 8), ("t.c", 10), ("t.frag", 3),
            ("t.frag", 4), ("t.frag", 6), ("t_slots.h", 5), ("t_shared.h", 2)}


def self_test():
    with tempfile.TemporaryDirectory() as root:
        for rel, text in PLANTED.items():
            os.makedirs(os.path.join(root, os.path.dirname(rel)), exist_ok=True)
            with open(os.path.join(root, rel), "w") as f:
                f.write("\n".join(text) + "\n")
        problems, _ = check_tree(root)
        got = {(os.path.basename(p.split(":")[0]), int(p.split(":")[1])) for p in problems}
        if got != EXPECTED:
            print("FAIL self-test: found %s, expected %s" % (sorted(got), sorted(EXPECTED)))
            for p in problems:
                print("  " + p)
            return 1
    print("self-test: the %d planted bare numbers found, nothing else" % len(EXPECTED))
    return 0


def main(argv):
    if len(argv) == 2 and argv[1] == "--self-test":
        return self_test()
    if len(argv) != 2:
        print(__doc__)
        return 2
    problems, files = check_tree(argv[1])
    for p in problems:
        print(p)
    if problems:
        print("FAIL: %d GL slots under %s are bare numbers; name them in harness/gl/bindings.h or "
              "the technique's <name>_slots.h" % (len(problems), argv[1]))
        return 1
    print("%d files under %s: every GL slot named" % (files, argv[1]))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
