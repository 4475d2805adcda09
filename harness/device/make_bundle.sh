#!/bin/sh
# Builds the self-contained bundle (`make bundle`): gibench for any x86-64 Linux machine with a GL
# driver (EGL through glvnd) and none of our Debian libraries, e.g. a bare machine with an NVIDIA GPU
# (harness/device/run_on_nvidia.sh runs it there).
#
#   harness/device/make_bundle.sh [BUILD_DIR]     (default build-bundle)
#
# Release, without OpenImageIO (GIB_OIIO=OFF: libstb reads the textures) and without -march=native
# (GIB_NATIVE=OFF: the target CPU is another one). BUILD_DIR/gibench-bundle.tar.xz holds
#   gibench-bundle/bin/gibench      stripped
#   gibench-bundle/schema.json      the results schema the scripts read (GIBENCH_SCHEMA)
#   gibench-bundle/lib/             the binary's ldd closure, less what the target machine has:
#                                   glibc, libstdc++ and libgcc_s (newer there), and glvnd's
#                                   vendor-neutral GL/EGL libraries (the driver's own come with them)
#   gibench-bundle/REVISION         the source revision built
# Built on Debian 12, it needs glibc 2.34 and the libstdc++ of GCC 11 or newer on the target.
# libOSMesa is not in it (gibench opens it at run time when there; a GPU machine uses EGL). Then it
# checks, unpacked into a temporary folder, that nothing but the excluded libraries resolves from
# the system, and prints the bundle's size.
set -eu
root=$(cd "$(dirname "$0")/../.." && pwd)
build=${1:-build-bundle}
case $build in /*) ;; *) build=$root/$build ;; esac
jobs=${JOBS:-$(nproc 2>/dev/null || echo 2)}

rev=$(git -C "$root" rev-parse --short=12 HEAD 2>/dev/null || echo unknown)
if [ "$rev" != unknown ] && [ -n "$(git -C "$root" status --porcelain --untracked-files=no -- . ':(exclude)results' 2>/dev/null)" ]; then
    rev=$rev-dirty
fi
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DGIB_OIIO=OFF -DGIB_NATIVE=OFF \
    -DGIB_REVISION="$rev" ${CMAKE_ARGS:-}
cmake --build "$build" -j"$jobs" --target gibench

# What the target machine provides: glibc's libraries and loader, the C++ and GCC runtimes, and the
# vendor-neutral GL libraries of glvnd (libEGL, libGL, libGLX, libGLdispatch, libOpenGL, libGLES*).
excluded='^(libc|libm|libpthread|libdl|librt|libresolv|ld-linux-x86-64|libstdc\+\+|libgcc_s|libEGL|libGL|libGLX|libGLdispatch|libOpenGL|libGLESv1_CM|libGLESv2)\.so'

stage=$build/bundle
rm -rf "$stage" && mkdir -p "$stage/gibench-bundle/bin" "$stage/gibench-bundle/lib"
b=$stage/gibench-bundle
cp "$build/gibench" "$b/bin/gibench"
strip --strip-unneeded "$b/bin/gibench"
cp "$build/schema.json" "$b/schema.json"
echo "$rev" >"$b/REVISION"
# ldd prints "libfoo.so.1 => /path/libfoo.so.1 (0x...)" for each library of the closure.
ldd "$build/gibench" | awk '$2 == "=>" && $3 ~ /^\// { print $1, $3 }' | while read -r name path; do
    if echo "$name" | grep -Eq "$excluded"; then continue; fi
    cp -L "$path" "$b/lib/$name"
    strip --strip-unneeded "$b/lib/$name" 2>/dev/null || true
done
out=$build/gibench-bundle.tar.xz
XZ_OPT="-9 -T$jobs" tar -C "$stage" --owner=0 --group=0 -cJf "$out" gibench-bundle

# The check: unpacked afresh, with only its lib/ on the library path, every library the binary
# needs resolves into lib/ except the excluded ones.
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
tar -C "$tmp" -xJf "$out"
u=$tmp/gibench-bundle
bad=$(env -i LD_LIBRARY_PATH="$u/lib" ldd "$u/bin/gibench" | awk '$2 == "=>" { print $1, $3 }' |
      while read -r name path; do
          case $path in "$u"/lib/*) continue ;; esac
          echo "$name" | grep -Eq "$excluded" || echo "  $name => $path"
      done)
if [ -n "$bad" ]; then
    echo "make_bundle: libraries that resolve outside the bundle:" >&2
    echo "$bad" >&2
    exit 1
fi
echo "make_bundle: from the system only:" \
    $(env -i LD_LIBRARY_PATH="$u/lib" ldd "$u/bin/gibench" | awk '$2 == "=>" && $3 !~ /gibench-bundle/ { print $1 }')
echo "make_bundle: $out ($(du -k "$out" | cut -f1) KiB; $(ls "$u/lib" | wc -l) libraries, $(du -sk "$u" | cut -f1) KiB unpacked), revision $rev"
