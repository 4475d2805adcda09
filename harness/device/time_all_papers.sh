#!/bin/bash
# The device run of all three papers: timing and memory only (no references, no scores, no images:
# quality comes from the paper profile's rows on llvmpipe), at the papers' settings and image sizes
# (profile gpu), warm-up until the time per frame settles, in the papers' order of priority, so
# that a run stopped by its budget has the papers' own tables first:
#   LRSM Tables 3 and 2; LDM Figs. 8-10; the thesis' Tables 4.1-4.5 and its gather costs; then the
#   rest (the LRSM quality rows, the dragon, LDM Fig. 11 and memory, the cross-paper indirect
#   matrix, shadow maps, the LRSM sweeps, the sequences).
#
#   bash harness/device/time_all_papers.sh [more gibench run options]
#
# On a lent machine, from a copy of the repository carrying .gl, .bundle and .scenes
# (harness/device/run_on_nvidia.sh says what each holds). GIB_DEVICE_BUDGET_S bounds the whole run
# (default 480 s); rows already in $GIB_DEVICE_TMP/results are skipped (a second call resumes), and
# GIB_DEVICE_RESULTS names a folder of finished CSVs to start from (the results of an earlier
# machine, carried there). GIB_DEVICE_FRAMES (default 5) timed frames a run: with 10, all 22
# matrices took 643 s on an H200; with 5, harness/device/estimate.py puts them at 423 s of the
# 480 s budget.
# harness/reporting/gpu_summary.py writes results/gpu/<gpu>/SUMMARY.md from what comes back.
set -u
here=$(cd "$(dirname "$0")" && pwd)
m=harness/matrices
order="lrsm_stages lrsm_memory ldm_fig8 ldm_fig9 ldm_fig10 thesis_t41_ring thesis_t42_occluded
       thesis_t43_bunnies thesis_t44_water thesis_t45_sponza thesis_t45_sponza_west thesis_gather_cost
       lrsm_quality lrsm_dragon ldm_fig11 ldm_memory thesis_indirect direct_shadows lrsm_sweeps
       temporal_lrsm_dragon temporal_ldm_cornell temporal_thesis_water"
files=()
for name in $order; do files+=("$m/$name.matrix"); done
tmp=${GIB_DEVICE_TMP:-/tmp}
if [ -n "${GIB_DEVICE_RESULTS:-}" ] && [ -d "$GIB_DEVICE_RESULTS" ]; then
    mkdir -p "$tmp/results"
    cp -n "$GIB_DEVICE_RESULTS"/*.csv "$tmp/results/" 2>/dev/null
fi
export GIB_DEVICE_PROFILE=${GIB_DEVICE_PROFILE:-gpu}
exec bash "$here/run_on_nvidia.sh" "${files[@]}" --timing-only --warmup auto \
    --frames "${GIB_DEVICE_FRAMES:-5}" --no-history "$@"
