#!/bin/sh
# make test's runs, at once: the sanitizer build's ctest (ASan+UBSan, LeakSanitizer with only
# Mesa's and the driver's own leaks suppressed), the release build's ctest and ThreadSanitizer's
# script, each line prefixed with its run's name. On 2 cores one run's idle moments (a long test
# alone at its end, a script waiting on a process it started) are another's work; the tests' own
# timeouts allow for the shared cores (a third of a timeout at most on a busy 2-core machine).
# Exit status 0 when all three pass; else each failed run is named at the end.
#
#   sh tests/run_suites.sh ASAN_BUILD RELEASE_BUILD TSAN_BUILD JOBS
set -u
root=$(cd "$(dirname "$0")/.." && pwd)
asan=$1 release=$2 tsan=$3 jobs=$4
status_dir=$(mktemp -d)
trap 'rm -rf "$status_dir"' EXIT

# run NAME DIR COMMAND...: COMMAND in DIR, its lines prefixed "[NAME] ", its status kept.
run() {
    name=$1 dir=$2
    shift 2
    ( cd "$dir" && "$@" 2>&1; echo $? > "$status_dir/$name" ) | sed -u "s/^/[$name] /"
}

run asan "$asan" env ASAN_OPTIONS=detect_leaks=1 \
    LSAN_OPTIONS=suppressions="$root/tests/lsan_mesa.supp" UBSAN_OPTIONS=print_stacktrace=1 \
    ctest --output-on-failure -j"$jobs" -LE release_only &
run release "$release" ctest --output-on-failure -j"$jobs" -LE sanitizer_only &
run tsan "$root" sh tests/tsan/run_tsan.sh "$tsan" "$tsan/tsan-work" &
wait

failed=""
for name in asan release tsan; do
    rc=$(cat "$status_dir/$name" 2>/dev/null || echo missing)
    [ "$rc" = 0 ] || failed="$failed $name(exit $rc)"
done
if [ -n "$failed" ]; then
    echo "make test: failed:$failed (their lines are prefixed with the run's name)"
    exit 1
fi
echo "make test: the sanitizer, release and ThreadSanitizer runs passed"
