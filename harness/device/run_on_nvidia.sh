#!/bin/bash
# Runs matrices (the paper profile unless told) on a bare machine with an NVIDIA driver and none of our Debian
# libraries, from a copy of this repository that carries, git-ignored, beside the tracked files:
#   .gl/*.deb                    glvnd's vendor-neutral libraries (libegl1 libglvnd0 libopengl0
#                                libgl1 libglx0 libgles2), unpacked into / (the machine's own recipe)
#   .bundle/gibench-bundle.tar.xz   `make bundle` (harness/device/make_bundle.sh)
#   .scenes/scenes.tar.xz        harness/device/make_scenes.sh
#   .refcache/ (optional)        references to start the cache with (results/cache of a checkout)
#
#   bash harness/device/run_on_nvidia.sh MATRIX... [more gibench run options]
#
# The device run of all three papers is `harness/device/time_all_papers.sh`: this script with the
# matrices in the papers' order and --timing-only --warmup auto.
#
# from the repository's root (a copy of this script elsewhere, e.g. .bundle/run_on_nvidia.sh in a
# checkout that does not have it yet, works the same: the root is the current folder when it holds
# scenes/ and .bundle/, else the folder two above this script).
#
# Writes into $OUT (default /tmp/gib-device-out): gpu.txt (GPU, driver, clocks, CPUs, kernel, the GL
# context gibench gets), gibench.log (the runs' stdout and stderr), results.tar.xz (the results
# folder without its images: the CSVs, manifests and history), clocks.csv (the GPU's clocks, power,
# temperature and throttle reasons before and after each matrix), gpu_samples.csv (the same every
# 200 ms) and device.log (this script's own steps). Those files are written whatever happens to the run: gibench stops at a time budget
# (GIB_DEVICE_BUDGET_S seconds from this script's start, default 480: under a 600 s command
# limit), and the rows it wrote by then stay valid (each row is appended and flushed as its run
# finishes; an unfinished last line is cut off here, as `gibench run` does when it resumes).
# /tmp/results and /tmp/cache are kept: a second call on the same machine resumes the run
# (GIB_DEVICE_FRESH=1 starts afresh).
#
# Environment: GIB_DEVICE_BACKEND (--backend, default egl-device: the device platform, how an NVIDIA
# GPU is reached without a display; egl tries the surfaceless platform first), GIB_DEVICE_PROFILE
# (default paper; gpu: the papers' settings at the papers' image sizes), GIB_DEVICE_FORCE=1
# unpacks .gl into / even without /usr/local/nvidia (never on a machine of ours: it overwrites the
# system's GL libraries), GIB_DEVICE_TMP (default /tmp) where bundle, scenes, results and cache go.
set -u
start=$(date +%s)
root=$PWD
[ -d "$root/scenes" ] && [ -d "$root/.bundle" ] || root=$(cd "$(dirname "$0")/../.." && pwd)
out=${OUT:-/tmp/gib-device-out}
budget=${GIB_DEVICE_BUDGET_S:-480}
backend=${GIB_DEVICE_BACKEND:-egl-device}
profile=${GIB_DEVICE_PROFILE:-paper}
tmp=${GIB_DEVICE_TMP:-/tmp}
mkdir -p "$out"
log=$out/device.log
say() { echo "run_on_nvidia: $*" | tee -a "$log"; }
: >"$log"
if [ $# -eq 0 ]; then
    say "usage: bash harness/device/run_on_nvidia.sh MATRIX... [gibench run options]"
    exit 2
fi
cd "$root" || exit 2

# glvnd's libraries, as the machine's documentation prescribes; skipped on a machine without the
# NVIDIA driver's folder (a dry run here must not replace the system's GL libraries).
if [ -e /usr/local/nvidia ] || [ -n "${GIB_DEVICE_FORCE:-}" ]; then
    for f in .gl/*.deb; do dpkg -x "$f" / 2>>"$log" || say "dpkg -x $f failed"; done
    ldconfig 2>>"$log"
    say "unpacked $(ls .gl/*.deb 2>/dev/null | wc -l) packages of .gl into /"
else
    say "no /usr/local/nvidia: .gl not unpacked (dry run; GIB_DEVICE_FORCE=1 forces it)"
fi

bundle=$tmp/gibench-bundle
rm -rf "$bundle"
tar -C "$tmp" -xJf .bundle/gibench-bundle.tar.xz 2>>"$log" || say "cannot unpack .bundle/gibench-bundle.tar.xz"
mkdir -p "$tmp/scenes"
if [ -f .scenes/scenes.tar.xz ]; then
    tar -C "$tmp/scenes" -xJf .scenes/scenes.tar.xz 2>>"$log" || say "cannot unpack .scenes/scenes.tar.xz"
fi
results=$tmp/results
cache=$tmp/cache
[ -n "${GIB_DEVICE_FRESH:-}" ] && rm -rf "$results" "$cache"
mkdir -p "$results" "$cache"
[ -d .refcache ] && cp -rn .refcache/. "$cache/" 2>>"$log"

export LD_LIBRARY_PATH=$bundle/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
export GIBENCH_SCENES=$tmp/scenes GIBENCH_SCHEMA=$bundle/schema.json GIBENCH_ROOT=$root
vendor=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
[ -e "$vendor" ] && export __EGL_VENDOR_LIBRARY_FILENAMES=$vendor
gibench=$bundle/bin/gibench

{
    echo "== date: $(date -u +%Y-%m-%dT%H:%M:%SZ)"
    echo "== kernel: $(uname -srvmo)"
    echo "== nproc: $(nproc)"
    echo "== $(ldd --version 2>&1 | head -n 1) (the bundle needs glibc 2.34 or newer)"
    grep -m1 "model name" /proc/cpuinfo
    grep -m1 MemTotal /proc/meminfo
    echo "== bundle revision: $(cat "$bundle/REVISION" 2>/dev/null)"
    echo "== __EGL_VENDOR_LIBRARY_FILENAMES=${__EGL_VENDOR_LIBRARY_FILENAMES:-(default)}"
    ls /usr/share/glvnd/egl_vendor.d /usr/local/nvidia/share/glvnd/egl_vendor.d 2>&1
    if command -v nvidia-smi >/dev/null 2>&1; then
        echo "== nvidia-smi --query-gpu"
        nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.mem,clocks.max.sm --format=csv 2>&1
        echo "== nvidia-smi -q"
        nvidia-smi -q 2>&1
    else
        echo "== no nvidia-smi"
    fi
    echo "== ldd gibench"
    ldd "$gibench" 2>&1
} >"$out/gpu.txt" 2>&1

# A one-frame render first: the context gibench gets (renderer, EGL device and its extensions) goes
# into gpu.txt even when the run fails, and a backend that gives no context falls back to egl.
probe() {
    timeout 60 "$gibench" render --scene cornell --technique direct --size 64x64 --frames 1 \
        --warmup 0 --backend "$1" --cache "$cache" --out "$tmp/probe" >>"$out/gpu.txt" 2>&1
}
echo "== gibench render --backend $backend" >>"$out/gpu.txt"
if ! probe "$backend" && [ "$backend" != egl ]; then
    say "no context with --backend $backend (gpu.txt); trying egl"
    backend=egl
    echo "== gibench render --backend $backend" >>"$out/gpu.txt"
    probe "$backend" || say "no context with --backend egl either (gpu.txt)"
fi

# The GPU's state: SM and memory clocks, power, temperature, performance state and the reasons the
# clocks are held down (nvidia-smi's clocks_event_reasons, named clocks_throttle_reasons by older
# drivers), as one CSV line; a sampler writes it every 200 ms for the whole run (gpu_samples.csv)
# and each matrix gets a line before and after (clocks.csv), so that rows timed while the clock
# moved or the GPU was held down can be marked (harness/reporting/gpu_summary.py).
fields=timestamp,clocks.sm,clocks.mem,clocks.max.sm,power.draw,temperature.gpu,pstate,utilization.gpu
if command -v nvidia-smi >/dev/null 2>&1; then
    if nvidia-smi --query-gpu=clocks_event_reasons.active --format=csv,noheader >/dev/null 2>&1; then
        fields=$fields,clocks_event_reasons.active
    else
        fields=$fields,clocks_throttle_reasons.active
    fi
    echo "$fields" >"$out/gpu_samples.csv"
    nvidia-smi --query-gpu="$fields" --format=csv,noheader,nounits -lms 200 >>"$out/gpu_samples.csv" 2>&1 &
    sampler=$!
    echo "matrix,when,$fields" >"$out/clocks.csv"
fi
snapshot() {
    command -v nvidia-smi >/dev/null 2>&1 || return 0
    echo "$1,$2,$(nvidia-smi --query-gpu="$fields" --format=csv,noheader,nounits 2>&1 | head -n 1)" >>"$out/clocks.csv"
}

# One gibench run per matrix, in the order given (the papers' tables first), each stopped at what
# is left of the budget. Line-buffered (stdbuf), so that what gibench printed before the budget
# stopped it is in the log.
line=
command -v stdbuf >/dev/null 2>&1 && line="stdbuf -oL -eL"
matrices=() opts=()
for a in "$@"; do
    case $a in *.matrix) matrices+=("$a") ;; *) opts+=("$a") ;; esac
done
rc=0
: >"$out/gibench.log"
for m in "${matrices[@]}"; do
    name=$(basename "$m" .matrix)
    left=$((budget - ($(date +%s) - start)))
    if [ "$left" -le 20 ]; then
        say "$name: not run, the budget is spent"
        continue
    fi
    snapshot "$name" before
    t0=$(date +%s)
    timeout -k 15 "$left" $line "$gibench" run "$m" "${opts[@]}" --profile "$profile" \
        --backend "$backend" --out "$results" --cache "$cache" >>"$out/gibench.log" 2>&1
    mrc=$?
    snapshot "$name" after
    [ $mrc -eq 124 ] && say "$name: stopped at the time budget: the rows written so far are kept"
    say "$name: gibench exited with $mrc after $(($(date +%s) - t0)) s"
    [ $mrc -ne 0 ] && rc=$mrc
done
[ -n "${sampler:-}" ] && kill "$sampler" 2>/dev/null
say "all matrices: $(($(date +%s) - start)) s"

# A row cut in the middle by the time budget is dropped: head keeps the newline-terminated lines.
for f in "$results"/*.csv; do
    [ -f "$f" ] || continue
    n=$(wc -l <"$f")
    if [ "$(head -n "$n" "$f" | wc -c)" -ne "$(wc -c <"$f")" ]; then
        head -n "$n" "$f" >"$f.tmp" && mv "$f.tmp" "$f"
        say "$(basename "$f"): cut off an unfinished last line"
    fi
done
(cd "$results" && find . -path ./images -prune -o -type f ! -name '*.lock' -print | sort) >"$tmp/results.list"
tar -C "$results" -cJf "$out/results.tar.xz" -T "$tmp/results.list" 2>>"$log"
say "results.tar.xz: $(wc -l <"$tmp/results.list") files, $(du -k "$out/results.tar.xz" | cut -f1) KiB"
grep -E "^gibench run:" "$out/gibench.log" | tail -3 | tee -a "$log"
exit $rc
