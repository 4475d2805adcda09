#!/bin/sh
# A reference written with --out reads back as rendered (harness/imaging/exr.c, the comment above
# gib_exr_write): in gibench's reader and in OpenImageIO every sample is finite, and the mean of
# the samples read back is the mean the renderer printed and put in the header.
# The requests are ones whose files once read back with a corrupt 16-line ZIP chunk (NaNs, values
# near 3.4e38): the first was reported; the others tie here (their zlib stream exactly as long as
# the chunk's pixels) with this machine's pixels and zlib. Whether a given render ties depends on
# its exact pixels and on zlib: tests/imaging/test_exr_roundtrip.c builds such chunks on purpose.
# Usage: ref_exr_readback.sh GIBENCH EXR_STATS WORKDIR.
set -u
G="$1"
S="$2"
D="$3/ref_exr_readback"
rm -rf "$D"
mkdir -p "$D"
fail=0

# near A B TOL: |A - B| <= TOL * |B|
near() { awk -v a="$1" -v b="$2" -v t="$3" 'BEGIN { d = a - b; if (d < 0) d = -d;
    m = b < 0 ? -b : b; exit !(d <= t * m) }'; }
# field LINE-PREFIX KEY STATS: the value of KEY= on the line of STATS starting with LINE-PREFIX
field() { printf '%s\n' "$3" | sed -n "s/^$1 .*$2=\([^ ]*\).*/\1/p"; }

check_request() { # check_request ARGS...: renders the request to $D/x.exr and checks it
    rm -f "$D/x.exr"
    out=$("$G" reference --scene hard_far --component indirect "$@" --out "$D/x.exr" 2>&1)
    printed=$(printf '%s\n' "$out" | sed -n 's/.*, mean \([^,]*\),.*/\1/p')
    stats=$("$S" "$D/x.exr" 2>&1)
    header=$(field header mean "$stats")
    what="$*"
    if [ -z "$printed" ] || [ -z "$header" ] || [ "$header" = none ]; then
        echo "FAIL: $what: no mean printed or in the header: $out / $stats"
        fail=1
        return
    fi
    # the header holds the printed mean to more digits
    if near "$header" "$printed" 1e-5; then echo "ok: $what: header mean $header"; else
        echo "FAIL: $what: header mean $header, printed $printed"; fail=1; fi
    for reader in gib oiio; do
        nf=$(field $reader nonfinite "$stats")
        mean=$(field $reader mean "$stats")
        maxabs=$(field $reader maxabs "$stats")
        # float pixels against the renderer's double mean: equal to ~1e-7; a corrupt chunk moves
        # the mean by orders of magnitude
        if [ "$nf" = 0 ] && near "$mean" "$header" 1e-6; then
            echo "ok: $what: $reader reads finite samples, mean $mean, max |value| $maxabs"
        else
            echo "FAIL: $what: $reader reads $nf non-finite samples, mean $mean (rendered" \
                 "$header), max |value| $maxabs"
            fail=1
        fi
    done
}

check_request --spp 256 --seed 1 --size 64x64
check_request --spp 64 --seed 8 --size 64x64
check_request --spp 64 --seed 9 --size 48x48
exit $fail
