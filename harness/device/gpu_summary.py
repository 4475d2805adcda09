#!/usr/bin/env python3
"""Summarises a GPU run of harness/device/run_on_nvidia.sh beside the papers' own numbers.

    python3 harness/device/gpu_summary.py results/gpu/NAME [--paper-values DIR] > results/gpu/NAME/SUMMARY.md

Reads the folder's gpu.txt (the machine, as the script recorded it) and its CSVs (lrsm_stages,
lrsm_memory, thesis_indirect, where present) and writes Markdown: the LRSM paper's Table 3 (GPU
time per stage) and Table 2 (frame time and memory) with this GPU's medians beside the paper's
GTX 770 and Iris Pro, and the cross-paper indirect comparison's times. Every time is the median of
the warm frames with its interquartile range; the cold first frame stands apart."""
import csv
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
PAPER_VALUES = os.path.join(HERE, "..", "..", "..", "shared", "paper-values")
STAGES = ("voxelization", "lrsm_construction", "shadow_cone", "diffuse_cones", "specular_cone")


def read_csv(path):
    if not os.path.exists(path):
        return []
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def param(row, key):
    for kv in row["params"].split(";"):
        k, _, v = kv.partition("=")
        if k == key:
            return v
    return ""


def machine(folder):
    """The lines of gpu.txt that name the machine: GPU, driver, clocks, CPUs, GL renderer."""
    keep = []
    lines = open(os.path.join(folder, "gpu.txt")).read().splitlines()
    for i, line in enumerate(lines):
        if line.startswith("== nvidia-smi --query-gpu") and i + 2 < len(lines):
            keep += [lines[i + 1], lines[i + 2]]
        elif line.startswith(("== nproc", "model name", "renderer:", "EGL device")):
            keep.append(line.lstrip("= "))
    return keep


def table3(folder, paper):
    passes = read_csv(os.path.join(folder, "lrsm_stages_passes.csv"))
    want = {("lrsm", "512"): "LRSM", ("vct", "256"): "VCT"}
    ours = {}
    for r in passes:
        method = want.get((r["technique"], param(r, "voxel_res")))
        stage = "diffuse_cones_6" if r["pass"] == "diffuse_cones" else \
            "specular_cone_1" if r["pass"] == "specular_cone" else r["pass"]
        if method:
            ours[(method, stage)] = (float(r["ms_median"]), float(r["ms_iqr"]), float(r["ms_first"]))
    paper_ms = {(p["method"], p["gpu"], p["stage"]): p["ms"] for p in paper}
    out = ["| method | stage | this GPU, ms (IQR; cold first) | GTX 770 (paper) | Iris Pro (paper) |",
           "|---|---|---|---|---|"]
    for method in ("LRSM", "VCT"):
        for stage in ("voxelization", "lrsm_construction", "shadow_cone", "diffuse_cones_6",
                      "specular_cone_1"):
            o = ours.get((method, stage))
            g = paper_ms.get((method, "GTX770", stage), "")
            i = paper_ms.get((method, "Iris Pro", stage), "")
            if o or g:
                cell = f"{o[0]:.2f} ({o[1]:.3f}; {o[2]:.1f})" if o else "-"
                out.append(f"| {method} | {stage} | {cell} | {g} | {i} |")
    return out


def table2(folder, paper):
    rows = [r for r in read_csv(os.path.join(folder, "lrsm_memory.csv")) if r["component"] == "indirect"]
    names = {"sibenik": "SIBENIK", "sponza_glossy": "SPONZA", "sponza_dragon": "SPONZA DRAGON"}
    out = ["| scene | technique | voxel_res | D | this GPU frame, ms (IQR) | planned MB | driver MB | "
           "paper total MB | paper GTX 770 ms |", "|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        res, depth = param(r, "voxel_res"), param(r, "layers_depth")
        p = next((p for p in paper if p["scene"] == names.get(r["scene"]) and
                  p["occlusion_voxel_res"] == res and (not depth or p["layers_depth"] == depth)), None)
        if r["status"] != "ok":
            out.append(f"| {r['scene']} | {r['technique']} | {res} | {depth} | {r['status']} | | | | |")
            continue
        drv = f"{float(r['driver_mem_bytes']) / 1e6:.1f}" if r["driver_mem_bytes"] else ""
        out.append(f"| {r['scene']} | {r['technique']} | {res} | {depth} | "
                   f"{float(r['gpu_ms_median']):.2f} ({float(r['gpu_ms_iqr']):.2f}) | "
                   f"{float(r['mem_bytes']) / 1e6:.1f} | {drv} | "
                   f"{p['total_mb'] if p and r['technique'] == 'lrsm' else ''} | "
                   f"{p['gtx770_ms'] if p and r['technique'] == 'lrsm' else ''} |")
    return out


def indirect(folder):
    rows = [r for r in read_csv(os.path.join(folder, "thesis_indirect.csv"))
            if r["component"] == "indirect" and r["status"] == "ok"]
    out = ["| scene | size | technique | parameters | ms (IQR) | rel RMSE | reference noisy |",
           "|---|---|---|---|---|---|---|"]
    for r in sorted(rows, key=lambda r: (r["scene"], int(r["width"]), float(r["gpu_ms_median"]))):
        short = ";".join(kv for kv in r["params"].split(";") if kv.split("=")[0] in
                         ("vpl_count", "directions", "voxel_res"))
        out.append(f"| {r['scene']} | {r['width']}x{r['height']} | {r['technique']} | {short} | "
                   f"{float(r['gpu_ms_median']):.2f} ({float(r['gpu_ms_iqr']):.2f}) | "
                   f"{float(r['rel_rmse']):.3f} | {'yes' if r['ref_noisy'] == '1' else 'no'} |")
    return out


def main(argv):
    if len(argv) < 2:
        sys.exit(__doc__)
    folder = argv[1]
    pv = argv[argv.index("--paper-values") + 1] if "--paper-values" in argv else PAPER_VALUES
    revisions = {r["git_revision"] for f in os.listdir(folder) if f.endswith(".csv")
                 for r in read_csv(os.path.join(folder, f))}
    print(f"# gibench on {os.path.basename(os.path.normpath(folder))}\n")
    print("Written by harness/device/gpu_summary.py from this folder's CSVs and gpu.txt; the rows "
          f"are from gibench {', '.join(sorted(revisions))} (the bundle, `make bundle`), profile "
          "`gpu` (the paper's sizes and parameters, 16-spp references: the errors are for "
          "context, the llvmpipe rows in results/ judge quality).\n")
    print("```\n" + "\n".join(machine(folder)) + "\n```\n")
    print("## LRSM paper, Table 3: GPU time per stage, Sponza (sun), 1280x720\n")
    print("\n".join(table3(folder, read_csv(os.path.join(pv, "lrsm_table3.csv")))) + "\n")
    print("## LRSM paper, Table 2: frame time and memory, 1280x720\n")
    print("\n".join(table2(folder, read_csv(os.path.join(pv, "lrsm_table2.csv")))) + "\n")
    ind = indirect(folder)
    if len(ind) > 2:
        print("## Indirect light across the papers (thesis_indirect), fastest first\n")
        print("\n".join(ind) + "\n")


if __name__ == "__main__":
    main(sys.argv)
