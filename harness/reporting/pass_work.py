"""The papers' timed stages with the work they did: per pass, on each machine that ran the papers'
settings (the paper profile on llvmpipe, a device run on a GPU), its kind (raster, compute, both),
the invocations the pipeline statistics counted in the first warm frame and the median time. The
counts follow the work asked for (image size, settings), not the machine's speed, so a llvmpipe time
reads as a CPU rasterizer's beside the work that took it, and a GPU's raster passes beside its raster
limit; drivers differ in what they count (llvmpipe shades fragments a GPU's early depth test
rejects) and budget-sized batches in how many dispatches a pass makes.

One table per paper's timed figure: LRSM Table 3 (lrsm_stages), LDM Fig. 10 (ldm_fig10), the
thesis' gather costs (thesis_gather_cost), each at the paper's reading (preset paper) where a
technique has one. Rows come from the newest valid device run (gpu_rows.py) and from the results'
own passes tables."""
import html
import os

from reporting import gpu_rows
from reporting.schema import fnum, param, preset, read_csv

# (title, matrix, {technique: the parameters of the paper's row}); lrsm and vct at their paper
# reading (preset paper) and Table 3's voxel grids.
FIGURES = (("LRSM Table 3: stages on Sponza (sun)", "lrsm_stages",
            {"lrsm": {"voxel_res": 512.0}, "vct": {"voxel_res": 256.0}}),
           ("LDM Fig. 10: indirect light on Sponza and the Cornell box", "ldm_fig10", {"ldm_indirect": {}}),
           ("Thesis: multi-resolution gathering against the full gather", "thesis_gather_cost",
            {"multires_ir": {}, "rsm_gather": {}}))
WITH_PRESETS = ("lrsm", "vct")
HEAD = ["technique", "scene", "pass", "kind", "machine", "size", "invocations", "ms"]
INTRO = ("Each paper's timed stages with the work they did: the pass's kind and the fragment and "
         "compute invocations the GL pipeline statistics counted in its first warm frame, beside its "
         "median time on each machine that ran the papers' settings. The counts follow the work asked "
         "for, not the machine's speed: llvmpipe's times are a CPU rasterizer's for that work, and a "
         "GPU's raster passes run on its raster units alone (the H100/H200: 2 TPCs). Drivers differ in "
         "what they count: llvmpipe shades fragments a GPU's early depth test rejects (ldm_build), and "
         "a pass batched by a memory budget (photon_trace) dispatches once per batch.")


def keep(p, techniques):
    """A pass of the paper's row: its technique, the figure's parameters, the paper's reading."""
    want = techniques.get(p["technique"])
    if want is None or (p["technique"] in WITH_PRESETS and preset(p) != "paper"):
        return False
    return all(param(p, k) == v for k, v in want.items())


def largest(passes):
    """The passes of each technique's largest image and first parameter setting met."""
    best = {}
    for p in passes:
        k = (p["technique"], p["scene"])
        size = int(p["width"]) * int(p["height"])
        if k not in best or size > best[k][0]:
            best[k] = (size, p["params"])
    return [p for p in passes if best[(p["technique"], p["scene"])] == (int(p["width"]) * int(p["height"]),
                                                                          p["params"])]


def machine_rows(passes, machine):
    out = []
    for p in largest(passes):
        inv = (fnum(p.get("fragment_invocations")) or 0) + (fnum(p.get("compute_invocations")) or 0)
        counted = p.get("kind", "") != ""
        out.append([p["technique"], p["scene"], p["pass"], p.get("kind") or "not counted", machine,
                    f"{p['width']}x{p['height']}", f"{inv:,.0f}" if counted else "",
                    f"{fnum(p['ms_median']):.3g}" if fnum(p.get("ms_median")) is not None else ""])
    return out


def tables(results):
    """[(title, rows)] of every figure with rows on some machine."""
    run = gpu_rows.newest_run(results)
    if run:
        gpu, folder, mine = run
        run = (gpu, folder, {(r["scene"], r["technique"], r["params"], r["width"]) for r in mine
                             if r["_valid"]})
    out = []
    for title, matrix, techniques in FIGURES:
        local = [p for p in read_csv(os.path.join(results, f"{matrix}_passes.csv"))
                 if p.get("profile") == "paper" and keep(p, techniques)]
        rows = machine_rows(local, local[0]["renderer"].split(" (")[0]) if local else []
        if run:
            gpu, folder, valid = run
            device = [p for p in read_csv(os.path.join(folder, f"{matrix}_passes.csv"))
                      if keep(p, techniques) and (p["scene"], p["technique"], p["params"], p["width"]) in valid]
            rows += machine_rows(device, gpu)
        if rows:
            out.append((title, sorted(rows, key=lambda r: (r[0], r[1], r[4] != "llvmpipe", r[2]))))
    return out


def section_md(results):
    ts = tables(results)
    if not ts:
        return []
    lines = ["## Work and time per pass", "", INTRO, ""]
    for title, rows in ts:
        lines += [f"**{title}**", "", "| " + " | ".join(HEAD) + " |", "|" + "---|" * len(HEAD)]
        lines += ["| " + " | ".join(r) + " |" for r in rows] + [""]
    return lines


def section_html(results):
    ts = tables(results)
    if not ts:
        return ""
    head = "".join(f"<th>{html.escape(h)}</th>" for h in HEAD)
    parts = [f'<h2 id="passes">Work and time per pass</h2><p>{html.escape(INTRO)}</p>']
    for title, rows in ts:
        body = "".join("<tr>" + "".join(f"<td>{html.escape(x)}</td>" for x in r) + "</tr>" for r in rows)
        parts.append(f'<details class="passes"><summary>{html.escape(title)}</summary>'
                     f'<table class="passes"><tr>{head}</tr>{body}</table></details>')
    return "".join(parts)
