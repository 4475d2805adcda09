#!/usr/bin/env python3
"""Shards and merge: tests/cluster/tiny.matrix run once unsharded, then in 3
shards through the repository's recipe (GNU parallel, or a Slurm job array on a one-node cluster
started here), merged, must give the unsharded table row for row: every column but the times
(gpu_ms_*, cpu_ms, the timestamp), compared exactly, because a shard renders the same images from
the same references on the same renderer (the reference is deterministic for a given request:
reference/). In `parallel` mode it also checks that `gibench merge` refuses what it must: a missing
or repeated shard, shards of different profiles, revisions or matrices, a missing or duplicated row,
an existing output.

Exit 77 (ctest SKIP_RETURN_CODE) only in `slurm` mode, when the daemons cannot start here; the
reason is printed."""
import argparse
import csv
import os
import shutil
import subprocess
import sys
import tempfile

TIME_COLUMNS = {"gpu_ms_median", "gpu_ms_min", "gpu_ms_max", "gpu_ms_iqr", "cpu_ms", "cpu_ms_iqr",
                "first_frame_ms", "first_frame_gpu_ms", "timestamp"}
PASS_TIME_COLUMNS = {"ms_median", "ms_min", "ms_max", "ms_iqr", "ms_first"}
SHARDS = 3
failures = []


def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what)
    if not cond:
        failures.append(what)


def run(cmd, env=None, expect=0):
    p = subprocess.run(cmd, env=env, capture_output=True, text=True)
    if expect is not None and p.returncode != expect:
        sys.stdout.write(p.stdout[-4000:])
        sys.stderr.write(p.stderr[-4000:])
        raise SystemExit(f"{' '.join(cmd)}: exit {p.returncode}, expected {expect}")
    return p


def read(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def compare(a_path, b_path, ignore, what):
    a, b = read(a_path), read(b_path)
    check(len(a) == len(b) and len(a) > 0, f"{what}: {len(b)} merged rows, {len(a)} unsharded")
    diffs = []
    for i, (x, y) in enumerate(zip(a, b)):
        if list(x) != list(y):
            diffs.append(f"row {i + 2}: different columns")
            continue
        for k in x:
            if k not in ignore and x[k] != y[k]:
                diffs.append(f"row {i + 2} {k}: unsharded {x[k]!r}, merged {y[k]!r}")
    for d in diffs[:10]:
        print("     " + d)
    check(not diffs, f"{what}: equal row for row but for the times ({len(diffs)} differences)")


def manifests(base):
    """Each shard's runs (index -> width*height, state) from its manifest, and the run count."""
    out = {}
    total = None
    for i in range(1, SHARDS + 1):
        runs = {}
        cur = None
        with open(os.path.join(base, f"shard-{i}", "tiny.shard")) as f:
            for line in f:
                t = line.rstrip("\n").split("\t")
                if t[0] == "runs":
                    total = int(t[1])
                elif t[0] == "run":
                    cur = int(t[1])
                    runs[cur] = (0, t[3])
                elif t[0] == "row":
                    k = t[1].split("|")  # profile|scene|camera|technique|component|params|w|h|time
                    runs[cur] = (int(k[6]) * int(k[7]), runs[cur][1])
        out[i] = runs
    return out, total


def check_split(base, rows):
    m, total_runs = manifests(base)
    every = sorted(j for runs in m.values() for j in runs)
    check(every == list(range(total_runs)), f"the {SHARDS} shards hold each of the {total_runs} runs once")
    skipped = sum(1 for runs in m.values() for _, st in runs.values() if st == "skipped")
    check(skipped == total_runs - rows, f"{skipped} runs skipped (bunny's data hidden), "
          f"{total_runs - rows} runs without rows unsharded")
    loads = [sum(p for p, _ in r.values()) for r in m.values()]
    # Longest-processing-time-first over (scene, size) groups: no shard is loaded beyond the fair
    # share plus the largest group (here 5 runs of 48x32 = 7680 pixels).
    fair = sum(loads) / SHARDS
    check(min(loads) > 0 and max(loads) <= fair + 5 * 48 * 32,
          f"balanced split: pixel loads {loads}, fair share {fair:.0f}")


def expect_refusal(gibench, dirs, out, words, what):
    p = run([gibench, "merge", *dirs, "--out", out], expect=None)
    msg = (p.stderr + p.stdout).strip().splitlines()
    ok = p.returncode != 0 and any(w in (p.stderr or "") for w in words) and \
        not os.path.exists(os.path.join(out, "tiny.csv"))
    check(ok, f"merge refuses {what}: exit {p.returncode}: {msg[-1] if msg else ''}")


def refusals(gibench, base, work):
    s = [os.path.join(base, f"shard-{i}") for i in range(1, SHARDS + 1)]
    out = os.path.join(work, "refused")

    def variant(name, src, edit_manifest=None, edit_csv=None, rename=None):
        d = os.path.join(work, name)
        shutil.rmtree(d, ignore_errors=True)
        shutil.copytree(src, d)
        if edit_manifest:
            p = os.path.join(d, "tiny.shard")
            with open(p) as f:
                text = f.read()
            with open(p, "w") as f:
                f.write(edit_manifest(text))
        if edit_csv:
            p = os.path.join(d, "tiny.csv")
            with open(p) as f:
                lines = f.readlines()
            with open(p, "w") as f:
                f.writelines(edit_csv(lines))
        if rename:
            for ext in (".shard", ".csv", "_passes.csv"):
                os.rename(os.path.join(d, "tiny" + ext), os.path.join(d, rename + ext))
            p = os.path.join(d, rename + ".shard")
            with open(p) as f:
                text = f.read()
            with open(p, "w") as f:
                f.write(text.replace("matrix\ttiny\n", f"matrix\t{rename}\n"))
        return d

    def set_line(key, value):
        return lambda t: "\n".join(f"{key}\t{value}" if l.startswith(key + "\t") else l
                                   for l in t.split("\n"))

    p = run([gibench, "merge", "--help"], expect=None)
    check(p.returncode == 0 and p.stdout.startswith("usage: gibench merge"), "merge --help")
    p = run([gibench, "merge", s[0]], expect=None)
    check(p.returncode == 2 and "--out DIR missing" in p.stderr, "merge without --out: exit 2")
    p = run([gibench, "run", "x.matrix", "--shard", "4/3"], expect=None)
    check(p.returncode == 2 and "--shard '4/3'" in p.stderr, "run --shard 4/3: exit 2 naming it")
    expect_refusal(gibench, s[:2], out, ["missing"], "a missing shard")
    expect_refusal(gibench, [s[0], s[0], s[1], s[2]], out, ["twice"], "a repeated shard")
    expect_refusal(gibench, [s[0], s[1], variant("v_profile", s[2], set_line("profile", "paper"))],
                   out, ["different profiles"], "shards of different profiles")
    expect_refusal(gibench, [s[0], s[1], variant("v_rev", s[2], set_line("revision", "0123456789ab"))],
                   out, ["different revisions"], "shards of different revisions")
    expect_refusal(gibench, [s[0], s[1], variant("v_fp", s[2], set_line("fingerprint", "0" * 16))],
                   out, ["different matrix expansions"], "shards of different matrix expansions")
    expect_refusal(gibench, [s[0], s[1], variant("v_matrix", s[2], rename="other")],
                   out, ["different matrices"], "shards of different matrices")
    expect_refusal(gibench, [s[0], s[1], variant("v_lost", s[2], edit_csv=lambda l: l[:-1])],
                   out, ["missing from"], "a missing row")
    expect_refusal(gibench, [s[0], s[1], variant("v_dup", s[2], edit_csv=lambda l: l + l[-1:])],
                   out, ["twice"], "a duplicated row")
    os.makedirs(out, exist_ok=True)
    shutil.copy(os.path.join(base, "merged", "tiny.csv"), os.path.join(out, "tiny.csv"))
    p = run([gibench, "merge", *s, "--out", out], expect=None)
    check(p.returncode != 0 and "exists" in p.stderr, "merge refuses to overwrite an existing table")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--gibench", required=True)
    ap.add_argument("--root", required=True, help="the repository (harness/cluster, tests/cluster)")
    ap.add_argument("--work", required=True)
    ap.add_argument("--mode", choices=["parallel", "slurm"], required=True)
    a = ap.parse_args()
    gibench = os.path.abspath(a.gibench)
    matrix = os.path.join(a.root, "tests", "cluster", "tiny.matrix")
    work = os.path.abspath(a.work)
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    # No shared scene data, here or not: tiny.matrix's `bunny` is skipped alike everywhere.
    no_scenes = os.path.join(work, "no-scenes")
    os.makedirs(no_scenes)
    os.environ["GIBENCH_SCENES"] = no_scenes
    env = dict(os.environ, GIBENCH=gibench)
    # Images in parallel mode (merge gathers them); the Slurm run checks the tables only.
    opts = [] if a.mode == "parallel" else ["--no-images"]

    # The daemons' folder holds munge's Unix socket, whose path must stay short (108 bytes).
    slurm_dir = tempfile.mkdtemp(prefix="gib-slurm-") if a.mode == "slurm" else None
    if a.mode == "slurm":
        p = run([os.path.join(a.root, "harness", "cluster", "slurm_local.sh"), "start", slurm_dir],
                expect=None)
        if p.returncode == 3:
            print("SKIP: " + p.stderr.strip())
            shutil.rmtree(slurm_dir, ignore_errors=True)
            return 77
        if p.returncode != 0:
            sys.stderr.write(p.stderr)
            return 1
        env["SLURM_CONF"] = os.path.join(slurm_dir, "slurm.conf")
        print("one-node Slurm cluster started: " + env["SLURM_CONF"])
    try:
        run([gibench, "run", matrix, "--out", os.path.join(work, "full"), "--cache",
             os.path.join(work, "cache-full"), *opts])
        base = os.path.join(work, "sharded")
        # The shards share one cache, as machines sharing a file system would: concurrent writers
        # of the same reference rename complete files into place (refcache.c).
        shard_opts = ["--cache", os.path.join(work, "cache-shards"), *opts]
        if a.mode == "parallel":
            cmd = [os.path.join(a.root, "harness", "cluster", "parallel_shards.sh"), matrix,
                   str(SHARDS), base, *shard_opts]
        else:
            env["WAIT"] = "1"
            cmd = [os.path.join(a.root, "harness", "cluster", "slurm_submit.sh"), matrix,
                   str(SHARDS), base, *shard_opts]
        p = run(cmd, env=env, expect=None)
        print(p.stdout.strip())
        check(p.returncode == 0, f"{os.path.basename(cmd[0])} exits 0 ({p.returncode}: {p.stderr.strip()[-300:]})")
        merged = os.path.join(base, "merged")
        if not os.path.exists(os.path.join(merged, "tiny.csv")):
            for f in sorted(os.listdir(base)):
                if f.endswith(".log"):
                    print(f"--- {f}\n" + open(os.path.join(base, f)).read()[-2000:])
            check(False, "the merged table exists")
            return 1
        full = os.path.join(work, "full")
        rows = sum(1 for _ in read(os.path.join(full, "tiny.csv")))  # 1 component per run here
        check_split(base, rows)
        compare(os.path.join(full, "tiny.csv"), os.path.join(merged, "tiny.csv"), TIME_COLUMNS,
                "tiny.csv")
        compare(os.path.join(full, "tiny_passes.csv"), os.path.join(merged, "tiny_passes.csv"),
                PASS_TIME_COLUMNS, "tiny_passes.csv")
        if a.mode == "parallel":
            want = sorted(os.listdir(os.path.join(full, "images", "tiny")))
            got = sorted(os.listdir(os.path.join(merged, "images", "tiny")))
            check(want == got and len(want) > 0,
                  f"merge gathers the shards' images: {len(got)} files, {len(want)} unsharded")
            # The same renderer on the same input writes the same bytes (EXR and PNG, no dates).
            differ = [f for f in want if f in got and
                      open(os.path.join(full, "images", "tiny", f), "rb").read() !=
                      open(os.path.join(merged, "images", "tiny", f), "rb").read()]
            check(not differ, f"the merged images are the unsharded run's, byte for byte ({differ[:3]})")
            refusals(gibench, base, work)
    finally:
        if a.mode == "slurm":
            run([os.path.join(a.root, "harness", "cluster", "slurm_local.sh"), "stop", slurm_dir],
                expect=None)
            shutil.rmtree(slurm_dir, ignore_errors=True)
    print(f"{len(failures)} failure(s)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
