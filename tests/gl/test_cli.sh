#!/usr/bin/env bash
# gibench end to end through its command line. Each check prints PASS/FAIL with what it expected.
set -u
G=${GIBENCH:?set GIBENCH to the gibench executable}
W=${1:?work directory}
rm -rf "$W" && mkdir -p "$W"
. "$(dirname "$0")/../common/cli_checks.sh"

# --help on every command exits 0 and prints a usage line.
for c in "" list render reference compare run bench merge history; do
  if $G $c --help 2>&1 | grep -q usage; then pass "gibench $c --help"; else fail "gibench $c --help"; fi
done
expect_rc 2 "unknown command" $G frobnicate

# The same scene through EGL and through OSMesa gives the same image.
expect_rc 0 "render with EGL" $G render --scene cornell --technique direct --size 64x64 --backend egl --out "$W/egl" --frames 1 --warmup 0
r_egl=$(grep -o 'renderer: .*' "$W/out.txt")
expect_rc 0 "render with OSMesa" $G render --scene cornell --technique direct --size 64x64 --backend osmesa --out "$W/osmesa" --frames 1 --warmup 0
r_osm=$(grep -o 'renderer: .*' "$W/out.txt")
if [ "${r_egl#*|}" = "${r_osm#*|}" ]; then
  # Same rasteriser (llvmpipe under both): the images must be identical.
  expect_rc 0 "EGL and OSMesa images identical (${r_egl#*| })" $G compare "$W/egl/direct_direct.exr" "$W/osmesa/direct_direct.exr" --fail-rmse 0
else
  # Different devices (a GPU through EGL): the same up to rasterisation and float differences.
  expect_rc 0 "EGL (${r_egl}) and OSMesa (${r_osm}) agree to 1e-3 relative RMSE" $G compare "$W/egl/direct_direct.exr" "$W/osmesa/direct_direct.exr" --fail-rel-rmse 1e-3
fi

# compare: JSON, thresholds and errors.
$G compare "$W/egl/direct_direct.exr" "$W/egl/direct_direct.exr" --json >"$W/json.txt"
if grep -q '"rmse": 0, "rel_rmse": 0' "$W/json.txt" && grep -q '"ssim": 1' "$W/json.txt" && grep -q '"nonfinite": 0' "$W/json.txt"; then
  pass "compare --json of an image with itself: rmse 0, ssim 1"; else fail "compare --json: $(cat "$W/json.txt")"; fi
expect_rc 0 "reference direct" $G reference --scene cornell --component direct --spp 1 --size 64x64 --out "$W/ref_direct.exr"
expect_rc 1 "compare above --fail-rmse exits 1" $G compare "$W/ref_direct.exr" "$W/egl/direct_direct.exr" --fail-rmse 1e-9
expect_rc 0 "compare within --fail-rel-rmse 0.5" $G compare "$W/ref_direct.exr" "$W/egl/direct_direct.exr" --fail-rel-rmse 0.5 --map "$W/map.png"
[ -s "$W/map.png" ] && pass "compare --map wrote an error map" || fail "compare --map wrote nothing"
expect_rc 2 "compare with a missing file exits 2" $G compare "$W/nope.exr" "$W/ref_direct.exr"
grep -q "nope.exr" "$W/out.txt" && pass "the error names the missing file" || fail "error does not name the file: $(cat "$W/out.txt")"

# Bad parameters are rejected before anything renders, naming the parameter.
expect_rc 2 "render with an out-of-range parameter" $G render --scene cornell --technique direct --param shadow_res=3 --out "$W/bad"
grep -q "shadow_res" "$W/out.txt" && pass "the error names the parameter" || fail "$(cat "$W/out.txt")"
expect_rc 2 "render with an unknown parameter" $G render --scene cornell --technique direct --param shadowres=512 --out "$W/bad"

# A matrix with a bad value: error names file and line; nothing rendered, no CSV.
cat >"$W/bad.matrix" <<'M'
[matrix]
scenes = cornell
techniques = direct
sizes = 32x32
[params.direct]
pcf = 0, 1
shadow_res = 256, 99999
M
expect_rc 2 "matrix with an out-of-range value" $G run "$W/bad.matrix" --profile default --out "$W/badrun"
grep -q "bad.matrix:7" "$W/out.txt" && pass "matrix error names file and line 7" || fail "$(cat "$W/out.txt")"
[ ! -e "$W/badrun/bad.csv" ] && pass "nothing was rendered for the bad matrix" || fail "bad matrix wrote a CSV"
# [scene_scale] names one of the matrix's scenes, and a scaled length must stay in its range.
cat >"$W/scale.matrix" <<'M'
[matrix]
scenes = cornell
techniques = hbao
sizes = 32x32
[scene_scale]
hard_tiny = 0.0018
M
expect_rc 2 "scene_scale naming a scene not in the matrix" $G run "$W/scale.matrix" --profile default --out "$W/badrun"
grep -q "scale.matrix:6.*hard_tiny" "$W/out.txt" && pass "scene_scale error names file, line and scene" || fail "$(cat "$W/out.txt")"
printf '[matrix]\nscenes = cornell\ntechniques = hbao\nsizes = 32x32\n[scene_scale]\ncornell = 1e-9\n' >"$W/scale.matrix"
expect_rc 2 "scene_scale taking dmax out of its range" $G run "$W/scale.matrix" --profile default --out "$W/badrun"
grep -q "scale.matrix:6.*hbao.dmax" "$W/out.txt" && pass "the error names the scaled parameter" || fail "$(cat "$W/out.txt")"

# One scoring path: `run`, `render` and `compare` give the same RMSE for the same image against the
# same reference (the CSV writes %.9g, render prints %.6g: equal to 1e-5 relative).
printf '[matrix]\nscenes = cornell\ntechniques = hbao\nsizes = 32x32\nframes = 1\nwarmup = 0\nref_spp_ao = 4\n' >"$W/one.matrix"
expect_rc 0 "one row run" $G run "$W/one.matrix" --profile default --out "$W/one" --cache "$W/onecache" --no-history
expect_rc 0 "the same row rendered and scored" $G render --scene cornell --technique hbao --size 32x32 --frames 1 --warmup 0 --ref-spp 4 --cache "$W/onecache" --out "$W/onerender"
rmse_render=$(grep -o 'ao: rmse [0-9.e+-]*' "$W/out.txt" | awk '{print $3}')
rmse_run=$(python3 -c 'import csv, sys; print(next(csv.DictReader(open(sys.argv[1])))["rmse"])' "$W/one/one.csv")
ref_exr=$(ls -t "$W/onecache"/cornell_ao_32x32_*.exr | head -1)
$G compare "$ref_exr" "$W/onerender/hbao_ao.exr" --json >"$W/onejson.txt" 2>&1
rmse_compare=$(python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["rmse"])' "$W/onejson.txt" 2>/dev/null)
if python3 -c 'import sys; a, b, c = map(float, sys.argv[1:]); sys.exit(0 if max(a, b, c) - min(a, b, c) <= 1e-5 * max(a, b, c) else 1)' "$rmse_run" "$rmse_render" "$rmse_compare" 2>/dev/null; then
  pass "run, render and compare score alike (rmse $rmse_run, $rmse_render, $rmse_compare)"
else fail "run, render and compare differ: rmse '$rmse_run', '$rmse_render', '$rmse_compare'"; fi

# Moving scenes: --time changes a moving scene's reference and its cache key, not a static one's;
# a matrix's `times` gives a CSV column `time` and is checked like any value.
expect_rc 0 "reference of a moving scene at t = 0" $G reference --scene cornell_moving --component depth --size 32x32 --cache "$W/tcache" --quiet
expect_rc 0 "reference of a moving scene at t = 1" $G reference --scene cornell_moving --component depth --size 32x32 --cache "$W/tcache" --quiet --time 1
[ "$(ls "$W/tcache"/cornell_moving_depth_32x32_*.exr | wc -l)" = 2 ] && pass "two instants, two cache entries" || fail "$(ls "$W/tcache")"
expect_rc 1 "the two instants differ" $G compare "$W/tcache"/cornell_moving_depth_32x32_*.exr --fail-rmse 0
expect_rc 0 "reference of a static scene at t = 1" $G reference --scene cornell --component depth --size 32x32 --cache "$W/tcache" --quiet --time 1
expect_rc 0 "... and at t = 0" $G reference --scene cornell --component depth --size 32x32 --cache "$W/tcache" --quiet
[ "$(ls "$W/tcache"/cornell_depth_32x32_*.exr | wc -l)" = 1 ] && pass "a static scene has one entry for every instant" || fail "$(ls "$W/tcache")"
cat >"$W/badtime.matrix" <<'M'
[matrix]
scenes = cornell_moving
techniques = direct
sizes = 32x32
times = 0, soon
M
expect_rc 2 "matrix with a bad time" $G run "$W/badtime.matrix" --profile default --out "$W/badrun"
grep -q "badtime.matrix:5" "$W/out.txt" && pass "the error names times' line 5" || fail "$(cat "$W/out.txt")"
cat >"$W/times.matrix" <<'M'
[matrix]
scenes = cornell_moving
techniques = direct
sizes = 32x32
frames = 1
warmup = 1
times = 0, 2
dt = 0.5
ref_spp_direct = 1
M
expect_rc 0 "matrix at two instants" $G run "$W/times.matrix" --profile default --out "$W/trun" --cache "$W/tcache"
[ "$(cut -d, -f10 "$W/trun/times.csv" | sort | tr '\n' ' ')" = "0 2 time " ] && pass "CSV column time holds 0 and 2" || fail "$(cut -d, -f10 "$W/trun/times.csv")"
grep -q ",scene_update," "$W/trun/times_passes.csv" && pass "the vertex upload is a pass of its own" || fail "no scene_update pass"

# Resume: a rerun adds no rows; a truncated last row is redone, the others are kept.
cat >"$W/tiny.matrix" <<'M'
[matrix]
scenes = cornell, plane_box, sponza
techniques = direct
sizes = 32x32
frames = 2
warmup = 0
ref_spp_direct = 1
[params.direct]
shadow_res = 64, 128
M
expect_rc 0 "tiny matrix (sponza skipped when its data is absent)" env GIBENCH_SCENES="$W/no-scenes" $G run "$W/tiny.matrix" --profile default --out "$W/run" --cache "$W/cache"
grep -q "sponza: skipped" "$W/out.txt" && pass "sponza is reported unavailable and skipped" || fail "no skip message: $(cat "$W/out.txt")"
rows=$(($(wc -l <"$W/run/tiny.csv") - 1))
[ "$rows" = 4 ] && pass "4 rows written (2 scenes x 2 resolutions)" || fail "expected 4 rows, got $rows"
expect_rc 0 "rerun" env GIBENCH_SCENES="$W/no-scenes" $G run "$W/tiny.matrix" --profile default --out "$W/run" --cache "$W/cache"
rows2=$(($(wc -l <"$W/run/tiny.csv") - 1))
[ "$rows2" = 4 ] && pass "rerun added no rows" || fail "rerun: $rows2 rows"
head -c -40 "$W/run/tiny.csv" >"$W/t.csv" && mv "$W/t.csv" "$W/run/tiny.csv" # kill mid-row
expect_rc 0 "run after an interruption" env GIBENCH_SCENES="$W/no-scenes" $G run "$W/tiny.matrix" --profile default --out "$W/run" --cache "$W/cache"
grep -q "1 rows written" "$W/out.txt" && pass "only the interrupted row was redone" || fail "$(tail -3 "$W/out.txt")"
notok=$(tail -n +2 "$W/run/tiny.csv" | grep -vc ',ok,')
[ "$notok" = 0 ] && pass "every row's status is ok" || fail "$notok rows are not ok"

finish
