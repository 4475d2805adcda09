#!/usr/bin/env python3
"""The voxel techniques' diffuse gather split into its six cones (make cone-study).

A cone technique's indirect error has two parts: each cone's own error (what it gathers against
the exact mean radiance over its cap) and the error of gathering the hemisphere from six caps at
all (the cone set's, which no cone can remove). `gibench reference --cone i` renders the first's
truth, and the weighted sum of the six is the best any technique with this cone set can score:
the "ideal" rows. Writes results/cone_study.csv:

  scene, technique, voxel_res, cone (0-5, or "gather"), weight, mean_ratio, rel_rmse,
  rel_rmse_denoised, ref_noise_rel, black_rel, worse_than_black, renderer, cores, git_revision,
  technique_hash, params

where a cone row compares the technique's cone i alone (--param cone=i) with the reference's cone
i, a "gather" row the whole indirect image with the whole reference, and the technique "ideal"
row the reference's six cones, weighted, against the whole reference. rel_rmse_denoised is the
RMSE with the reference's own noise taken out, ref_noise_rel that noise, black_rel what a black
image scores (gibench compare), each over the reference's mean; worse_than_black is 1 where the
row's RMSE exceeds that; params the --param settings of the technique's renders ("" for its
defaults). --append adds the rows to --out's (a control: the same study with another parameter).

Usage: python3 -m reporting.cone_study [--gibench build/gibench] [--out results/cone_study.csv]
       [--cache results/cache] [--size 128x128] [--spp 256] [--full-spp 1024]
       [--scenes cornell,cornell_spot45] [--voxel-res 64,128,256] [--techniques lrsm,vct]
       [--param K=V]... [--append]
"""
import argparse
import csv
import json
import os
import shutil
import subprocess
import sys
import tempfile

from reporting import schema  # noqa: E402
from reporting import source_hash  # noqa: E402

WEIGHTS = schema.cone_weights()  # harness/base/cone_set.h, as gibench exports it
TECHNIQUES = ["lrsm", "vct"]


def run(cmd):
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if r.returncode != 0:
        sys.exit("cone_study: %s failed (%d):\n%s" % (" ".join(cmd), r.returncode, r.stdout))
    return r.stdout


def reference(a, scene, spp, cone=None):
    """The cached reference's EXR path (rendered when missing)."""
    cmd = [a.gibench, "reference", "--scene", scene, "--component", "indirect", "--spp", str(spp),
           "--size", a.size, "--cache", a.cache, "--quiet"]
    if cone is not None:
        cmd += ["--cone", str(cone)]
    out = run(cmd)
    for word in out.split():
        if word.endswith(".exr"):
            return word
    sys.exit("cone_study: no EXR named in: " + out)


def compare(a, ref, test):
    return json.loads(run([a.gibench, "compare", ref, test, "--json"]))


PROVENANCE = {"renderer": "", "cores": str(os.cpu_count()),
              "git_revision": source_hash.git_revision()}
SOURCES = source_hash.Tree()  # the sources the gibench that renders was built from (a clean tree)
PARAMS = []  # --param, recorded in each row


def row(scene, technique, res, cone, weight, m):
    black = m["black_rmse"]
    return {"scene": scene, "technique": technique, "voxel_res": res, "cone": cone,
            "weight": "%.6f" % weight if weight is not None else "",
            "mean_ratio": "%.4f" % m["mean_ratio"], "rel_rmse": "%.4f" % m["rel_rmse"],
            "rel_rmse_denoised": "%.4f" % (m["rmse_denoised"] / m["rmse"] * m["rel_rmse"]
                                           if m["rmse"] > 0 else 0.0),
            "ref_noise_rel": "%.4f" % (m["ref_noise_rmse"] / m["rmse"] * m["rel_rmse"]
                                       if m["rmse"] > 0 else 0.0),
            "black_rel": "%.4f" % (black / m["rmse"] * m["rel_rmse"] if m["rmse"] > 0 else 0.0),
            "worse_than_black": int(m["rmse"] > black), **PROVENANCE,
            "technique_hash": source_hash.technique_hash(SOURCES, technique) if technique != "ideal" else "",
            "params": ";".join(PARAMS)}


def weighted_sum(paths, out):
    cmd = ["oiiotool"]
    for i, p in enumerate(paths):
        cmd += [p, "--ch", "R,G,B", "--mulc", "%.9g" % WEIGHTS[i]]
        if i:
            cmd += ["--add"]
    run(cmd + ["-d", "float", "-o", out])


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--gibench", default="build/gibench")
    ap.add_argument("--out", default="results/cone_study.csv")
    ap.add_argument("--cache", default="results/cache")
    ap.add_argument("--size", default="128x128")
    ap.add_argument("--spp", type=int, default=256, help="samples of each cone's reference")
    ap.add_argument("--full-spp", type=int, default=1024, help="samples of the whole reference")
    ap.add_argument("--scenes", default="cornell,cornell_spot45")
    ap.add_argument("--voxel-res", default="64,128,256")
    ap.add_argument("--param", action="append", default=[], metavar="K=V",
                    help="a technique parameter for every render (repeatable)")
    ap.add_argument("--techniques", default=",".join(TECHNIQUES))
    ap.add_argument("--append", action="store_true", help="add the rows to --out's")
    a = ap.parse_args()
    PARAMS.extend(a.param)
    rows = []
    work = tempfile.mkdtemp(prefix="gib_cone_study_")
    for scene in a.scenes.split(","):
        full = reference(a, scene, a.full_spp)
        cones = [reference(a, scene, a.spp, i) for i in range(6)]
        ideal = os.path.join(work, scene + "_ideal.exr")
        weighted_sum(cones, ideal)
        rows.append(row(scene, "ideal", "", "gather", None, compare(a, full, ideal)))
        for tech in a.techniques.split(","):
            for res in a.voxel_res.split(","):
                for cone in list(range(6)) + [-1]:
                    d = os.path.join(work, "%s_%s_%s_%d" % (scene, tech, res, cone))
                    out = run([a.gibench, "render", "--scene", scene, "--technique", tech,
                               "--size", a.size, "--out", d, "--param", "voxel_res=" + res,
                               "--param", "cone=%d" % cone, "--warmup", "0", "--frames", "1"]
                              + [x for kv in a.param for x in ("--param", kv)])
                    if out.startswith("renderer: "):  # backend | GL_RENDERER | GL_VERSION
                        PROVENANCE["renderer"] = out.splitlines()[0].split(" | ")[1]
                    img = os.path.join(d, tech + "_indirect.exr")
                    ref = cones[cone] if cone >= 0 else full
                    m = compare(a, ref, img)
                    rows.append(row(scene, tech, res, cone if cone >= 0 else "gather",
                                    WEIGHTS[cone] if cone >= 0 else None, m))
                    print("%-15s %-5s %3s %-6s mean %s rel %s" % (
                        scene, tech, res, rows[-1]["cone"], rows[-1]["mean_ratio"],
                        rows[-1]["rel_rmse"]), flush=True)
    for r in rows:  # the ideal rows come before the first render names the renderer
        r["renderer"] = PROVENANCE["renderer"]
    if a.append and os.path.exists(a.out):
        with open(a.out, newline="") as f:
            rows = list(csv.DictReader(f)) + rows
    with open(a.out, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[-1].keys()), restval="",
                           lineterminator="\n")
        w.writeheader()
        w.writerows(rows)
    shutil.rmtree(work)
    print("cone_study: %d rows -> %s" % (len(rows), a.out))


if __name__ == "__main__":
    main()
