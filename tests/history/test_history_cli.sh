#!/bin/bash
# The results history end to end (harness/app/history.c, cmd_history.c): two `gibench run` at once
# into one history lose no row; --no-history, the default path, a bad path; `gibench history`'s
# table, --find (no regression on identical reruns; a constructed worse revision found), --plot,
# --machines; the quality gate's history comparison (check_quality.py) on these rows.
# Usage: GIBENCH=path/to/gibench test_history_cli.sh WORKDIR
set -u
W=${1:?work dir}
G=${GIBENCH:?GIBENCH}
HERE=$(cd "$(dirname "$0")" && pwd)
rm -rf "$W"
mkdir -p "$W"
. "$HERE/../common/cli_checks.sh"
py() { /usr/bin/python3 -c "$@"; }

cat >"$W/tiny.matrix" <<'M'
[matrix]
description = history test: procedural scenes, tiny
scenes = cornell, plane_box
techniques = direct, hbao
sizes = 32x32
frames = 1
warmup = 0
ref_spp_direct = 4
ref_spp_ao = 4
[params.direct]
pcf = 0, 1
M
R="$G run $W/tiny.matrix --profile default --cache $W/cache --no-images"
# References first, so the two concurrent runs below write rows, not references, at once.
$R --out "$W/warm" --no-history >"$W/warm.txt" 2>&1 || { cat "$W/warm.txt"; fail "warm-up run"; }

# 1. Two writers at once into one history.
$R --out "$W/a" --history "$W/h.sqlite" >"$W/a.txt" 2>&1 &
pa=$!
$R --out "$W/b" --history "$W/h.sqlite" >"$W/b.txt" 2>&1 &
pb=$!
wait $pa; ra=$?
wait $pb; rb=$?
[ $ra = 0 ] && [ $rb = 0 ] && pass "two concurrent runs exit 0" || { cat "$W/a.txt" "$W/b.txt"; fail "concurrent runs exit $ra $rb"; }
csv_rows=$(( $(tail -n +2 "$W/a/tiny.csv" | wc -l) + $(tail -n +2 "$W/b/tiny.csv" | wc -l) ))
db_rows=$(py "import sqlite3; print(sqlite3.connect('$W/h.sqlite').execute('select count(*) from result').fetchone()[0])")
[ "$csv_rows" = 12 ] && [ "$db_rows" = "$csv_rows" ] && pass "history holds all $db_rows rows of both runs" \
  || fail "history has $db_rows rows, the CSVs $csv_rows (12 expected)"
py "
import sqlite3, csv, json
db = sqlite3.connect('$W/h.sqlite')
got = sorted((r['scene'], r['technique'], r['params'], r['rmse'], r['ssim']) for r in
             (json.loads(j) for (j,) in db.execute('select row_json from result')))
want = sorted((r['scene'], r['technique'], r['params'], float(r['rmse']), float(r['ssim']))
              for f in ('a', 'b') for r in csv.DictReader(open('$W/' + f + '/tiny.csv')))
assert got == want, (got, want)
m = db.execute('select renderer, cores, cpu from machine').fetchall()
assert len(m) == 1 and m[0][1] > 0 and m[0][2], m
" && pass "row_json equals the CSV rows; one machine with cores and CPU" || fail "history rows differ from the CSVs"

# A rerun that finds every row in its CSV records nothing (no empty run either).
$R --out "$W/a" --history "$W/h.sqlite" >"$W/a2.txt" 2>&1
n=$(py "import sqlite3; print(*sqlite3.connect('$W/h.sqlite').execute('select count(*), (select count(*) from run) from result').fetchone())")
[ "$n" = "12 2" ] && pass "a rerun with nothing to do records nothing" || fail "after a rerun: rows, runs = $n"

# 2. --no-history writes none; the default is DIR/history.sqlite; a bad path is an error naming it.
$R --out "$W/c" --no-history >/dev/null 2>&1
[ ! -e "$W/c/history.sqlite" ] && pass "--no-history records nothing" || fail "--no-history wrote a history"
$R --out "$W/d" >/dev/null 2>&1
[ -s "$W/d/history.sqlite" ] && pass "default history DIR/history.sqlite" || fail "no DIR/history.sqlite"
$R --out "$W/e" --history "$W/missing/dir/h.sqlite" >"$W/e.txt" 2>&1
rc=$?
[ $rc = 1 ] && grep -q "missing/dir/h.sqlite" "$W/e.txt" && pass "unwritable --history: exit 1 naming the file" \
  || fail "unwritable --history: exit $rc: $(cat "$W/e.txt")"

# 3. gibench history: table, find, plot, machines, bad options.
$G history --db "$W/h.sqlite" --technique hbao >"$W/t.txt" 2>&1
[ "$(grep -c 'tiny: .* hbao ao' "$W/t.txt")" = 2 ] && grep -q " 2 .*0\." "$W/t.txt" \
  && pass "table: 2 hbao series, 2 rows per revision" || fail "table: $(cat "$W/t.txt")"
$G history --db "$W/h.sqlite" --find >"$W/f.txt" 2>&1
[ $? = 0 ] && grep -q "0 of 6 series got worse" "$W/f.txt" && pass "--find: identical reruns are no regression" \
  || fail "--find: $(cat "$W/f.txt")"
cp "$W/h.sqlite" "$W/h2.sqlite"
# A later revision whose hbao rows have 1.5x the RMSE, appended as gibench run would.
py "
import sqlite3
db = sqlite3.connect('$W/h2.sqlite')
db.execute(\"insert into run(machine_id, revision, started, matrix, profile, host) select machine_id, 'later', started, matrix, profile, host from run where id = 1\")
rid = db.execute('select max(id) from run').fetchone()[0]
cols = [c[1] for c in db.execute('pragma table_info(result)') if c[1] not in ('id', 'run_id', 'revision', 'row_json')]
db.execute(f\"insert into result(run_id, revision, row_json, {', '.join(cols)}) select {rid}, 'later', json_set(row_json, '$.rmse', json_extract(row_json, '$.rmse') * 1.5, '$.git_revision', 'later'), {', '.join(cols)} from result where run_id = 1 and technique = 'hbao'\")
db.commit()
"
$G history --db "$W/h2.sqlite" --find >"$W/f2.txt" 2>&1
rc=$?
[ $rc = 1 ] && [ "$(grep -c 'rmse worse at revision later' "$W/f2.txt")" = 2 ] && grep -q "2 of 6 series got worse" "$W/f2.txt" \
  && pass "--find names the worse revision of both hbao rows, exit 1" || fail "--find exit $rc: $(cat "$W/f2.txt")"
$G history --db "$W/h2.sqlite" --find --metric ssim >/dev/null 2>&1
[ $? = 0 ] && pass "--find --metric ssim: unchanged ssim is no regression" || fail "--find --metric ssim"
$G history --db "$W/h2.sqlite" --technique hbao --plot "$W/plot.png" >"$W/p.txt" 2>&1
[ "$(head -c 4 "$W/plot.png" 2>/dev/null | od -An -c | tr -d ' ')" = "211PNG" ] && pass "--plot writes a PNG" \
  || fail "--plot: $(cat "$W/p.txt")"
# A foreign history whose revision carries a gnuplot command, and a PNG path with a quote: the
# plot is drawn and the command never runs (text reaches gnuplot only as a quoted string).
cp "$W/h2.sqlite" "$W/evil.sqlite"
py "import sqlite3; db = sqlite3.connect('$W/evil.sqlite'); db.execute(\"update result set revision = ? where revision = 'later'\", (\"x' ; system('touch $W/pwned') ; print '\",)); db.commit()"
$G history --db "$W/evil.sqlite" --technique hbao --plot "$W/it's.png" >"$W/e.txt" 2>&1
[ ! -e "$W/pwned" ] && [ "$(head -c 4 "$W/it's.png" 2>/dev/null | od -An -c | tr -d ' ')" = "211PNG" ] \
  && pass "--plot: quotes in a revision and the path are text, not gnuplot commands" \
  || fail "--plot with quotes: $(cat "$W/e.txt"); pwned: $(ls "$W/pwned" 2>&1)"
$G history --db "$W/h.sqlite" --machines | grep -q "machine 1: .* 2 runs, 12 rows" && pass "--machines" \
  || fail "--machines: $($G history --db "$W/h.sqlite" --machines)"
$G history --db "$W/h.sqlite" --metric "rmse;drop" >/dev/null 2>&1
[ $? = 2 ] && pass "a metric that is no column: exit 2" || fail "bad metric accepted"
$G history --help | grep -q "usage: gibench history" && pass "history --help" || fail "history --help"
$G history --db "$W/nothing.sqlite" >/dev/null 2>&1
[ $? = 3 ] && pass "no history file: exit 3" || fail "missing history file"
cp "$W/h.sqlite" "$W/ro.sqlite" && chmod a-w "$W/ro.sqlite"
$G history --db "$W/ro.sqlite" --technique hbao >/dev/null 2>&1
[ $? = 0 ] && pass "a read-only history is queried" || fail "read-only history"
cp "$W/a/tiny.csv" "$W/notdb.sqlite"
$G history --db "$W/notdb.sqlite" >"$W/n.txt" 2>&1
rc=$?
[ $rc = 1 ] && grep -q "notdb.sqlite" "$W/n.txt" && pass "a file that is no history: exit 1 naming it" \
  || fail "not a history: exit $rc: $(cat "$W/n.txt")"

# 4. The quality gate's comparison with the history's best (check_quality.py --history).
py "
import csv, sys
sys.path.insert(0, '$HERE/../quality')
import check_quality as q
rows = {tuple(r[k] for k in q.KEY): r for r in csv.DictReader(open('$W/a/tiny.csv'))}
ren = next(iter(rows.values()))['renderer']
last = q.history_last_run('$W/h2.sqlite')
b = q.history_bests('$W/h2.sqlite', 'tiny', ren, last)
assert len(b) == 6, b
assert q.history_bests('$W/h2.sqlite', 'tiny', 'another renderer', last) == {}
p, f = q.check_history(rows, b)
assert (p, f) == (6, 0), (p, f)   # the 1.5x revision does not lower the bar: the best is kept
for r in rows.values():
    r['rmse'] = str(float(r['rmse']) * 1.1)   # 10% worse: beyond the gate's 2%
p, f = q.check_history(rows, b)
assert (p, f) == (0, 6), (p, f)
" >"$W/q.txt" 2>&1 && pass "quality gate against the history's best: equal rows pass, 10% worse fail" \
  || fail "quality gate history: $(cat "$W/q.txt")"

finish
