"""The cone study in the report (results/cone_study.csv, written by `make cone-study`).

For each scene, technique and voxel_res: the six-cone gather's mean over the reference's and its
rel RMSE, set beside the ideal gather's (the path tracer's six cones, weighted: the best any
technique with this cone set can score) and the black image's rel RMSE, and each cone's mean over
its cap's light, so that a gather near the reference by errors that cancel shows as such.
"""
import csv
import glob
import html
import os

INTRO = ("Each cone of the voxel techniques against the path tracer's cone (gibench reference "
         "--cone i: rho_d times the mean radiance over cone i's cap). The ideal gather is the "
         "path tracer's six cones weighted as the techniques weight theirs: the least error any "
         "technique with this cone set can reach. Cones 1-5 are tilted 60 degrees from the normal; "
         "a cone's ratio far from 1 with a gather near 1 is an error that others cancel.")


def read(results):
    """The rows of results/cone_study.csv (make cone-study: the Cornell boxes) and of any
    cone_study_<scene>.csv beside it (a scene of the papers', run by hand: PERFORMANCE.md)."""
    rows = []
    for path in sorted(glob.glob(os.path.join(results, "cone_study*.csv"))):
        with open(path, newline="") as f:
            rows += list(csv.DictReader(f))
    return rows


def table(rows):
    """One entry per scene, technique and voxel_res, in the file's order."""
    ideal = {r["scene"]: r for r in rows if r["technique"] == "ideal"}
    entries, index = [], {}
    for r in rows:
        if r["technique"] == "ideal":
            continue
        key = (r["scene"], r["technique"], r["voxel_res"])
        if key not in index:
            index[key] = {"key": key, "gather": None, "cones": {}, "ideal": ideal.get(r["scene"])}
            entries.append(index[key])
        if r["cone"] == "gather":
            index[key]["gather"] = r
        else:
            index[key]["cones"][int(r["cone"])] = r
    return [e for e in entries if e["gather"]]


HEAD = ["scene", "technique", "voxel_res", "gather: mean / reference's", "rel RMSE (without noise)",
        "ideal gather: mean, rel RMSE", "black's rel RMSE", "each cone's mean / its cap's (0-5)"]


def cells(e):
    g, i = e["gather"], e["ideal"]
    worse = " (worse than black)" if g.get("worse_than_black") == "1" else ""
    cones = " ".join(e["cones"][c]["mean_ratio"] if c in e["cones"] else "-" for c in range(6))
    return list(e["key"]) + [
        g["mean_ratio"], f'{g["rel_rmse"]} ({g["rel_rmse_denoised"]}){worse}',
        f'{i["mean_ratio"]}, {i["rel_rmse"]}' if i else "-", g["black_rel"], cones]


def provenance(rows):
    found = sorted({(r.get("renderer", ""), r.get("cores", ""), r.get("git_revision", "")) for r in rows})
    return "; ".join(f"{r}, {c} cores, revision {v}" for r, c, v in found)


def section_md(results):
    rows = read(results)
    if not rows:
        return []
    lines = ["## Each cone against the path tracer's cone", "", INTRO, "",
             f"From cone_study.csv: {provenance(rows)}.", "",
             "| " + " | ".join(HEAD) + " |", "|" + "---|" * len(HEAD)]
    lines += ["| " + " | ".join(str(c).replace("|", "\\|") for c in cells(e)) + " |"
              for e in table(rows)]
    return lines + [""]


def section_html(results):
    rows = read(results)
    if not rows:
        return ""
    esc = html.escape
    body = "".join("<tr>" + "".join(f"<td>{esc(str(c))}</td>" for c in cells(e)) + "</tr>"
                   for e in table(rows))
    return (f'<h2 id="cones">Each cone against the path tracer\'s cone</h2><p>{esc(INTRO)}</p>'
            f'<p class="source">From <code>cone_study.csv</code>: {esc(provenance(rows))}.</p>'
            '<table class="cones"><tr>' + "".join(f"<th>{esc(h)}</th>" for h in HEAD) + "</tr>"
            + body + "</table>")
