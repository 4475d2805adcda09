#!/bin/sh
# Submits a matrix to Slurm as an N-task job array (harness/cluster/slurm_array.sbatch) and a merge
# job that runs once every task has ended: the Slurm recipe of README's "Spreading a matrix over
# machines".
#
#   harness/cluster/slurm_submit.sh MATRIX N OUT [gibench run options...]
#
# Shard I writes OUT/shard-I/, its log OUT/shard-I.log; the merge writes OUT/merged/ and logs to
# OUT/merge.log. The merge depends on the array with afterany, not afterok: a shard whose rows are
# not all `ok` exits 1 yet wrote its rows; the merge itself refuses shards that did not finish.
# Environment: GIBENCH (the binary, default build/gibench of this checkout), SBATCH_ARGS (more sbatch
# options: partition, time, account...), WAIT=1 to return only when the merge has run, with its
# exit status.
set -u
. "$(dirname "$0")/shard_args.sh"
export GIBENCH="${GIBENCH:-$root/build/gibench}"
# shellcheck disable=SC2086
array=$(sbatch --parsable ${SBATCH_ARGS:-} --array="1-$n" --chdir="$root" --export=ALL \
    --output="$out/shard-%a.log" "$root/harness/cluster/slurm_array.sbatch" "$matrix" "$out" "$@") || exit 1
array=${array%%;*}
echo "job array $array: $n shards of $(basename "$matrix") into $out/shard-*"
dirs=$(seq -f "$out/shard-%g" 1 "$n" | tr '\n' ' ')
wait_opt=
[ "${WAIT:-0}" = 1 ] && wait_opt=--wait
# shellcheck disable=SC2086
merge=$(sbatch --parsable ${SBATCH_ARGS:-} $wait_opt --dependency="afterany:$array" --chdir="$root" \
    --export=ALL --job-name=gibench-merge --output="$out/merge.log" \
    --wrap="rm -rf '$out/merged' && '$GIBENCH' merge $dirs --out '$out/merged'")
rc=$?
echo "merge job ${merge%%;*}: $out/merged (log $out/merge.log)"
exit $rc
