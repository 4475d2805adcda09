#!/bin/sh
# Runs every libFuzzer target of BUILD (configured with GIB_FUZZ=ON: `make fuzz` does it) for at
# most SECONDS each and RUNS executions each (-1: no count limit), from the seed corpora plus a
# writable corpus per target in BUILD/fuzz-corpus/, with the INI dictionary for the INI formats.
# Writes OUT (CSV: target, executions, coverage edges, features, corpus size, seconds, result) and
# exits 1 when a target crashed, leaked, hung or tripped a sanitizer; its input is in
# BUILD/fuzz-artifacts/<target>/ and belongs in tests/fuzz/regressions/<target>/ once fixed.
# usage: run_fuzz.sh BUILD SECONDS RUNS OUT [TARGET...]   (default: every target)
set -u
build=$1; seconds=$2; runs=$3; out=$4
shift 4
targets=${*:-fuzz_scene fuzz_matrix fuzz_values fuzz_exr fuzz_mesh fuzz_merge fuzz_history fuzz_resume}
src=$(cd "$(dirname "$0")/../.." && pwd)
fz="$src/tests/fuzz"
# The targets' temporary files (the input as a file, merge's shard folders, a history) go to RAM
# where there is a tmpfs: SQLite's syncs on a disk would halve fuzz_history's rate.
[ -z "${TMPDIR:-}" ] && [ -d /dev/shm ] && [ -w /dev/shm ] && export TMPDIR=/dev/shm
export LSAN_OPTIONS="suppressions=$fz/lsan.supp${LSAN_OPTIONS:+:$LSAN_OPTIONS}"
echo "target,executions,cov_edges,features,corpus_inputs,seconds,result" > "$out"
status=0
for t in $targets; do
  exe="$build/tests/fuzz/$t"
  case $t in
    fuzz_scene)  seeds="$src/scenes"; dict="-dict=$fz/ini.dict" ;;
    fuzz_matrix) seeds="$src/harness/matrices $src/tests/quality"; dict="-dict=$fz/ini.dict" ;;
    *)           seeds="$fz/corpus/$t"; dict="" ;;
  esac
  [ -d "$fz/regressions/$t" ] && seeds="$seeds $fz/regressions/$t"
  mkdir -p "$build/fuzz-corpus/$t" "$build/fuzz-artifacts/$t"
  log="$build/fuzz-artifacts/$t.log"
  start=$(date +%s)
  # -timeout: an input taking over 10 s is a hang; -rss_limit_mb: over 2 GiB is a bug too.
  # -close_fd_mask=3: the targets' own messages (merge's and history's refusals) are not logged;
  # libFuzzer's and the sanitizers' reports still are.
  "$exe" $dict -close_fd_mask=3 -max_total_time="$seconds" -runs="$runs" -timeout=10 -rss_limit_mb=2048 \
    -max_len=16384 -print_final_stats=1 -artifact_prefix="$build/fuzz-artifacts/$t/" \
    "$build/fuzz-corpus/$t" $seeds > "$log" 2>&1
  rc=$?
  secs=$(( $(date +%s) - start ))
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  last=$(grep -E '^#[0-9]+' "$log" | tail -1)
  cov=$(echo "$last" | sed -n 's/.*cov: \([0-9]*\).*/\1/p')
  ft=$(echo "$last" | sed -n 's/.*ft: \([0-9]*\).*/\1/p')
  corp=$(echo "$last" | sed -n 's/.*corp: \([0-9]*\).*/\1/p')
  result=ok
  if [ $rc -ne 0 ]; then result=$(grep -oE 'ERROR: (libFuzzer|AddressSanitizer|LeakSanitizer): [a-z-]+|runtime error' "$log" | head -1 | tr ' ,' '__'); result=${result:-exit_$rc}; status=1; fi
  echo "$t,${execs:-0},${cov:-},${ft:-},${corp:-},$secs,$result" >> "$out"
  echo "$t: ${execs:-0} executions, ${cov:-?} edges, $secs s: $result (log $log)"
done
exit $status
