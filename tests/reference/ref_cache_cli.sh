#!/bin/sh
# The reference cache through the CLI (harness/app/refcache.c, cmd_reference.c): a first request
# renders into the cache, a second one reads it, --force renders again, and an entry that is
# truncated, whose header belongs to another request, or whose header or pixels were edited after
# it was written (its seal) is detected and rendered again, never used.
# Also: --out beside --cache writes the same pixels (gibench compare: RMSE exactly 0), and two
# plain --out renders of the same request have identical pixels; output paths that could not be
# written are refused before rendering; the --stderr map is marked as one; Ctrl-C during a
# --target-noise render keeps the rounds done (exit 130), equal to a plain render of that spp;
# --cone (one diffuse cone of indirect) has entries and a header of its own; the temporaries of
# writers killed mid-write are removed at the entry's next write; a set of components (--component
# with a list) writes one entry or file each, each its render alone.
# Usage: ref_cache_cli.sh GIBENCH WORKDIR. Expected values are exact strings and an RMSE of 0.
set -u
G="$1"
D="$2/ref_cache_cli"
rm -rf "$D"
mkdir -p "$D"
fail=0
check() { # check WHAT EXPECTED-SUBSTRING OUTPUT
    case "$3" in
    *"$2"*) echo "ok: $1" ;;
    *) echo "FAIL: $1: expected '$2' in: $3"; fail=1 ;;
    esac
}
check_eq() { # check_eq WHAT EXPECTED ACTUAL
    if [ "$2" = "$3" ]; then echo "ok: $1"; else echo "FAIL: $1: expected '$2', got '$3'"; fail=1; fi
}
check_not() { # check_not WHAT UNEXPECTED-SUBSTRING OUTPUT
    case "$3" in
    *"$2"*) echo "FAIL: $1: did not expect '$2' in: $3"; fail=1 ;;
    *) echo "ok: $1" ;;
    esac
}
attr() { # attr FILE KEY: the header attribute's value, quoted as oiiotool prints it
    oiiotool --info -v "$1" 2>&1 | sed -n "s/^ *$2: //p"
}
ref() { "$G" reference --scene cornell --component ao --spp 4 --size 16x12 --quiet "$@" 2>&1; }

out=$(ref --cache "$D/cache")
check "first request renders" "rendered into cache" "$out"
entry=$(ls "$D"/cache/*.exr)
out=$(ref --cache "$D/cache")
check "second request reads the cache" "from cache" "$out"
out=$(ref --cache "$D/cache" --force)
check "--force renders again" "rendered into cache" "$out"

# what writers killed mid-write (SIGKILL) left beside the entry: their temporaries, ours and the
# one OpenEXR writes through, go at the entry's next write; a running writer's (this shell's) stay
dead=$(sh -c 'echo $$')
base=$(basename "$entry")
touch "$entry.tmp$dead" "$D/cache/tmp.$dead$base.tmp$dead" "$entry.tmp$$"
ref --cache "$D/cache" --force > /dev/null
check_eq "a dead writer's temporaries are removed" "" "$(ls "$D/cache" | grep "tmp$dead")"
check_eq "... a running writer's kept" "$base.tmp$$" "$(ls "$D/cache" | grep "tmp$$")"
rm -f "$entry.tmp$$"

# a truncated entry
head -c 100 "$entry" > "$D/trunc" && mv "$D/trunc" "$entry"
out=$(ref --cache "$D/cache")
check "a truncated entry is rendered again" "unreadable" "$out"
check "... and replaced" "rendered into cache" "$out"

# another request's entry (dmax 0.5) copied over this one: its key does not match
ref --cache "$D/cache" --dmax 0.5 > /dev/null
other=$(ls "$D"/cache/*.exr | grep -v "$entry")
cp "$other" "$entry"
out=$(ref --cache "$D/cache")
check "an entry of another request is rendered again" "does not match its key" "$out"
out=$(ref --cache "$D/cache")
check "... and then read" "from cache" "$out"

# an entry whose header (spp) or pixels were edited after it was written: its seal does not match
oiiotool "$entry" --sattrib spp 99 -o "$D/edit.exr" && mv "$D/edit.exr" "$entry"
out=$(ref --cache "$D/cache")
check "an entry with an edited header is rendered again" "does not match its seal" "$out"
oiiotool "$entry" --mulc 2 -o "$D/edit.exr" && mv "$D/edit.exr" "$entry"
out=$(ref --cache "$D/cache")
check "an entry with edited pixels is rendered again" "does not match its seal" "$out"
out=$(ref --cache "$D/cache" --threads 1)
check "--threads goes with --cache (it does not change the image)" "from cache" "$out"

# --out beside --cache, and two plain renders: the same pixels
ref --cache "$D/cache" --out "$D/via_cache.exr" > /dev/null
ref --out "$D/a.exr" > /dev/null
ref --out "$D/b.exr" > /dev/null
out=$("$G" compare "$D/a.exr" "$D/via_cache.exr" --json 2>&1)
check "--out beside --cache holds the rendered pixels" '"rmse": 0,' "$out"
out=$("$G" compare "$D/a.exr" "$D/b.exr" --json 2>&1)
check "two renders of one request: identical pixels" '"rmse": 0,' "$out"

# a random component with one sample is refused (its variance would be unknown)
out=$("$G" reference --scene cornell --component indirect --spp 1 --size 8x8 --out "$D/x.exr" 2>&1)
check "spp 1 of a random component is refused" "at least 2" "$out"
# --force without --cache is refused
out=$(ref --out "$D/x.exr" --force)
check "--force needs --cache" "give --cache" "$out"
# output files that could not be written are refused before rendering, naming the option
mkdir -p "$D/dir.exr"
out=$(ref --out "$D/dir.exr"); rc=$?
check "--out a directory is refused" "--out $D/dir.exr is a directory" "$out"
check_eq "... as a usage error" "2" "$rc"
out=$(ref --out "$D/no_such_folder/x.exr")
check "--out in a missing folder is refused" "folder $D/no_such_folder does not exist" "$out"
out=$(ref --out "$D/x.png")
check "--out must be an EXR" "must end in .exr" "$out"
out=$(ref --out "$D/s.exr" --stderr "$D/./s.exr")
check "--stderr onto the --out file is refused" "need two files" "$out"
out=$("$G" reference --scene cornell --component indirect --size 8x8 --spp 8 --target-noise 0.1 \
      --max-spp 4 --out "$D/x.exr" 2>&1)
check "--max-spp below --spp is refused, naming both" "--max-spp 4 is below --spp 8" "$out"

# the standard-error map says what it is, and is no cache entry
ref --out "$D/s.exr" --stderr "$D/se.exr" > /dev/null
check "the --stderr header is marked" '"standard_error"' "$(attr "$D/se.exr" image)"
check "... and has no cache key" '"none"' "$(attr "$D/se.exr" cache_key)"
check_not "the image's header is not marked" 'standard_error' "$(attr "$D/s.exr" image)"

# --sampler: the header names it; random renders stay out of the cache (it holds sobol renders)
check "the default sampler is sobol" '"sobol"' "$(attr "$D/s.exr" sampler)"
ref --out "$D/random.exr" --sampler random > /dev/null
check "--sampler random renders with PCG32 and says so" '"random"' "$(attr "$D/random.exr" sampler)"
out=$(ref --cache "$D/cache" --sampler random); rc=$?
check_eq "--sampler random with --cache: exit 2" "2" "$rc"
check "... saying why" "--sampler random goes with --out only" "$out"
out=$(ref --out "$D/h.exr" --sampler halton); rc=$?
check_eq "an unknown sampler: exit 2" "2" "$rc"
check "... naming it" "--sampler 'halton': sobol or random" "$out"

# --cone: one diffuse cone's share of indirect, its own cache entry, named in the header; refused
# for other components
ci() { "$G" reference --scene cornell --component indirect --spp 4 --size 8x8 --quiet "$@" 2>&1; }
out=$(ci --cache "$D/cache" --cone 2)
check "--cone renders into the cache" "rendered into cache" "$out"
out=$(ci --cache "$D/cache")
check "... an entry apart from the whole hemisphere's" "rendered into cache" "$out"
ci --out "$D/cone.exr" --cone 2 > /dev/null
check "the header names the cone" '"2 of 6, aperture 60 degrees"' "$(attr "$D/cone.exr" cone)"
check_eq "... the whole hemisphere's header has no cone" "" "$(attr "$D/a.exr" cone)"
out=$(ref --out "$D/x.exr" --cone 1); rc=$?
check_eq "--cone with ao: exit 2" "2" "$rc"
check "... saying why" "--cone and --cone-aperture go with --component indirect" "$out"
out=$(ci --out "$D/x.exr" --cone 6)
check "a cone beyond the set is refused" "--cone" "$out"

# a target noise asked of a deterministic estimator is met at once (its noise is exactly 0)
out=$("$G" reference --scene cornell --component direct --size 8x8 --target-noise 0.01 \
      --out "$D/d.exr" 2>&1)
check_not "a deterministic component meets any target noise" "not reached" "$out"

# Ctrl-C once a round is done: the round in progress is abandoned, the rounds finished are
# written (exit 130), and they are exactly a plain render of that many samples. The target
# cannot be met.
# A background job of a script inherits SIGINT ignored; `env --default-signal=INT` gives it the
# terminal's default, as an interactive shell would.
start() { # start LOG PREFIX ARGS...: PREFIX gibench reference ARGS in the background ($pid),
           # returning after its round 2
    log="$1"; pre="$2"; shift 2
    $pre "$G" reference --scene cornell --component ao --size 16x12 --spp 4 \
        --target-noise 1e-9 --max-spp 16777216 "$@" 2> "$log" &
    pid=$!
    wait_for "(round 2)" "$log"
}
wait_for() { # wait_for TEXT LOG: up to 60 s
    n=0
    while ! grep -q "$1" "$2" && [ $n -lt 1200 ]; do sleep 0.05; n=$((n + 1)); done
}
finish() { # finish: waits for $pid (killing it after 60 s: one that ignored SIGINT fails here)
    (sleep 60; kill -KILL $pid) > /dev/null 2>&1 &
    watchdog=$!
    wait $pid
    rc=$?
    kill $watchdog 2> /dev/null
    return $rc
}
start "$D/int.log" "env --default-signal=INT" --out "$D/int.exr" > /dev/null
kill -INT $pid; finish; rc=$?
check_eq "an interrupted render exits with 130" "130" "$rc"
check "... and says why it stopped in its header" '"interrupted"' "$(attr "$D/int.exr" stop)"
spp=$(attr "$D/int.exr" spp | tr -d '"')
ref --spp "$spp" --out "$D/plain.exr" > /dev/null
out=$("$G" compare "$D/plain.exr" "$D/int.exr" --json 2>&1)
check "the rounds done ($spp spp) are a plain render of that spp" '"rmse": 0,' "$out"
start "$D/intc.log" "env --default-signal=INT" --cache "$D/icache" > /dev/null
kill -INT $pid; finish; rc=$?
check_eq "an interrupted cache render exits with 130" "130" "$rc"
check "... writes the rounds done beside the entry" "interrupted.exr" "$(ls "$D/icache")"
check_not "... and no entry (it missed its target)" "_ao_16x12_" "$(ls "$D/icache" | grep -v interrupted)"
oiiotool "$entry" --sattrib stop interrupted -o "$D/edit.exr" && mv "$D/edit.exr" "$entry"
out=$(ref --cache "$D/cache")
check "an interrupted render put in as an entry is rendered again" "a finished render" "$out"
# SIGINT ignored by whoever started it (a script's background job) stays ignored: more rounds
# follow the signal than the one that was in progress
start "$D/ign.log" "" --out "$D/ign.exr" > /dev/null
kill -INT $pid
wait_for "(round 4)" "$D/ign.log"
check "an inherited SIGINT ignore is kept" "(round 4)" "$(cat "$D/ign.log")"
kill -TERM $pid; finish 2> /dev/null

# a set (--component with a list): one entry a component, which single requests find; --out
# writes F.C.exr a component, each the pixels of its render alone
set_ref() { "$G" reference --scene cornell --size 16x12 --spp 4 --quiet "$@" 2>&1; }
out=$(set_ref --component ao,direct,indirect:8 --cache "$D/scache")
check "a set renders each component into the cache" "indirect 16x12: rendered into cache" "$out"
out=$(set_ref --component indirect:8 --cache "$D/scache")
check "... where a single request finds it" "from cache" "$out"
set_ref --component ao,indirect:8 --out "$D/set.exr" > /dev/null
set_ref --component indirect:8 --out "$D/one.exr" > /dev/null
out=$("$G" compare "$D/one.exr" "$D/set.indirect.exr" --json 2>&1)
check "a set's --out file is its component's render alone" '"rmse": 0,' "$out"
out=$(set_ref --component ao,ao --out "$D/twice.exr")
check "a component named twice is refused" "twice" "$out"
exit $fail
