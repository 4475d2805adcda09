# gibench tests — the one check helper of the shell tests, sourced after `W` (the work directory)
# is set: PASS/FAIL lines counted in `passes` and `fails`, and `finish` to end with them.
#   pass WHAT                         a check that held
#   fail WHAT                         a check that did not
#   expect_rc RC WHAT COMMAND...      COMMAND exits RC; its output is kept in $W/out.txt
#   finish                            prints the counts; exit status 0 when nothing failed
fails=0 passes=0
pass() { echo "PASS: $*"; passes=$((passes + 1)); }
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }
expect_rc() {
  local want=$1 what=$2; shift 2
  "$@" >"$W/out.txt" 2>&1; local rc=$?
  if [ "$rc" = "$want" ]; then pass "$what (exit $rc)"; else fail "$what: exit $rc, expected $want"; cat "$W/out.txt"; fi
}
finish() {
  echo "$passes passed, $fails failed"
  [ "$fails" = 0 ]
}
