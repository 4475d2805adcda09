#!/usr/bin/env bash
# A parameter a descriptor's constraints forbid is refused before any scene is read: by `render`
# (the scene named does not exist, so an error naming it would mean the scene came first) and by
# `run` while it reads a matrix (nothing rendered, no CSV), the error naming the parameters, the values and the
# rule. One check per kind of constraint: an enumeration, a multiple, a rule between parameters.
set -u
G=${GIBENCH:?set GIBENCH to the gibench executable}
W=${1:?work directory}
rm -rf "$W" && mkdir -p "$W"
. "$(dirname "$0")/../common/cli_checks.sh"
# refused description expected-text command...: exit 2, the text in the error, no scene error
refused() {
  local what=$1 want=$2; shift 2
  "$@" >"$W/out.txt" 2>&1; local rc=$?
  if [ "$rc" = 2 ] && grep -qF -- "$want" "$W/out.txt" && ! grep -q "no scene named" "$W/out.txt"; then
    pass "$what (exit $rc)"
  else
    fail "$what: exit $rc, expected 2 and '$want' before any scene: $(cat "$W/out.txt")"
  fi
}
R="$G render --scene no_such_scene --size 8x8 --out $W/img"

refused "enumeration: ispm_caustics layers=2" "is none of its values (lists = 0, peeled = 4)" \
  $R --technique ispm_caustics --param layers=2
refused "enumeration: lrsm hits by an unknown name" "expects one of its values (algorithm1 = 0, planes = 1)" \
  $R --technique lrsm --param hits=rays
refused "multiple: lrsm rsm_res=513" "'rsm_res' = 513 must be a multiple of 2" \
  $R --technique lrsm --param rsm_res=513
refused "rule: lrsm hits=planes with backface=cosine" "backface = 0 (cosine), coverage = 1 break a rule" \
  $R --technique lrsm --param hits=planes --param backface=cosine
refused "rule: ldm_ao obscurance=1 with dmax=inf" "obscurance = 1, dmax = inf break a rule" \
  $R --technique ldm_ao --param obscurance=1

# The names are the numbers: hits=algorithm1 with backface=cosine passes the rules and reaches
# the scene, which is then the error.
$R --technique lrsm --param hits=algorithm1 --param backface=cosine >"$W/out.txt" 2>&1
grep -q "no scene named 'no_such_scene'" "$W/out.txt" && pass "a combination the rules allow reaches the scene" \
  || fail "hits=algorithm1 backface=cosine: $(cat "$W/out.txt")"

# A matrix whose lists combine into a forbidden run: refused with the file while the matrix is
# read, before its first scene is loaded: nothing rendered.
cat >"$W/rule.matrix" <<'M'
[matrix]
scenes = cornell
techniques = ispm_caustics
sizes = 8x8
[params.ispm_caustics]
rsm_res = 16, 64
mask_level = 5
M
refused "a matrix combining rsm_res=16 with mask_level=5" "rule.matrix: [params.ispm_caustics] on scene cornell: technique 'ispm_caustics': rsm_res = 16, mask_level = 5 break a rule" \
  $G run "$W/rule.matrix" --profile default --out "$W/run"
[ ! -e "$W/run" ] || [ -z "$(ls -A "$W/run")" ] && pass "nothing written for the refused matrix" || fail "the refused matrix wrote $(ls "$W/run")"

finish
