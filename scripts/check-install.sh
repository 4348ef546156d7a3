#!/usr/bin/env bash
# The library as an integrator gets it: installs build/ into a temporary prefix, checks what is there
# (headers, libellicast.so with its SONAME exporting only ellicast_* symbols, static C++ libraries, the
# CMake package, the pkg-config file), builds examples/ against the installed package only (the C
# receiver through pkg-config, then the CMake consumer project through find_package), and runs the
# receiver against `ellicast serve` on loopback: it must write a GLB the Khronos glTF-Validator accepts.
# Usage: bash scripts/check-install.sh   (after scripts/setup.sh; ELLICAST_BUILD_DIR as there)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${ELLICAST_BUILD_DIR:-$root/build}
work=$(mktemp -d "${TMPDIR:-/tmp}/ellicast-install.XXXXXX")
serve_pid=""
cleanup() {
  [ -n "$serve_pid" ] && kill "$serve_pid" 2>/dev/null || true
  rm -rf "$work"
}
trap cleanup EXIT
prefix="$work/prefix"
failures=0
check() {  # check DESCRIPTION COMMAND...: one line a check
  local what=$1
  shift
  if "$@" >"$work/check.log" 2>&1; then
    echo "ok: $what"
  else
    echo "FAILED: $what" >&2
    sed 's/^/  | /' "$work/check.log" >&2
    failures=$((failures + 1))
  fi
}

[ -x "$build/ellicast" ] && [ -d "$build/CMakeFiles" ] || { echo "check-install: no build in $build (run scripts/setup.sh)" >&2; exit 2; }
echo "== install into $prefix" >&2
cmake --install "$build" --prefix "$prefix" >/dev/null
pc_file=$(find "$prefix" -path '*/pkgconfig/ellicast.pc' | head -n 1)
[ -n "$pc_file" ] || { echo "check-install: no pkgconfig/ellicast.pc was installed under $prefix" >&2; exit 1; }
libdir=$(dirname "$(dirname "$pc_file")")  # PREFIX/lib, or PREFIX/lib/<multiarch> for a prefix of /usr

check "the C API header" test -f "$prefix/include/ellicast.h"
check "the C++ headers (format umbrella, codec, converters, broadcast, auth)" \
  test -f "$prefix/include/ellicast/format.h" -a -f "$prefix/include/ellicast/codec/decoder.h" \
       -a -f "$prefix/include/ellicast/converters/asset.h" -a -f "$prefix/include/ellicast/broadcast/reception.h" \
       -a -f "$prefix/include/ellicast/auth.h"
check "libellicast.so.1 is the SONAME" sh -c "objdump -p '$libdir/libellicast.so' | grep -q 'SONAME *libellicast.so.1\$'"
check "libellicast.so exports only ellicast_* functions" \
  sh -c "! nm -D --defined-only '$libdir/libellicast.so' | awk '\$2 ~ /[TDBRW]/ {print \$3}' | grep -v '^ellicast_' | grep -v '^_init\$\|^_fini\$\|^_edata\$\|^_end\$\|^__bss_start\$'"
check "the static C++ libraries" test -f "$libdir/libellicast_format.a" -a -f "$libdir/libellicast_codec.a" -a -f "$libdir/libellicast_converters.a"
check "the CMake package" test -f "$libdir/cmake/ellicast/ellicastConfig.cmake" -a -f "$libdir/cmake/ellicast/ellicastConfigVersion.cmake"
check "pkg-config knows ellicast 1.0.0 at the prefix" \
  sh -c "[ \"\$(PKG_CONFIG_PATH='$libdir/pkgconfig' pkg-config --modversion ellicast)\" = 1.0.0 ] && \
         PKG_CONFIG_PATH='$libdir/pkgconfig' pkg-config --cflags ellicast | grep -q -- '-I$prefix/include'"
check "ellicast.h compiles as C99 with -Wall -Wextra -Wpedantic -Werror" \
  sh -c "echo '#include <ellicast.h>' | cc -std=c99 -Wall -Wextra -Wpedantic -Werror -fsyntax-only -I'$prefix/include' -x c -"

echo "== build the examples against the installed package only" >&2
cp -r "$root/examples" "$work/examples"
check "examples/receive_udp with make and pkg-config" make -C "$work/examples/receive_udp" PKG_CONFIG_PATH="$libdir/pkgconfig"
check "examples/cmake_consumer with find_package(ellicast CONFIG)" sh -c "
  cmake -S '$work/examples/cmake_consumer' -B '$work/consumer' -DCMAKE_PREFIX_PATH='$prefix' -DCMAKE_BUILD_TYPE=Release &&
  cmake --build '$work/consumer' -j '$(nproc)'"

echo "== a broadcast on loopback: ellicast serve -> examples/receive_udp -> GLB" >&2
"$build/ellicast" encode "$root/samples/trefoil.obj" -o "$work/trefoil.ellc" -q >/dev/null
check "count_packets (ellicast::format) reads the stream" sh -c "'$work/consumer/count_packets' '$work/trefoil.ellc' | grep -q 'STREAM_INFO'"
check "decode_glb (ellicast::converters, static) decodes it exactly" sh -c "'$work/consumer/decode_glb' '$work/trefoil.ellc' '$work/decoded.glb' | grep -q '1 objects, 1 exact'"
port=$((20000 + RANDOM % 20000))
receiver="$work/examples/receive_udp/receive_udp"
if [ -x "$receiver" ]; then
  "$receiver" 127.0.0.1 "$port" "$work/received.glb" 1 60 2>"$work/receive.log" &
  receive_pid=$!
  sleep 0.5
  # Enough cycles that a datagram lost on a loaded machine comes round again; stopped once received.
  "$build/ellicast" serve "$work/trefoil.ellc" --to "127.0.0.1:$port" --rate 8000000 --cycles 40 -q >"$work/serve.log" 2>&1 &
  serve_pid=$!
  receive_status=0
  wait "$receive_pid" || receive_status=$?
  kill "$serve_pid" 2>/dev/null || true
  wait "$serve_pid" 2>/dev/null || true
  serve_pid=""
  tr '\r' '\n' <"$work/receive.log" | tail -n 3 >&2
  check "the receiver ends complete and writes a GLB" sh -c "[ $receive_status = 0 ] && grep -q complete '$work/receive.log' && [ -s '$work/received.glb' ]"
  node_modules="$root/.cache/node/node_modules"
  if [ -d "$node_modules/gltf-validator" ] && command -v node >/dev/null; then
    check "the received GLB is valid glTF (Khronos glTF-Validator)" \
      sh -c "NODE_PATH='$node_modules' node '$root/tests/gltf_validate.js' '$work/received.glb' | tee /dev/stderr | grep -q '\"numErrors\":0'"
  else
    echo "skipped: the glTF-Validator is not installed (run scripts/setup.sh)" >&2
  fi
  rms=$("$build/ellicast" diff "$root/samples/trefoil.obj" "$work/received.glb" | awk '/^A -> B/' | grep -o '[0-9.]*%' | sed -n 3p | tr -d %)
  check "the received model is the original (RMS ${rms:-?}% of the diagonal, under 0.01%: the exact layer)" \
    awk -v rms="${rms:-100}" 'BEGIN {exit !(rms < 0.01)}'
else
  echo "FAILED: no receiver was built" >&2
  failures=$((failures + 1))
fi

if [ "$failures" -gt 0 ]; then
  echo "check-install: $failures check(s) failed" >&2
  exit 1
fi
echo "check-install: every check passed" >&2
