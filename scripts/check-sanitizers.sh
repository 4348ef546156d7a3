#!/usr/bin/env bash
# Sanitizers and fuzzing for the format layer (the code that reads untrusted bytes):
#   1. builds the format tests with AddressSanitizer + UndefinedBehaviorSanitizer (-DELLICAST_SANITIZE=ON)
#      in build-asan/ and runs them (ellicast_format_tests: test_format, test_container, test_conformance);
#      ELLICAST_SANITIZE_FULL=1 builds and runs the whole suite under the sanitizers instead (slow: the
#      codec, converters and tinygltf are rebuilt instrumented);
#   2. builds the libFuzzer targets with clang in build-fuzz/ and runs each for ELLICAST_FUZZ_SECONDS
#      (default 60) seconds, seeded from spec/vectors. A crash leaves its input in build-fuzz/crashes/.
# Usage: bash scripts/check-sanitizers.sh        (from anywhere; exits non-zero on any finding)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
jobs=${ELLICAST_JOBS:-$(nproc)}
fuzz_seconds=${ELLICAST_FUZZ_SECONDS:-60}
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1:strict_string_checks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$root/scripts/lsan.supp:print_suppressions=0}
t0=$(date +%s)

echo "== sanitizers: ASan + UBSan build in build-asan/" >&2
cmake -S "$root" -B "$root/build-asan" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DELLICAST_SANITIZE=ON "${launcher[@]}" >/dev/null
if [ "${ELLICAST_SANITIZE_FULL:-0}" = 1 ]; then
  cmake --build "$root/build-asan" -j "$jobs"
  t1=$(date +%s)
  (cd "$root/build-asan" && ctest --output-on-failure -j "$jobs" --timeout 1800)
else
  cmake --build "$root/build-asan" -j "$jobs" --target ellicast_format_tests
  t1=$(date +%s)
  (cd "$root/build-asan" && ./tests/ellicast_format_tests)
fi
t2=$(date +%s)
echo "== sanitizers: build $((t1 - t0)) s, tests $((t2 - t1)) s" >&2

if ! command -v clang++ >/dev/null; then
  echo "== fuzzing: skipped, clang++ is not installed (apt-get install clang)" >&2
  exit 0
fi
echo "== fuzzing: libFuzzer targets in build-fuzz/, ${fuzz_seconds} s each" >&2
cmake -S "$root" -B "$root/build-fuzz" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DELLICAST_FUZZ=ON -DELLICAST_FORMAT_ONLY=ON \
  -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_C_COMPILER=clang "${launcher[@]}" >/dev/null
cmake --build "$root/build-fuzz" -j "$jobs" --target fuzz_packet fuzz_container
t3=$(date +%s)

# Seeds: the conformance vectors; the packet target takes a mode byte (1: reseal checksums) and the
# packets without the container header.
corpus="$root/build-fuzz/corpus"
mkdir -p "$corpus/container" "$corpus/packet" "$root/build-fuzz/crashes"
for f in "$root"/spec/vectors/*/*.ellc; do
  name="$(basename "$(dirname "$f")")_$(basename "$f" .ellc)"
  cp "$f" "$corpus/container/$name"
  { printf '\001'; tail -c +13 "$f"; } > "$corpus/packet/$name"
done
for target in packet container; do
  echo "== fuzzing: fuzz_$target" >&2
  log="$root/build-fuzz/fuzz_$target.log"
  status=0
  "$root/build-fuzz/fuzz/fuzz_$target" -max_total_time="$fuzz_seconds" -rss_limit_mb=2048 -max_len=70000 \
    -print_final_stats=1 -artifact_prefix="$root/build-fuzz/crashes/$target-" "$corpus/$target" > "$log" 2>&1 || status=$?
  grep -E "^(stat::number_of_executed_runs|stat::peak_rss_mb|Done |SUMMARY)" "$log" >&2 || true
  if [ "$status" -ne 0 ]; then
    tail -40 "$log" >&2
    echo "== fuzzing: fuzz_$target found a problem (exit $status); the input is in build-fuzz/crashes/" >&2
    exit 1
  fi
done
t4=$(date +%s)
echo "== sanitizers and fuzzing passed: fuzz build $((t3 - t2)) s, fuzzing $((t4 - t3)) s, total $((t4 - t0)) s" >&2
