#!/bin/sh
# Packs shared scene data for a machine that has none (harness/device/run_on_nvidia.sh unpacks it
# and points GIBENCH_SCENES at it).
#
#   harness/device/make_scenes.sh [OUT [FOLDER...]]
#
# OUT defaults to .scenes/scenes.tar.xz in the checkout; FOLDERs (default: sibenik sponza-crytek)
# are folders of the scene data root ($GIBENCH_SCENES, else ../shared/scenes beside the checkout),
# as the scene files' `data =` lines name them. Prints the archive's size.
set -eu
root=$(cd "$(dirname "$0")/../.." && pwd)
out=${1:-$root/.scenes/scenes.tar.xz}
[ $# -gt 0 ] && shift
[ $# -gt 0 ] || set -- sibenik sponza-crytek
src=${GIBENCH_SCENES:-$root/../shared/scenes}
for d in "$@"; do
    [ -d "$src/$d" ] || { echo "make_scenes: no folder $src/$d" >&2; exit 2; }
done
mkdir -p "$(dirname "$out")"
XZ_OPT="-9 -T$(nproc 2>/dev/null || echo 2)" tar -C "$src" --owner=0 --group=0 -cJf "$out.tmp" "$@"
mv "$out.tmp" "$out"
echo "make_scenes: $out ($(du -k "$out" | cut -f1) KiB): $*"
