#!/usr/bin/env python3
"""Summarises a device run (harness/device/time_all_papers.sh) beside the papers' own numbers.

    PYTHONPATH=harness python3 -m reporting.gpu_summary results/gpu/NAME [--paper-values DIR] > results/gpu/NAME/SUMMARY.md

Reads the folder's gpu.txt (the machine), clocks.csv and gpu_samples.csv (the GPU's state per matrix
and every 200 ms), and its runs and passes tables, and writes Markdown: the machine and its raster
limit; which rows the report may use (harness/reporting/gpu_rows.py: current, not held down, steady); the clocks
per matrix; the LRSM paper's Tables 3 and 2, the LDM paper's Figs. 8-10 and the thesis' Tables 4.1-4.5
with this GPU's times beside the papers'; what each pass kind costs a unit of work; the cross-paper
indirect light. Every time is the median of the warm frames with its interquartile range; the cold
first frame stands apart. Quality is not here: the run is timing only (the paper profile's llvmpipe
rows in results/ judge error)."""
import csv
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
from reporting import gpu_rows  # noqa: E402
from reporting import ldm_tables  # noqa: E402
from reporting import lrsm_tables  # noqa: E402
from reporting import thesis_tables  # noqa: E402

PAPER_VALUES = os.path.join(HERE, "..", "..", "..", "shared", "paper-values")
# Where a card runs vertex and fragment work on a part of its chip only: what its times of raster
# passes then stand for (NVIDIA H100 Tensor Core GPU Architecture whitepaper: of the GH100's TPCs,
# two per GPU are graphics-capable; the H200 is the same GH100 chip with more memory).
RASTER_LIMITS = {
    "H100": "only 2 TPCs of the chip run vertex and fragment shaders (GH100); compute runs on every SM",
    "H200": "only 2 TPCs of the chip run vertex and fragment shaders (GH100, as the H100); compute "
            "runs on every SM",
}


def read_csv(path):
    return gpu_rows.read_csv(path)


def param(row, key):
    for kv in row["params"].split(";"):
        k, _, v = kv.partition("=")
        if k == key:
            return v
    return ""


def num(v):
    try:
        return float(v)
    except (TypeError, ValueError):
        return None


def ms(row, key="gpu_ms_median", iqr="gpu_ms_iqr"):
    m, q = num(row.get(key)), num(row.get(iqr))
    return "" if m is None else f"{m:.2f}" + (f" ({q:.2f})" if q is not None else "")


def machine(folder):
    """The lines of gpu.txt that name the machine: GPU, driver, clocks, CPUs, GL renderer."""
    keep = []
    path = os.path.join(folder, "gpu.txt")
    lines = open(path).read().splitlines() if os.path.exists(path) else []
    for i, line in enumerate(lines):
        if line.startswith("== nvidia-smi --query-gpu") and i + 2 < len(lines):
            keep += [lines[i + 1], lines[i + 2]]
        elif line.startswith(("== nproc", "model name", "renderer:", "EGL device")):
            keep.append(line.lstrip("= "))
    return keep


def raster_limit(renderer):
    for card, text in RASTER_LIMITS.items():
        if card in renderer:
            return f"{card}: {text}"
    return ""


def judged(folder):
    """The folder's runs rows, judged (gpu_rows), by matrix."""
    rows = [r for r in gpu_rows.load(os.path.dirname(os.path.dirname(os.path.abspath(folder))))
            if os.path.abspath(r["_folder"]) == os.path.abspath(folder)]
    by = {}
    for r in rows:
        by.setdefault(r["matrix"], []).append(r)
    return by


def validity(by):
    rows = [r for rs in by.values() for r in rs]
    n = len(rows)
    count = lambda f: sum(1 for r in rows if f(r))  # noqa: E731
    return [f"- {n} rows from gibench {', '.join(sorted({r['git_revision'] for r in rows}))}: "
            f"{count(lambda r: r['status'] == 'ok')} ok, "
            f"{count(lambda r: r['status'] == 'out_of_memory')} out of memory (plans over the "
            "technique's memory budget, by design).",
            f"- Usable by the report (harness/reporting/gpu_rows.py): {count(lambda r: r['_valid'])}. "
            f"Stale (technique changed since): {count(lambda r: not r['_current'])}. Held down "
            f"(a throttle reason other than idle): {count(lambda r: r['_held_down'])}. Clock below 97% "
            f"of its maximum somewhere in the row's window: {count(lambda r: r['_clock_moved'])}, of which "
            f"{count(lambda r: r['_clock_moved'] and not r['_spread_ok'])} also have a spread over 5% "
            "and are left out.",
            f"- Warm-up until three frames agree within 5%: "
            f"{min(int(r['warmup']) for r in rows)}-{max(int(r['warmup']) for r in rows)} frames, "
            f"then {sorted({r['frames'] for r in rows})[0]} timed frames."]


def clocks(folder, by):
    rows = read_csv(os.path.join(folder, "clocks.csv"))
    if not rows:
        return ["(no clocks.csv: nvidia-smi was not there)"]
    reasons = next((k for k in rows[0] if "reasons" in k), None)
    pairs = {}
    for r in rows:
        pairs.setdefault(r["matrix"], {}).setdefault(r["when"], r)
    out = ["| matrix | rows | seconds | SM MHz before / after (max) | power W | temp C | reasons | "
           "marked |", "|---|---|---|---|---|---|---|---|"]
    for name, p in pairs.items():
        b, a = p.get("before"), p.get("after")
        rs = by.get(name, [])
        if not b or not a or not rs:
            continue
        t0, t1 = gpu_rows.epoch(b["timestamp"]), gpu_rows.epoch(a["timestamp"])
        if t1 - t0 < 1:  # a resumed call that found every row done
            continue
        marked = sum(1 for r in rs if r["_held_down"] or r["_clock_moved"])
        out.append(f"| {name} | {len(rs)} | {t1 - t0:.0f} | {b['clocks.sm'].strip()} / "
                   f"{a['clocks.sm'].strip()} ({b['clocks.max.sm'].strip()}) | "
                   f"{b['power.draw'].strip()} / {a['power.draw'].strip()} | "
                   f"{b['temperature.gpu'].strip()} / {a['temperature.gpu'].strip()} | "
                   f"{b[reasons].strip() if reasons else ''} / {a[reasons].strip() if reasons else ''} | "
                   f"{marked} |")
    return out


def passes(folder, matrix):
    return read_csv(os.path.join(folder, f"{matrix}_passes.csv"))


def table3(folder, paper):
    """LRSM Table 3: per-stage times on Sponza at 1280x720, each preset, with the pass kind."""
    want = {("lrsm", "512"): "LRSM", ("vct", "256"): "VCT", ("vct", "512"): "VCT"}
    stage_of = {ours: paper for paper, ours in lrsm_tables.TABLE3_STAGE.items()}
    paper_ms = {(p["method"], p["gpu"], p["stage"]): p["ms"] for p in paper}
    out = ["| method | preset | voxel_res | stage | kind | this GPU ms (IQR; cold first) | "
           "GTX 770 (paper) | Iris Pro (paper) |", "|---|---|---|---|---|---|---|---|"]
    rows = sorted(passes(folder, "lrsm_stages"), key=lambda r: (r["technique"], param(r, "preset"),
                                                                int(param(r, "voxel_res") or 0)))
    for r in rows:
        method = want.get((r["technique"], param(r, "voxel_res")))
        if not method:
            continue
        stage = stage_of.get(r["pass"], r["pass"])
        g = paper_ms.get((method, "GTX770", stage), "")
        i = paper_ms.get((method, "Iris Pro", stage), "")
        out.append(f"| {method} | {param(r, 'preset') or 'default'} | {param(r, 'voxel_res')} | {stage} "
                   f"| {r.get('kind', '')} | {ms(r, 'ms_median', 'ms_iqr')}; {num(r['ms_first']):.1f} "
                   f"| {g} | {i} |")
    return out


def table2(folder, paper):
    rows = [r for r in read_csv(os.path.join(folder, "lrsm_memory.csv")) if r["component"] == "indirect"]
    names = {"sibenik": "SIBENIK", "sponza_glossy": "SPONZA", "sponza_dragon": "SPONZA DRAGON"}
    out = ["| scene | technique | preset | voxel_res | D | this GPU frame ms (IQR) | planned MB | "
           "driver MB | paper total MB | paper GTX 770 ms |", "|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        res, depth = param(r, "voxel_res"), param(r, "layers_depth")
        p = next((p for p in paper if p["scene"] == names.get(r["scene"]) and
                  p["occlusion_voxel_res"] == res and (not depth or p["layers_depth"] == depth)), None)
        lrsm = p and r["technique"] == "lrsm"
        head = f"| {r['scene']} | {r['technique']} | {param(r, 'preset') or 'default'} | {res} | {depth} |"
        if r["status"] != "ok":
            out.append(f"{head} {r['status']} | | | {p['total_mb'] if lrsm else ''} | "
                       f"{p['gtx770_ms'] if lrsm else ''} |")
            continue
        drv = f"{float(r['driver_mem_bytes']) / 1e6:.1f}" if r.get("driver_mem_bytes") else ""
        out.append(f"{head} {ms(r)} | {float(r['mem_bytes']) / 1e6:.1f} | {drv} | "
                   f"{p['total_mb'] if lrsm else ''} | {p['gtx770_ms'] if lrsm else ''} |")
    return out


def table(header, lines):
    """A Markdown table: its header cells, then its rows' cells."""
    return ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)] + \
        ["| " + " | ".join(str(c) for c in cells) + " |" for cells in lines]


def ldm(folder, pv):
    path = os.path.join(pv, "ldm_figures.csv")
    if not os.path.exists(path):
        return ["(no ldm_figures.csv among the paper values)"]
    lines = [(rec["figure"], rec["scene"], rec["method"], rec["paper_settings"],
              f"{rec['paper_ms']} ({rec['paper_gpu']})",
              "" if num(rec.get("our_ms")) is None else f"{num(rec['our_ms']):.1f}",
              rec.get("our_settings", "not run")) for rec in ldm_tables.ldm_rows(folder, path)]
    return table(("figure", "scene", "method", "paper's settings", "paper ms (GPU)", "this GPU ms",
                  "ours run"), lines)


STAGES = ("split", "gather", "tracing", "splat", "frame")


def thesis(folder, pv):
    path = os.path.join(pv, "thesis_tables.csv")
    if not os.path.exists(path):
        return ["(no thesis_tables.csv among the paper values)"]
    paper_keys = ("paper_split_ms", "paper_gather_ms", "paper_tracing_ms", "paper_splat_ms", "paper_frame_ms")
    our_keys = ("our_split_ms", "our_gather_ms", "our_tracing_ms", "our_splat_ms", "our_frame_ms")
    lines = [(rec["table"], rec["paper_scene"], rec["resolution"], rec["ray_resolution"],
              " / ".join(rec.get(k, "") for k in paper_keys),
              " / ".join(rec.get(k, "") or "-" for k in our_keys),
              f"{rec.get('status', '')} {rec.get('note', '')}")
             for rec in thesis_tables.rows_for(folder, thesis_tables.thesis_rows(path))[0]]
    stages = " / ".join(STAGES)
    return table(("table", "scene", "size", "rays", f"thesis {stages} ms", f"this GPU {stages} ms",
                  "status"), lines)


def work_rates(folder):
    """Per pass kind, the work done per microsecond (median over passes): raster passes' fragment
    invocations and compute passes' invocations, from the pipeline statistics of every passes table."""
    rates = {"raster": [], "compute": []}
    for name in sorted(os.listdir(folder)):
        if not name.endswith("_passes.csv"):
            continue
        for r in read_csv(os.path.join(folder, name)):
            t = num(r.get("ms_median"))
            if not t or t < 0.05:
                continue
            if r.get("kind") == "raster" and num(r.get("fragment_invocations")):
                rates["raster"].append(num(r["fragment_invocations"]) / (t * 1e3))
            elif r.get("kind") == "compute" and num(r.get("compute_invocations")):
                rates["compute"].append(num(r["compute_invocations"]) / (t * 1e3))
    out = ["| pass kind | passes | invocations per microsecond, median (quartiles) |", "|---|---|---|"]
    for kind, v in rates.items():
        if not v:
            continue
        v.sort()
        q = lambda f: v[min(len(v) - 1, int(f * len(v)))]  # noqa: E731
        out.append(f"| {kind} | {len(v)} | {q(0.5):.0f} ({q(0.25):.0f}-{q(0.75):.0f}) |")
    return out


def indirect(folder):
    rows = [r for r in read_csv(os.path.join(folder, "thesis_indirect.csv"))
            if r["component"] == "indirect" and r["status"] == "ok"]
    out = ["| scene | size | technique | parameters | this GPU ms (IQR) |", "|---|---|---|---|---|"]
    for r in sorted(rows, key=lambda r: (r["scene"], int(r["width"]), float(r["gpu_ms_median"]))):
        short = ";".join(kv for kv in r["params"].split(";") if kv.split("=")[0] in
                         ("vpl_count", "directions", "voxel_res", "preset"))
        out.append(f"| {r['scene']} | {r['width']}x{r['height']} | {r['technique']} | {short} | {ms(r)} |")
    return out


def main(argv):
    if len(argv) < 2:
        sys.exit(__doc__)
    folder = argv[1]
    pv = argv[argv.index("--paper-values") + 1] if "--paper-values" in argv else PAPER_VALUES
    by = judged(folder)
    renderer = next((r["renderer"] for rs in by.values() for r in rs), "")
    limit = raster_limit(renderer)
    print(f"# gibench on {os.path.basename(os.path.normpath(folder))}\n")
    print("Written by harness/reporting/gpu_summary.py from this folder's CSVs, gpu.txt, clocks.csv and "
          "gpu_samples.csv. A timing-only run (harness/device/time_all_papers.sh): the papers' "
          "parameters at the papers' image sizes (profile `gpu`), no references, no scores, no images; "
          "the paper profile's rows in results/ judge quality.\n")
    print("```\n" + "\n".join(machine(folder)) + "\n```\n")
    if limit:
        print(f"**Raster limit.** {limit}. The papers timed GeForce cards whose every SM rasterises: "
              "here a raster pass (vertex and fragment work) is slower against a compute pass than on "
              "their GPUs, and each pass below says which it is.\n")
    print("## Which rows count\n")
    print("\n".join(validity(by)) + "\n")
    print("## The GPU per matrix: clocks, power, temperature, throttle reasons (before / after)\n")
    print("\n".join(clocks(folder, by)) + "\n")
    print("## LRSM paper, Table 3: GPU time per stage, Sponza (sun), 1280x720\n")
    print("\n".join(table3(folder, read_csv(os.path.join(pv, "lrsm_table3.csv")))) + "\n")
    print("## LRSM paper, Table 2: frame time and memory, 1280x720\n")
    print("\n".join(table2(folder, read_csv(os.path.join(pv, "lrsm_table2.csv")))) + "\n")
    print("## LDM paper, Figs. 8-10: time at the paper's settings\n")
    print("\n".join(ldm(folder, pv)) + "\n")
    print("## Thesis, Tables 4.1-4.5: time per stage at the thesis' settings\n")
    print("\n".join(thesis(folder, pv)) + "\n")
    print("## Work per microsecond by pass kind (pipeline statistics of the first warm frame)\n")
    print("\n".join(work_rates(folder)) + "\n")
    ind = indirect(folder)
    if len(ind) > 2:
        print("## Indirect light across the papers (thesis_indirect), fastest first\n")
        print("\n".join(ind) + "\n")


if __name__ == "__main__":
    main(sys.argv)
