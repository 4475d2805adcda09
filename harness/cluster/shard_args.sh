# shellcheck shell=sh disable=SC2034
# Sourced by parallel_shards.sh and slurm_submit.sh: reads "MATRIX N OUT [gibench run options...]"
# from the caller's arguments (shifting the first three off), checks them, and sets root (this
# checkout), matrix (absolute), n and out (created, absolute). Exits 2 on bad usage.
if [ $# -lt 3 ]; then
    echo "usage: $0 MATRIX N OUT [gibench run options...]" >&2
    exit 2
fi
root=$(cd "$(dirname "$0")/../.." && pwd)
matrix=$1
n=$2
out=$3
shift 3
case "$n" in '' | *[!0-9]* | 0) echo "$0: N must be a positive integer, got '$n'" >&2; exit 2 ;; esac
[ -f "$matrix" ] || { echo "$0: no matrix file '$matrix'" >&2; exit 2; }
mkdir -p "$out" || exit 2
out=$(cd "$out" && pwd)
matrix=$(cd "$(dirname "$matrix")" && pwd)/$(basename "$matrix")
