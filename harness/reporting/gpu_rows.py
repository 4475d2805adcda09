"""The rows of the device runs (results/gpu/<gpu>/, older runs in results/gpu/<gpu>/older/<rev>/),
each judged before the report takes a time from it:

- current: its technique's source hash (column technique_hash; for a row written before the column,
  the hash of its git_revision's files) equals the hash of the sources now (source_hash.py). A stale
  row describes code that has changed since and is shown as such, never used. An external
  renderer's row (external.py) has no sources here: it is current by its version (in its params).
- held down: a sample of the GPU's state in the row's window (from the previous row's timestamp to
  its own, gpu_samples.csv) names a reason the clocks are held down other than idle (power or
  thermal caps, slowdowns, application clocks). Such a row is not used.
- clock moved: a sample in that window has the SM clock below 97% of its maximum (the GPU idles
  down between runs while the CPU loads a scene). Its timed frames may still have run at full
  clock: the row is used when their spread (IQR) is within 5% of their median.

A valid row is ok, current, not held down and steady by that rule; `valid` keeps the newest valid
row of each run and component."""
import csv
import glob
import os
from datetime import datetime, timezone

from reporting import external  # noqa: E402
from reporting import source_hash  # noqa: E402
from reporting.schema import read_csv  # noqa: E402

IDLE_REASONS = {0x0, 0x1}  # none; GPU idle (nvidia-smi clocks_event_reasons)
CLOCK_FLOOR = 0.97
SPREAD_LIMIT = 0.05
KEY = ("matrix", "scene", "camera", "technique", "component", "params", "width", "height", "time")


def run_folders(results):
    """[(gpu, folder)] of every device run under results/gpu, each GPU's newest run first."""
    out = []
    for gpu_dir in sorted(glob.glob(os.path.join(results, "gpu", "*"))):
        if not os.path.isdir(gpu_dir):
            continue
        gpu = os.path.basename(gpu_dir)
        out.append((gpu, gpu_dir))
        out += [(gpu, d) for d in sorted(glob.glob(os.path.join(gpu_dir, "older", "*")), reverse=True)
                if os.path.isdir(d)]
    return out


def epoch(text):
    """Seconds since 1970 of a row's timestamp (2026-11-27T17:35:28Z) or a sample's
    (2026/11/27 17:35:24.575, UTC on the device machine); None when unreadable."""
    for fmt in ("%Y-%m-%dT%H:%M:%SZ", "%Y/%m/%d %H:%M:%S.%f", "%Y/%m/%d %H:%M:%S"):
        try:
            return datetime.strptime(text.strip(), fmt).replace(tzinfo=timezone.utc).timestamp()
        except ValueError:
            pass
    return None


def samples(folder):
    """[(seconds, sm MHz, max sm MHz, reasons bit mask)] of the folder's gpu_samples.csv."""
    out = []
    path = os.path.join(folder, "gpu_samples.csv")
    if not os.path.exists(path):
        return out
    with open(path, newline="") as f:
        rows = csv.reader(f)
        head = [h.strip() for h in next(rows, [])]
        if "timestamp" not in head:
            return out
        reason = next((i for i, h in enumerate(head) if "reasons" in h), None)
        for r in rows:
            try:
                t = epoch(r[0])
                sm, mx = float(r[head.index("clocks.sm")]), float(r[head.index("clocks.max.sm")])
                bits = int(r[reason].strip(), 16) if reason is not None else 0
            except (ValueError, IndexError):
                continue
            if t is not None:
                out.append((t, sm, mx, bits))
    return out


def window_state(smp, t0, t1):
    """(held down, clock moved, samples seen) over [t0 - 1, t1 + 1] (timestamps are whole seconds)."""
    inside = [s for s in smp if t0 - 1 <= s[0] <= t1 + 1]
    held = any(s[3] not in IDLE_REASONS for s in inside)
    moved = any(s[1] < CLOCK_FLOOR * s[2] for s in inside)
    return held, moved, len(inside)


class Hashes:
    """Technique source hashes now and at past revisions, computed once each."""

    def __init__(self, root=source_hash.ROOT):
        self.root, self.now, self.past = root, source_hash.Tree(root), {}

    def current(self, technique):
        return source_hash.technique_hash(self.now, technique)

    def is_current(self, r):
        """Whether row r describes the sources now: its technique hash equals theirs. An external
        renderer's row has no sources here (its technique_hash is a hash of its command and
        version): it is current by its version string, part of its params, so it is never stale
        by hash (external.superseded judges its version within a table)."""
        if external.is_external(r):
            return True
        now = self.current(r.get("technique", ""))
        return bool(now) and self.of_row(r) == now

    def of_row(self, r):
        if r.get("technique_hash"):
            return r["technique_hash"]
        rev = r.get("git_revision", "")
        key = (rev, r.get("technique"))
        if key not in self.past:
            try:
                tree = source_hash.Tree(self.root, rev) if rev and "dirty" not in rev else None
                self.past[key] = source_hash.technique_hash(tree, r["technique"]) if tree else ""
            except Exception:  # a revision this clone lacks: the row cannot be shown current
                self.past[key] = ""
        return self.past[key]


def judge(r, smp, start, hashes):
    """The row's judgement fields (see the module's text), added in place."""
    try:
        med, iqr = float(r.get("gpu_ms_median") or "nan"), float(r.get("gpu_ms_iqr") or "nan")
    except ValueError:
        med = iqr = float("nan")
    end = epoch(r.get("timestamp", ""))
    held, moved, seen = window_state(smp, start or end or 0, end or 0) if end else (False, False, 0)
    r["_current"] = hashes.is_current(r)
    r["_held_down"], r["_clock_moved"], r["_samples"] = held, moved, seen
    r["_spread_ok"] = med == med and iqr == iqr and iqr <= SPREAD_LIMIT * med
    r["_valid"] = (r.get("status") == "ok" and r["_current"] and not held
                   and (not moved or r["_spread_ok"]))
    why = [w for w, bad in (("not ok", r.get("status") != "ok"), ("stale", not r["_current"]),
                            ("held down", held), ("clock moved, spread over 5%",
                                                  moved and not r["_spread_ok"])) if bad]
    r["_why"] = ", ".join(why)
    return end


def load(results, hashes=None):
    """Every runs row of every device run, judged, with _gpu (the folder's GPU name) and _folder."""
    hashes = hashes or Hashes()
    out = []
    for gpu, folder in run_folders(results):
        smp = samples(folder)
        for path in sorted(glob.glob(os.path.join(folder, "*.csv"))):
            rows = read_csv(path)
            if not rows or "gpu_ms_median" not in rows[0] or path.endswith("_passes.csv"):
                continue
            start = None
            for r in rows:
                r["_gpu"], r["_folder"] = gpu, folder
                end = judge(r, smp, start, hashes)
                start = end
                out.append(r)
    return out


def newest_run(results, loaded=None):
    """(gpu, folder, its judged rows) of the newest device run whose rows are mostly valid (the
    run the report and the claims read), or None."""
    loaded = load(results) if loaded is None else loaded
    for gpu, folder in run_folders(results):
        mine = [r for r in loaded if r["_folder"] == folder]
        if mine and sum(r["_valid"] for r in mine) * 2 > len(mine):
            return gpu, folder, mine
    return None


def valid(rows):
    """{KEY values: the newest valid row} (rows as `load` returns them, each GPU's newest run
    first: the first valid row met is kept)."""
    out = {}
    for r in rows:
        if r.get("_valid"):
            out.setdefault(tuple(r.get(k, "") for k in KEY) + (r["_gpu"],), r)
    return out


def summary_counts(rows):
    """{gpu: {rows, ok, valid, stale, held_down, clock_moved, revisions}} for a report's line."""
    out = {}
    for r in rows:
        c = out.setdefault(r["_gpu"], {"rows": 0, "ok": 0, "valid": 0, "stale": 0, "held_down": 0,
                                        "clock_moved": 0, "revisions": set()})
        c["rows"] += 1
        c["ok"] += r.get("status") == "ok"
        c["valid"] += bool(r["_valid"])
        c["stale"] += not r["_current"]
        c["held_down"] += r["_held_down"]
        c["clock_moved"] += r["_clock_moved"]
        c["revisions"].add(r.get("git_revision", ""))
    return out


GPU_TIE = 0.05  # two GPU medians within 5% tie (the auto warm-up settles frames to within 5%)


def size_map(llvm_rows, gpu_rows_of_matrix):
    """{(width, height) of the paper profile: (width, height) the GPU ran}: the i-th size of one
    pairs with the i-th of the other (the paper profile shrinks each of the papers' sizes alike),
    {} when the two list different numbers of sizes."""
    a = sorted({(int(r["width"]), int(r["height"])) for r in llvm_rows})
    b = sorted({(int(r["width"]), int(r["height"])) for r in gpu_rows_of_matrix})
    return dict(zip(a, b)) if len(a) == len(b) else {}


def timed_copies(rows, results, gpu_loaded=None):
    """For the paper profile's rows (error on llvmpipe), copies timed by the newest valid GPU row of
    the same run at the papers' image size: gpu_ms_* from the GPU, renderer the GPU's, and
    time_source naming the GPU and that size; the error columns stay the llvmpipe row's. A copy is
    made only where every ok row of its (matrix, scene, component, size, instant) has one, so that a
    group is timed on one machine or not at all."""
    loaded = gpu_loaded if gpu_loaded is not None else load(results)
    by_matrix = {}
    for r in loaded:
        if r["_valid"]:
            by_matrix.setdefault((r["matrix"], r["_gpu"]), []).append(r)
    paper = [r for r in rows if r.get("profile") == "paper" and r.get("status") == "ok"]
    out = []
    for (matrix, gpu), grs in by_matrix.items():
        mine = [r for r in paper if r.get("matrix") == matrix]
        sizes = size_map(mine, grs)
        index = {}
        for g in grs:  # each GPU's newest valid row first (load's order)
            index.setdefault((g["scene"], g["camera"], g["technique"], g["component"], g["params"],
                              g["time"], int(g["width"]), int(g["height"])), g)
        groups = {}
        for r in mine:
            w, h = sizes.get((int(r["width"]), int(r["height"])), (None, None))
            g = index.get((r["scene"], r["camera"], r["technique"], r["component"], r["params"],
                           r["time"], w, h))
            groups.setdefault((r["scene"], r["component"], r["width"], r["time"]), []).append((r, g))
        # an external's copy ranks on the GPU its run's built-in rows name (external.group_renderer)
        host = next((g["renderer"] for g in grs if not external.is_external(g) and g.get("renderer")), None)
        for pairs in groups.values():
            if any(g is None for _, g in pairs):
                continue
            for r, g in pairs:
                ext = {"_group_renderer": host or g["renderer"]} if external.is_external(r) else {}
                out.append(dict(r, gpu_ms_median=g["gpu_ms_median"], gpu_ms_iqr=g["gpu_ms_iqr"],
                                gpu_ms_min=g["gpu_ms_min"], gpu_ms_max=g["gpu_ms_max"],
                                renderer=g["renderer"], time_resolution=str(GPU_TIE), **ext,
                                time_source=f"{gpu} at {g['width']}x{g['height']} (the papers' size), "
                                            f"gibench {g['git_revision']}; error on {r['renderer']}"))
    return out
