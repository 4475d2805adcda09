"""External renderers' rows (README.md, "Bring your own renderer"; examples/external_renderer/README.md,
"The rows"): a matrix's `[external.NAME]` runs another program as a technique, and gibench writes its
rows beside the built-ins' in the matrix's CSV. This module is the report's one way to know such a row
and to name it.

A row is an external's when its technique is `ext:NAME` (a built-in's name is its folder's,
[a-z0-9_], never with a colon) or its backend is `external` (harness/app/run_rows.c writes both). From
the row alone:
- the version: `version=` in its params (the last parameter; `unversioned` where the matrix names
  none; the same text is in gl_version). A new version is new rows: the version is part of the row's
  identity, as a built-in's parameters are;
- the command: the message of an ok row (`external command: <command>`) or of a failure that names it
  (`external 'NAME' (<command>): ...`); a failure whose message does not (a wrong image size, NaN in
  the image) takes it from another row of the same external and version in its table (annotate);
- the program: the command's first word that is not an interpreter (`python3 render.py` -> render.py);
- the renderer column: what the program's timings.json says (else `<NAME> <version>`).

Its times (gpu_ms_*, cpu_ms, first_frame_ms), memory (mem_bytes) and renderer are the program's own,
read from its timings.json: not gibench's GL timer queries nor its memory ledger. The report says so
wherever it shows them (TIMES). Its error columns are gibench's, from the program's EXR against the same
reference as the built-ins': an external ranks beside the built-ins on error exactly as one of them.

Grouping: answers.py ranks rows that estimate one image on one renderer. The external ran in the same
`gibench run` as its table's built-in rows, on the same machine, so it is grouped under the renderer
of those rows (the built-in row of its table nearest it in time; its own renderer where the table has
no built-in row): annotate sets `_group_renderer`, group_renderer reads it.

Currency: an external has no sources in this tree, so no technique source hash (source_hash.py gives
none; its technique_hash column is a hash of command and version). It is current by its version
string: within a table, the version of the external's newest row (by timestamp) is current and its
other versions' rows are superseded (superseded).

A failed external row's status is one of FAILURES, its message the reason (the command's stderr tail):
the report shows the status and the message, never the numbers the row may hold (a `nonfinite` row
has an RMSE of the finite pixels)."""
import os
import re
import shlex
from datetime import datetime, timezone

PREFIX = "ext:"
BACKEND = "external"
# The statuses an external's failure writes (harness/app/external.c, README.md), beside those any row can have.
FAILURES = ("external_failed", "timeout", "readback_failed", "nonfinite")
TIMES = "reported by the program"
# Words that run a program rather than being it.
INTERPRETERS = {"sh", "bash", "dash", "zsh", "env", "exec", "nice", "stdbuf", "time", "node", "perl", "ruby",
                "uv", "uvx", "wine", "java", "julia", "Rscript", "mono", "dotnet", "lua", "php"}
_OK_MESSAGE = re.compile(r"^external command: (.*)$", re.S)
_FAIL_MESSAGE = re.compile(r"^external '[^']*' \((.*?)\)(?::| exited 0 but )", re.S)


def is_external(r):
    """Whether row r is an external renderer's."""
    return (r.get("technique") or "").startswith(PREFIX) or r.get("backend") == BACKEND


def name(r):
    """NAME of ext:NAME."""
    t = r.get("technique") or ""
    return t[len(PREFIX):] if t.startswith(PREFIX) else t


def version(r):
    """An external row's version text as the matrix wrote it (params `version=`, else gl_version);
    '' for a built-in's."""
    if not is_external(r):
        return ""
    for kv in (r.get("params") or "").split(";"):
        if kv.startswith("version="):
            return kv[len("version="):]
    return r.get("gl_version") or ""


def command_of_message(message):
    """The command a row's message names, or ''."""
    m = _OK_MESSAGE.match(message or "") or _FAIL_MESSAGE.match(message or "")
    return m.group(1).strip() if m else ""


def program(command):
    """The program a command runs: its first word that is not an interpreter, an option or a
    variable assignment, by its file name (`python3 /x/render.py --mode a` -> render.py)."""
    try:
        words = shlex.split(command or "")
    except ValueError:
        words = (command or "").split()
    for w in words:
        base = os.path.basename(w)
        if w.startswith("-") or re.fullmatch(r"[A-Za-z_][A-Za-z_0-9]*=.*", w) or base in INTERPRETERS \
                or re.fullmatch(r"(python|pypy)[0-9.]*", base):
            continue
        return base or w
    return os.path.basename(words[0]) if words else ""


def epoch(text):
    try:
        return datetime.strptime((text or "").strip(), "%Y-%m-%dT%H:%M:%SZ").replace(tzinfo=timezone.utc).timestamp()
    except ValueError:
        return None


def annotate(rows):
    """Marks a table's external rows in place: `_ext_command` (the external's command, from its own
    message or another row of the same external and version), `_group_renderer` (the renderer of the
    table's built-in row nearest it in time: the machine it ran on). Returns rows."""
    ext = [r for r in rows if is_external(r)]
    if not ext:
        return rows
    commands = {}
    for r in ext:
        c = command_of_message(r.get("message"))
        if c:
            commands.setdefault((r.get("technique"), version(r)), c)
    builtin = [(epoch(r.get("timestamp")), r["renderer"]) for r in rows
               if not is_external(r) and r.get("renderer")]
    for r in ext:
        r["_ext_command"] = command_of_message(r.get("message")) or commands.get((r.get("technique"), version(r)), "")
        if builtin:
            t = epoch(r.get("timestamp"))
            r["_group_renderer"] = min(builtin, key=lambda b: abs(b[0] - t) if b[0] is not None and t is not None
                                       else float("inf"))[1]
    return rows


def group_renderer(r):
    """The renderer a row ranks on (answers.group_key): an external's its table's built-ins'."""
    return r.get("_group_renderer") or r.get("renderer", "")


def command(r):
    return r.get("_ext_command") or command_of_message(r.get("message"))


def label(r):
    """The technique as the report names it: a built-in's name; an external's
    `ext:NAME (external, <program> <version>)` (`(external, version V)` where no row names its command)."""
    if not is_external(r):
        return r.get("technique", "")
    prog = program(command(r))
    return f"{r.get('technique', '')} (external, {prog + ' ' if prog else 'version '}{version(r)})"


def labels(rows):
    """{technique: its label} over rows, from its ok rows where it has any (an external at two
    versions there: both, joined by ' / ')."""
    out = {}
    for r in sorted(rows, key=lambda r: r.get("status") != "ok"):  # ok rows first (a stable sort)
        lab, t = label(r), r.get("technique", "")
        if t in out and (r.get("status") != "ok" or lab in out[t].split(" / ")):
            continue
        out[t] = (out[t] + " / " + lab) if t in out else lab
    return out


def failed(r):
    """Whether r is an external's row that failed (its status is the result: no number is shown)."""
    return is_external(r) and r.get("status") not in ("ok", "stale")


def times_note(r):
    """' (reported by the program)' after an external's time or memory, '' for a built-in's."""
    return f" ({TIMES})" if is_external(r) else ""


def reported_renderer(r):
    """The renderer an ok external row's program reported (its timings.json), or ''."""
    rend = r.get("renderer") or ""
    return "" if not is_external(r) or rend == f"{name(r)} {version(r)}" else rend


def superseded(rows):
    """{id(row): the current version} of the external rows of one table whose version is not the
    external's current one (the version of its newest row, by timestamp)."""
    newest = {}
    for r in rows:
        if is_external(r):
            t = epoch(r.get("timestamp")) or 0.0
            if r.get("technique") not in newest or t >= newest[r["technique"]][0]:
                newest[r["technique"]] = (t, version(r))
    return {id(r): newest[r["technique"]][1] for r in rows
            if is_external(r) and version(r) != newest[r["technique"]][1]}
