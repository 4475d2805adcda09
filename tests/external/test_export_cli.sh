#!/bin/bash
# `gibench export` (harness/app/cmd_export.c): its refusals, each naming the parameter (no
# arguments, --size, --camera by a name or an index the scene lacks, --components, --time, an
# unknown scene), then an export of hard_thin_wall's second camera by name: the files, job.json's
# camera and size, and the .scene it prints read back: its `direct` reference equals the built-in
# scene's at that camera within 1e-5 relative RMSE (direct is deterministic; the camera's basis
# read back from the node's quaternion differs by float rounding, ~1e-7). About a second.
# Usage: GIBENCH=path/to/gibench test_export_cli.sh WORKDIR
set -u
W=${1:?work dir}
G=${GIBENCH:?GIBENCH}
HERE=$(cd "$(dirname "$0")" && pwd)
rm -rf "$W"
mkdir -p "$W"
. "$HERE/../common/cli_checks.sh"

# expect_msg RC WHAT PHRASE COMMAND...: exits RC and says PHRASE
expect_msg() {
  local rc=$1 what=$2 phrase=$3; shift 3
  expect_rc "$rc" "$what" "$@"
  if grep -qF -- "$phrase" "$W/out.txt"; then pass "$what: says '$phrase'"
  else fail "$what: does not say '$phrase'"; cat "$W/out.txt"; fi
}

expect_msg 0 "export --help" "usage: gibench export SCENE DIR" $G export --help
expect_msg 2 "no arguments" "needs SCENE and DIR" $G export
expect_msg 2 "one argument" "needs SCENE and DIR" $G export cornell
expect_msg 2 "bad --size" "--size expects WIDTHxHEIGHT" $G export cornell "$W/x" --size 0x5
expect_msg 2 "unknown camera name" "--camera 'nosuch': scene 'hard_thin_wall' has no camera" \
  $G export hard_thin_wall "$W/x" --camera nosuch
expect_msg 2 "camera index out of range" "its cameras: 0 dark_side, 1 lit_side" \
  $G export hard_thin_wall "$W/x" --camera 2
expect_msg 2 "bad --components" "--components: unknown component 'light'" \
  $G export cornell "$W/x" --components light
expect_msg 2 "bad --time" "--time expects" $G export cornell "$W/x" --time soon
expect_msg 1 "unknown scene" "nosuchscene" $G export nosuchscene "$W/x"

expect_rc 0 "export hard_thin_wall --camera lit_side" \
  $G export hard_thin_wall "$W/thin" --camera lit_side --size 32x24
cp "$W/out.txt" "$W/export.txt"
for f in scene.gltf scene.bin job.json; do
  [ -s "$W/thin/$f" ] && pass "wrote $f" || fail "no $f"
done
/usr/bin/python3 - "$W/thin/job.json" "$W/thin/scene.gltf" <<'PY' && pass "job.json: camera lit_side, 32x24; glTF: its camera" || fail "job.json or scene.gltf"
import json, sys
job, gltf = (json.load(open(p)) for p in sys.argv[1:3])
c = job["camera"]
assert c["name"] == "lit_side" and c["width"] == 32 and c["height"] == 24, c
assert gltf["cameras"][0]["name"] == "lit_side", gltf["cameras"]
assert abs(gltf["cameras"][0]["perspective"]["aspectRatio"] - 32 / 24) < 1e-12
assert [l["name"] for l in gltf["extensions"]["KHR_lights_punctual"]["lights"]] == ["strong", "dim"]
PY
cp "$W/export.txt" "$W/back.scene" # stdout is the .scene (its other lines comments)
grep -q "^gltf = .*/thin/scene.gltf" "$W/back.scene" && pass "prints a .scene naming the glTF" \
  || { fail "the printed .scene"; cat "$W/export.txt"; }
R="$G reference --component direct --size 32x24 --quiet"
expect_rc 0 "the built-in's reference" $R --scene hard_thin_wall --camera 1 --out "$W/a.exr"
expect_rc 0 "the read-back scene's reference" \
  env GIBENCH_SCENES="$W" $R --scene "$W/back.scene" --out "$W/b.exr"
expect_rc 0 "the two agree within 1e-5 relative RMSE" \
  $G compare "$W/a.exr" "$W/b.exr" --fail-rel-rmse 1e-5
finish
