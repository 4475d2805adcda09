"""The results tables as gibench defines them (harness/app/schema.h), for every report script.

The columns of a matrix's runs table (RESULTS/<matrix>.csv) and passes table (<matrix>_passes.csv),
which columns make a row's identity and a run's, and the names of a row's images are defined once,
in C where the rows are written; the build exports them as build/schema.json (`gibench describe`),
read here with what else the binary knows: each technique's outputs, passes and parameters, the
row statuses, the parameters that set a component's reference, the cone set, the software
renderers. A name the scripts use for one of those (a pass a table reads, a status a claim tests)
goes through pass_name or status, which refuse a name the binary does not declare, so a renamed
pass fails the report at once instead of leaving a table empty. This module is the scripts' one way to
- read a CSV (read_csv), a matrix's runs (runs_table, matrices) and its passes (passes_of);
- know a row (row_key: its identity in its table; run_key: the run it belongs to, shared by the
  run's rows, one per component, and its passes rows);
- read a parameter (params, param: from the wide column where the table has one, else from the
  `params` column, which holds every parameter);
- name a row's images (image_name);
- turn CSV text into numbers and numbers into text (fnum, fmt).

The schema file: $GIBENCH_SCHEMA, else build/schema.json beside harness/ (make build writes it), else
the newest build*/schema.json there.
"""
import csv
import glob
import json
import os

from reporting import external  # noqa: E402 (rows only: it imports no other module of the package)

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))  # the repository
_schema = None


def schema():
    """The exported schema (a dict, read once)."""
    global _schema
    if _schema is None:
        path = os.environ.get("GIBENCH_SCHEMA") or os.path.join(ROOT, "build", "schema.json")
        if not os.environ.get("GIBENCH_SCHEMA") and not os.path.exists(path):
            # another build folder of this tree (build-asan, ...): the schema is the sources'
            found = sorted(glob.glob(os.path.join(ROOT, "build*", "schema.json")), key=os.path.getmtime)
            path = found[-1] if found else path
        if not os.path.exists(path):
            raise SystemExit(f"schema.py: {path} not found: build gibench first (make build writes "
                             "it; or set GIBENCH_SCHEMA to the output of `gibench describe`)")
        with open(path) as f:
            _schema = json.load(f)
    return _schema


def columns(table="runs"):
    """The base column names of the runs or the passes table, in order."""
    return [c["name"] for c in schema()[table]["columns"]]


def cone_weights():
    """The diffuse cone set's weights in the gather (harness/base/cone_set.h), cone 0 first."""
    return list(schema()["cone_set"]["weights"])


def reference_params():
    """{component: ((technique parameter, the reference's default), ...)}: the parameters that set
    a component's reference (the techniques' gib_ref_binding), as gibench exports them."""
    return {comp: tuple((b["param"], float(b["default"])) for b in binds)
            for comp, binds in schema()["reference_params"].items()}


def is_software_renderer(renderer):
    """Whether a GL_RENDERER names a software rasteriser (history.c's rule, the schema's list)."""
    return any(w.lower() in (renderer or "").lower() for w in schema()["software_renderers"])


def technique(name):
    """The exported descriptor of technique `name` (outputs, passes, params, presets)."""
    for t in schema()["techniques"]:
        if t["name"] == name:
            return t
    raise SystemExit(f"schema.py: gibench declares no technique '{name}'")


def pass_name(technique_name, name):
    """`name`, checked to be a pass technique_name declares (or one the runner times itself)."""
    if name not in technique(technique_name)["passes"] + schema()["harness_passes"]:
        raise SystemExit(f"schema.py: technique '{technique_name}' declares no pass '{name}' "
                         f"(its passes: {', '.join(technique(technique_name)['passes'])})")
    return name


def status(name):
    """`name`, checked to be one of the row statuses gibench declares (harness/base/status.h)."""
    if name not in [s["name"] for s in schema()["statuses"]]:
        raise SystemExit(f"schema.py: gibench declares no row status '{name}'")
    return name


def key_columns(table="runs", key="row_key"):
    """The names of the columns of a row's identity (row_key) or its run's (run_key)."""
    return [c["name"] for c in schema()[table]["columns"] if c[key]]


# ---- numbers ------------------------------------------------------------------------------------

def fnum(text):
    """A finite float from CSV text (or a number), or None."""
    try:
        x = float(text)
    except (TypeError, ValueError):
        return None
    return x if x == x and abs(x) != float("inf") else None


def fmt(x, digits=4, missing=""):
    """A number (or CSV text holding one) to `digits` significant digits; None or empty text is
    `missing`; text that is no number is returned as it is."""
    if isinstance(x, str):
        try:
            x = float(x)
        except ValueError:
            return x or missing
    if x is None:
        return missing
    return f"{x:.{digits}g}"


# ---- reading ------------------------------------------------------------------------------------

def read_csv(path):
    """Every row of a CSV as a dict of text, [] when the file is absent."""
    if not os.path.exists(path):
        return []
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def header(path):
    with open(path, newline="") as f:
        return next(csv.reader(f), [])


def is_runs_table(names):
    """Whether a header is a runs table's: the first column, every identity column and status."""
    base = columns("runs")
    return names[:1] == base[:1] and set(key_columns("runs")) | {"status"} <= set(names)


def runs_table(results, matrix, ok_only=False):
    """The rows of RESULTS/<matrix>.csv ([] when absent); only status ok with ok_only."""
    rows = read_csv(os.path.join(results, matrix + ".csv"))
    return [r for r in rows if r["status"] == "ok"] if ok_only else rows


def matrices(results):
    """{matrix: rows} for every runs table in RESULTS (not *_passes, nor other tables), by name; an
    external renderer's rows marked with what their table says of them (external.annotate)."""
    out = {}
    for name in sorted(os.listdir(results)):
        path = os.path.join(results, name)
        if not name.endswith(".csv") or name.endswith("_passes.csv") or not is_runs_table(header(path)):
            continue
        out[name[:-4]] = external.annotate(read_csv(path))
    return out


def passes_of(results, matrix):
    """{run_key: {pass: median ms}} of RESULTS/<matrix>_passes.csv (times that are no finite
    number left out)."""
    out = {}
    for p in read_csv(os.path.join(results, matrix + "_passes.csv")):
        ms = fnum(p["ms_median"])
        if ms is not None:
            out.setdefault(run_key(p), {})[p["pass"]] = ms
    return out


# ---- identity -----------------------------------------------------------------------------------

def row_key(r, table="runs"):
    """A row's identity in its table: a table holds each once."""
    return tuple(r.get(k, "") for k in key_columns(table, "row_key"))


def run_key(r):
    """The run a runs row (one of its components) or a passes row belongs to."""
    return tuple(r.get(k, "") for k in key_columns("runs", "run_key"))


def runs(rows):
    """One row per run (a run writes one row per output component), the first of each."""
    seen, out = set(), []
    for r in rows:
        k = run_key(r)
        if k not in seen:
            seen.add(k)
            out.append(r)
    return out


# ---- parameters ---------------------------------------------------------------------------------

def parse_params(text):
    """{name: float} of a `params` text ("name=value;..."); a preset's value stays its name."""
    p = schema()["params"]
    out = {}
    for kv in (text or "").split(p["separator"]):
        if p["assign"] in kv:
            k, v = kv.split(p["assign"], 1)
            try:
                out[k] = float(v)
            except ValueError:
                out[k] = v
    return out


def papers_rows(rows):
    """The rows a verdict is judged on: those at the papers' settings (profile `paper`) where the
    table has any, else all of them (the quick profile's, which the verdict then names)."""
    paper = [r for r in rows if r.get("profile") == "paper"]
    return paper or list(rows)


def preset(r):
    """The named reading a row ran (`default`: the technique's defaults; `paper`: its paper's
    literal reading)."""
    return str(params(r).get("preset", r.get("preset") or "default"))


def params(r):
    """Every parameter of a row, {name: float}."""
    return parse_params(r.get(schema()["params"]["column"], ""))


def param(r, name, default=None):
    """One parameter of a row: its wide column where the table has one, else from `params`."""
    wide = r.get(name)
    if wide:
        try:
            return float(wide)
        except ValueError:
            pass
    return params(r).get(name, default)


# ---- image names --------------------------------------------------------------------------------

def fnv1a64(text):
    """64-bit FNV-1a over the text and its NUL, 16 hex digits (harness/base/hash.c)."""
    h = 0xcbf29ce484222325
    for b in text.encode() + b"\0":
        h = ((h ^ b) * 0x100000001b3) & 0xFFFFFFFFFFFFFFFF
    return f"{h:016x}"


def _fill(template, fields, replace):
    out = template
    for k, v in fields.items():
        out = out.replace("{" + k + "}", v)
    for a, b in replace.items():
        out = out.replace(a, b)
    return out


def image_name(r):
    """The name (no extension) `gibench run` gives a row's images in DIR/images/<matrix>/."""
    spec = schema()["image_name"]
    t = float(r.get("time") or 0)
    fields = {"scene": r["scene"], "technique": r["technique"], "params": r["params"],
              "width": r["width"], "height": r["height"], "component": r["component"],
              "at": f"_t{t:g}" if t != 0.0 else "", "params_hash": fnv1a64(r["params"])}
    name = _fill(spec["template"], fields, spec["replace"])
    if len(name) > spec["long_when_over"]:
        name = _fill(spec["long_template"], fields, spec["replace"])
    return name


# ---- writing ------------------------------------------------------------------------------------

def write_csv(path, rows, cols):
    """Writes rows (dicts) under the header cols, a missing value empty. Returns the path."""
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=cols)
        w.writeheader()
        for r in rows:
            w.writerow({c: r.get(c, "") for c in cols})
    return path
