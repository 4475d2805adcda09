#!/bin/bash
# The example plugin end to end (tests/plugins/CMakeLists.txt): install, build out of tree (CMake and
# pkg-config), list, check-technique, a matrix run, and the refusals. One PASS/FAIL line per check.
# Environment: BUILD (gibench's build tree), SRC (its sources), CMAKE, CC. $1: a scratch folder.
set -u
work=${1:?scratch folder}
rm -rf "$work" && mkdir -p "$work"
failures=0
check() { # check WHAT CONDITION-EXIT-STATUS [DETAIL]
    if [ "$2" = 0 ]; then echo "PASS $1"; else echo "FAIL $1${3:+: $3}"; failures=$((failures + 1)); fi
}
# Commands whose output a failure prints.
run() { local log=$1; shift; "$@" >"$log" 2>&1; local rc=$?; [ $rc = 0 ] || tail -30 "$log"; return $rc; }

prefix=$work/prefix
run "$work/install.log" "$CMAKE" --install "$BUILD" --prefix "$prefix"
check "cmake --install into a temporary prefix" $?
gibench=$prefix/bin/gibench
[ -x "$gibench" ] && [ -f "$prefix/include/gibench/techniques/technique.h" ] &&
    [ -f "$prefix/include/gibench/glad/gl.h" ]
check "installed: bin/gibench, include/gibench/techniques/technique.h, glad/gl.h" $?

# Out of tree with CMake: find_package(gibench) through CMAKE_PREFIX_PATH.
run "$work/configure.log" "$CMAKE" -S "$SRC/examples/ssao_plugin" -B "$work/build" \
    -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release -DCMAKE_C_COMPILER="$CC" &&
    run "$work/build.log" "$CMAKE" --build "$work/build"
check "example built out of tree with find_package(gibench)" $?
plugin=$work/build/ssao.so

# The same source with the pkg-config compile line.
pc=$(dirname "$(find "$prefix" -name gibench.pc | head -1)")
flags=$(PKG_CONFIG_PATH=$pc pkg-config --cflags --libs gibench)
check "pkg-config --cflags --libs gibench" $? "$flags"
echo "  pkg-config: $flags"
pcc() { "$CC" -std=c11 -shared -fPIC -fvisibility=hidden -Wall -Werror -Wno-missing-field-initializers \
        $flags "$@" "$SRC/examples/ssao_plugin/ssao.c"; }
run "$work/pc.log" pcc -o "$work/ssao_pc.so"
check "example compiled with the pkg-config line" $?

out=$("$gibench" --plugin "$plugin" list 2>&1)
rc=$?
echo "$out" | grep -q "^  ssao .*outputs ao" && echo "$out" | grep -q "plugin: $plugin" &&
    echo "$out" | grep -q "^  hbao "
check "gibench --plugin ssao.so list: ssao listed (with its file) beside the built-ins" $(( rc || $? ))

"$gibench" --plugin "$plugin" check-technique ssao >"$work/check.log" 2>&1
rc=$?
cat "$work/check.log"
[ $rc = 0 ] && grep -q "^PASS ssao: 0 failed checks" "$work/check.log" &&
    ! grep -q "^FAIL" "$work/check.log" && grep -q "^PASS ssao contract at run time" "$work/check.log"
check "gibench --plugin ssao.so check-technique ssao" $?

GIBENCH_PLUGINS="/nonexistent-first-is-fine-no:$work/ssao_pc.so" "$gibench" check-technique ssao --no-gl \
    >"$work/env.log" 2>&1
grep -q "cannot be loaded" "$work/env.log"
check "GIBENCH_PLUGINS: a missing file refused by name" $? "$(cat "$work/env.log")"
GIBENCH_PLUGINS="$work/ssao_pc.so" "$gibench" check-technique ssao --no-gl >"$work/env.log" 2>&1
check "GIBENCH_PLUGINS=ssao_pc.so (the pkg-config build) check-technique ssao --no-gl" $? \
    "$(tail -5 "$work/env.log")"

# The example's matrix: ssao beside hbao and ldm_ao on the Cornell box, at its quick profile's size.
run "$work/run.log" "$gibench" --plugin "$plugin" run "$SRC/examples/ssao_plugin/ssao.matrix" \
    --profile quick --out "$work/out" --cache "$work/cache" --no-history --no-images
check "gibench --plugin ssao.so run examples/ssao_plugin/ssao.matrix" $?
python3 - "$work/out/ssao.csv" <<'PY'
import csv, math, sys
rows = list(csv.DictReader(open(sys.argv[1])))
for r in rows:
    print("  %-8s %-7s status %-4s rmse %s" % (r["technique"], r["scene"], r["status"], r["rmse"]))
seen = {r["technique"] for r in rows if r["status"] == "ok" and math.isfinite(float(r["rmse"]))}
sys.exit(0 if {"ssao", "hbao", "ldm_ao"} <= seen else 1)
PY
check "ssao.csv: ssao, hbao and ldm_ao rows with status ok and a finite RMSE" $?

# A plugin of another contract version: refused, naming both versions and the file.
run "$work/v999.log" pcc -DGIB_CONTRACT_VERSION_OVERRIDE=999 -o "$work/ssao_v999.so"
"$gibench" --plugin "$work/ssao_v999.so" list >"$work/v999.out" 2>&1
rc=$?
cat "$work/v999.out" | head -3
version=$(sed -n 's/^#define GIB_CONTRACT_VERSION \([0-9]*\)$/\1/p' "$SRC/techniques/technique.h")
[ $rc != 0 ] && grep -q "ssao_v999.so" "$work/v999.out" && grep -q "version 999" "$work/v999.out" &&
    grep -q "version $version" "$work/v999.out"
check "a plugin of contract version 999 refused naming both versions (999, $version) and its file" $?

# A plugin technique named after a built-in: refused.
run "$work/hbao.log" pcc '-DSSAO_NAME="hbao"' -o "$work/ssao_hbao.so"
"$gibench" --plugin "$work/ssao_hbao.so" list >"$work/hbao.out" 2>&1
rc=$?
head -3 "$work/hbao.out"
[ $rc != 0 ] && grep -q "'hbao' has the name of a built-in" "$work/hbao.out"
check "a plugin technique named hbao refused (the name of a built-in)" $?

echo "$([ $failures = 0 ] && echo PASS || echo FAIL): techniques as plugins ($failures failed)"
[ $failures = 0 ]
