#!/usr/bin/env bash
# Sanitizers and fuzzing for the format layer (the code that reads untrusted bytes):
#   1. builds the format tests with AddressSanitizer + UndefinedBehaviorSanitizer (-DELLICAST_SANITIZE=ON)
#      in build-asan/ and runs them (ellicast_format_tests: test_format, test_container, test_conformance);
#      ELLICAST_SANITIZE_FULL=1 builds and runs the whole suite under the sanitizers instead (slow: the
#      codec, converters and tinygltf are rebuilt instrumented);
#   2. builds the libFuzzer targets with clang in build-fuzz/ and runs each for ELLICAST_FUZZ_SECONDS
#      (default 60) seconds, seeded from spec/vectors. A crash leaves its input in build-fuzz/crashes/;
#   3. builds every library instrumented with clang in build-fuzz-pipeline/ and runs fuzz_decode (received
#      packets through the decoder and the glTF writer) and fuzz_readers (glTF/GLB, OBJ, PLY, OFF, STL)
#      for as long, seeded from spec/vectors and ../shared/samples (ELLICAST_FUZZ_PIPELINE=0 skips it),
#      with short inputs (-max_len 1024 and 4096) and -entropic_scale_per_exec_time=1 (slow inputs are
#      mutated less often) so that each runs thousands of inputs a second, not tens (see the targets).
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
fuzz_targets=(packet container)
pkg-config --exists libsodium && fuzz_targets+=(reception)  # the receiver's candidates need the auth library
cmake --build "$root/build-fuzz" -j "$jobs" --target "${fuzz_targets[@]/#/fuzz_}"
t3=$(date +%s)

# Seeds: the conformance vectors; the packet target takes a mode byte (1: reseal checksums) and the
# packets without the container header.
corpus="$root/build-fuzz/corpus"
mkdir -p "$corpus/container" "$corpus/packet" "$corpus/reception" "$root/build-fuzz/crashes"
for f in "$root"/spec/vectors/*/*.ellc; do
  name="$(basename "$(dirname "$f")")_$(basename "$f" .ellc)"
  cp "$f" "$corpus/container/$name"
  { printf '\001'; tail -c +13 "$f"; } > "$corpus/packet/$name"
  # The reception target: resealed, several senders (mode bit 2), four candidate places (bits 3-4).
  { printf '\035'; tail -c +13 "$f"; } > "$corpus/reception/$name"
done
# Runs one fuzz target for fuzz_seconds on its corpus; exits on a finding. A fixed seed (-seed=1)
# makes a run repeatable: a longer local run with the same seed, binary and corpus covers what CI's
# shorter one does.
run_target() {  # build dir, target, corpus dir, extra libFuzzer options...
  local build=$1 target=$2 dir=$3
  shift 3
  echo "== fuzzing: fuzz_$target" >&2
  local log="$build/fuzz_$target.log" status=0
  mkdir -p "$build/crashes"
  "$build/$(cd "$build" && find . -name "fuzz_$target" -type f -perm -u+x | head -1)" -max_total_time="$fuzz_seconds" \
    -seed=1 -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix="$build/crashes/$target-" "$@" "$dir" > "$log" 2>&1 || status=$?
  grep -E "^(stat::number_of_executed_runs|stat::peak_rss_mb|Done |SUMMARY)" "$log" >&2 || true
  if [ "$status" -ne 0 ]; then
    tail -40 "$log" >&2
    echo "== fuzzing: fuzz_$target found a problem (exit $status); the input is in $build/crashes/" >&2
    exit 1
  fi
}
for target in "${fuzz_targets[@]}"; do
  run_target "$root/build-fuzz" "$target" "$corpus/$target" -max_len=70000
done
t4=$(date +%s)
echo "== fuzzing the format layer: fuzz build $((t3 - t2)) s, fuzzing $((t4 - t3)) s" >&2

# The decoder with the glTF writer, and the input readers: every library instrumented, in
# build-fuzz-pipeline/ (ELLICAST_FUZZ_PIPELINE=0 skips this stage).
if [ "${ELLICAST_FUZZ_PIPELINE:-1}" = 1 ]; then
  pipeline="$root/build-fuzz-pipeline"
  cmake -S "$root" -B "$pipeline" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DELLICAST_FUZZ_PIPELINE=ON \
    -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_C_COMPILER=clang "${launcher[@]}" >/dev/null
  cmake --build "$pipeline" -j "$jobs" --target fuzz_decode fuzz_readers
  t5=$(date +%s)
  mkdir -p "$pipeline/corpus/decode" "$pipeline/corpus/readers"
  cp "$corpus/packet/"* "$pipeline/corpus/decode/"
  decode_max_len=1024
  # Seeds that fit fuzz_decode's -max_len: from each vector at least that long, its first STREAM_INFO,
  # ELLIPSOIDS and POINTS packets followed by as many of its other packets (scene, materials, textures,
  # manifests, repair, more points) as fit, for each run of them, so that short inputs reach them too.
  for f in "$root"/spec/vectors/*/*.ellc; do
    size=$(wc -c < "$f")
    [ "$size" -ge "$decode_max_len" ] || continue
    name="$(basename "$(dirname "$f")")_$(basename "$f" .ellc)"
    core=() rest=() used=1 off=12 seen=""
    while [ $((off + 24)) -le "$size" ]; do  # packets: type at offset 6, payload length at 18 (u16 LE)
      read -r type lo hi < <(od -An -tu1 -j $((off + 6)) -N 14 "$f" | tr -s ' \n' '  ' | awk '{print $1, $13, $14}')
      len=$((24 + lo + 256 * hi))
      [ $((off + len)) -le "$size" ] || len=$((size - off))
      if [ "$type" -ge 1 ] && [ "$type" -le 3 ] && [[ $seen != *"<$type>"* ]] && [ $((used + len)) -le "$decode_max_len" ]; then
        core+=("$off:$len") used=$((used + len)) seen+="<$type>"
      else
        rest+=("$off:$len")
      fi
      off=$((off + len))
    done
    n=0 i=0
    while [ "$i" -lt "${#rest[@]}" ]; do
      seed=("${core[@]}") len=$used
      while [ "$i" -lt "${#rest[@]}" ] && [ $((len + ${rest[i]#*:})) -le "$decode_max_len" ]; do
        seed+=("${rest[i]}") len=$((len + ${rest[i]#*:})) i=$((i + 1))
      done
      if [ "${#seed[@]}" -eq "${#core[@]}" ]; then i=$((i + 1)); continue; fi  # a packet too long for any seed
      { printf '\001'; for p in "${seed[@]}"; do dd if="$f" iflag=skip_bytes,count_bytes skip="${p%%:*}" count="${p#*:}" status=none; done; } \
        > "$pipeline/corpus/decode/${name}_part$n"
      n=$((n + 1))
    done
  done
  # Reader seeds: small sample files, the type byte first (0 glb, 1 gltf, 2 obj, 3 ply, 4 off, 5 stl).
  samples="$root/../shared/samples"
  [ -d "$samples" ] || samples="$root/samples"
  n=0
  while IFS= read -r f; do
    case "${f,,}" in
      *.glb) t='\000' ;; *.gltf) t='\001' ;; *.obj) t='\002' ;; *.ply) t='\003' ;; *.off) t='\004' ;; *.stl) t='\005' ;;
      *) continue ;;
    esac
    { printf "$t"; cat "$f"; } > "$pipeline/corpus/readers/seed$n"
    n=$((n + 1))
  done < <(find "$samples" -type f -size -200k \( -iname '*.glb' -o -iname '*.gltf' -o -iname '*.obj' -o -iname '*.ply' -o -iname '*.off' -o -iname '*.stl' \) 2>/dev/null | sort)
  printf '\003ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n' > "$pipeline/corpus/readers/triangle"
  # The samples hold no OFF nor STL file: one triangle each (STL in ASCII and binary).
  printf '\004OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n' > "$pipeline/corpus/readers/off_triangle"
  printf '\005solid t\nfacet normal 0 0 1\n outer loop\n  vertex 0 0 0\n  vertex 1 0 0\n  vertex 0 1 0\n endloop\nendfacet\nendsolid t\n' \
    > "$pipeline/corpus/readers/stl_ascii"
  { printf '\005binary stl%70s\001\000\000\000' ''; printf '\000\000\000\000\000\000\000\000\000\000\200\077'
    printf '\000%.0s' {1..12}; printf '\000\000\200\077\000\000\000\000\000\000\000\000'
    printf '\000\000\000\000\000\000\200\077\000\000\000\000\000\000'; } > "$pipeline/corpus/readers/stl_binary"
  run_target "$pipeline" decode "$pipeline/corpus/decode" -max_len="$decode_max_len" -entropic_scale_per_exec_time=1
  run_target "$pipeline" readers "$pipeline/corpus/readers" -max_len=4096 -timeout=30 -entropic_scale_per_exec_time=1
  t6=$(date +%s)
  echo "== fuzzing the decoder and readers: build $((t5 - t4)) s, fuzzing $((t6 - t5)) s" >&2
fi
echo "== sanitizers and fuzzing passed in $(($(date +%s) - t0)) s" >&2
