#!/usr/bin/env bash
# Builds each layer probe (tests/layers/CMakeLists.txt) and checks it compiles, or fails because
# its header cannot be found; then checks cmake/check_includes.cmake refuses a "../" include.
# Usage: check_layers.sh BUILD_DIR SOURCE_DIR WORK_DIR target:header:ok|fail ...
set -u
build=$1 src=$2 work=$3; shift 3
mkdir -p "$work"
failed=0 passed=0
for probe in "$@"; do
  IFS=: read -r target header expect <<<"$probe"
  log="$work/$target.log"
  if cmake --build "$build" --target "$target" >"$log" 2>&1; then got=ok; else got=fail; fi
  if [ "$got" = ok ] && [ "$expect" = ok ]; then
    passed=$((passed + 1))
  elif [ "$got" = fail ] && [ "$expect" = fail ] && grep -q "$header: No such file" "$log"; then
    passed=$((passed + 1))
  else
    echo "FAIL $target: including $header expected $expect, got $got (log: $log)"
    tail -5 "$log"; failed=$((failed + 1))
  fi
done
# A "../" include is refused, naming the file; the project's own tree passes.
mkdir -p "$work/tree/scenes"
printf '#include "../harness/gl/view.h"\n' >"$work/tree/scenes/climbs.c"
if cmake -DROOT="$work/tree" -DFOLDERS=scenes -P "$src/cmake/check_includes.cmake" \
     >"$work/climb.log" 2>&1 || ! grep -q "scenes/climbs.c" "$work/climb.log"; then
  echo "FAIL check_includes.cmake did not refuse scenes/climbs.c's ../ include"; failed=$((failed + 1))
else passed=$((passed + 1)); fi
if cmake -DROOT="$src" -DFOLDERS="harness|scenes|reference|techniques|tests" \
     -P "$src/cmake/check_includes.cmake" >"$work/tree.log" 2>&1; then passed=$((passed + 1))
else echo "FAIL the source tree has a ../ include:"; cat "$work/tree.log"; failed=$((failed + 1)); fi
echo "$passed passed, $failed failed"
[ "$failed" = 0 ]
