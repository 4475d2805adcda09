#!/bin/sh
# The reference cache through the CLI (harness/app/refcache.c, cmd_reference.c): a first request
# renders into the cache, a second one reads it, --force renders again, and an entry that is
# truncated or whose header belongs to another request is detected and rendered again, never used.
# Also: --out beside --cache writes the same pixels (gibench compare: RMSE exactly 0), and two
# plain --out renders of the same request have identical pixels.
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
ref() { "$G" reference --scene cornell --component ao --spp 4 --size 16x12 --quiet "$@" 2>&1; }

out=$(ref --cache "$D/cache")
check "first request renders" "rendered into cache" "$out"
entry=$(ls "$D"/cache/*.exr)
out=$(ref --cache "$D/cache")
check "second request reads the cache" "from cache" "$out"
out=$(ref --cache "$D/cache" --force)
check "--force renders again" "rendered into cache" "$out"

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
exit $fail
