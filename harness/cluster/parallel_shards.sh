#!/bin/sh
# Runs a matrix as N shards with GNU parallel (Debian `parallel`), then merges them: the recipe of
# README's "Spreading a matrix over machines".
#
#   harness/cluster/parallel_shards.sh MATRIX N OUT [gibench run options...]
#
# Shard I writes OUT/shard-I/ (its CSVs, manifest, images) and its log OUT/shard-I.log; the merged
# table goes to OUT/merged/. Environment:
#   GIBENCH        the gibench binary (default: build/gibench of this checkout)
#   JOBS           shards at once on this machine (default N)
#   PARALLEL_ARGS  more options for parallel, e.g. over ssh hosts that see this checkout and OUT at
#                  the same paths (a shared file system): PARALLEL_ARGS="-S host1,host2 --workdir ."
# Exit status: the merge's (0 when every shard's rows are there and agree), 2 for bad usage.
set -u
. "$(dirname "$0")/shard_args.sh"
gibench=${GIBENCH:-$root/build/gibench}
command -v parallel >/dev/null 2>&1 || { echo "$0: GNU parallel is not installed (make deps)" >&2; exit 2; }

# --halt never: every shard runs even when another has rows that are not `ok` (exit 1); the merge
# then checks that each shard finished (its manifest) and that no row is missing.
# shellcheck disable=SC2086
parallel --halt never --jobs "${JOBS:-$n}" ${PARALLEL_ARGS:-} \
    "$gibench" run "$matrix" --shard "{}/$n" --out "$out/shard-{}" "$@" ">" "$out/shard-{}.log" "2>&1" \
    ::: $(seq 1 "$n")
failed=$?
[ $failed -eq 0 ] || echo "$0: $failed shard(s) exited non-zero (rows not ok, or a failure): see $out/shard-*.log" >&2
rm -rf "$out/merged"
exec "$gibench" merge $(seq -f "$out/shard-%g" 1 "$n") --out "$out/merged"
