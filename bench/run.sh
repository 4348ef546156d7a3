#!/usr/bin/env bash
# Reruns the benchmarks whose figures the README quotes and writes their output to bench/results/.
#   bash bench/run.sh [encode|decode|quality|broadcast|compare ...]   (default: encode decode quality)
# Speed figures are only meaningful on an otherwise idle machine: check `uptime` first.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${ELLICAST_BUILD_DIR:-$root/build}
samples=${ELLICAST_SAMPLES:-$root/../shared/samples}
results="$root/bench/results"
bash "$root/scripts/setup.sh" >/dev/null
mkdir -p "$results"
[ $# -gt 0 ] || set -- encode decode quality
[ -d "$samples" ] || { echo "bench: $samples is absent (the benchmarks use the shared sample models)" >&2; exit 2; }
timed() { /usr/bin/time -f "wall %e s, user %U s, peak memory %M KB" "$@"; }

for what in "$@"; do
  case "$what" in
    encode)
      echo "== encode (bench_encode: bunny, 50k-vertex torus with 400 ellipsoids, every sample)" >&2
      timed "$build/bench/bench_encode" --samples "$samples" 2>&1 | tee "$results/encode.txt" ;;
    decode)
      echo "== decode speed (bench_decode: 400 ellipsoids, 50k and 100k points)" >&2
      timed "$build/bench/bench_decode" 2>&1 | tee "$results/decode.txt" ;;
    quality)
      echo "== decode quality: every packet, ellipsoids only, half of the point packets lost (3 seeds)" >&2
      tmp=$(mktemp -d)
      : > "$results/quality.txt"
      for m in spot.obj fandisk.obj woody.obj bunny.ply; do
        "$build/ellicast" encode -q "$samples/meshes/$m" -o "$tmp/${m%.*}.ellc"
        "$build/bench/bench_decode" "$tmp/${m%.*}.ellc" "$samples/meshes/$m" 3 2>&1 | tee -a "$results/quality.txt"
      done
      rm -rf "$tmp" ;;
    broadcast)
      echo "== broadcast on loopback (bench_broadcast, bunny, 2 Mbit/s)" >&2
      "$build/bench/bench_broadcast" "$samples/meshes/bunny.ply" --trials 20 --loss 0,0.05,0.1,0.2,0.3,0.5,0.7 --out "$results/broadcast" 2>&1 |
        tee "$results/broadcast/broadcast.txt" ;;
    compare)
      echo "== ellicast against Draco baselines (bunny and spot, 20 trials per setting)" >&2
      "$build/ellicast" compare "$samples/meshes/bunny.ply" --times 0.25,0.5,1,2 --time-loss 0.1,0.5 --samples 50000 \
        -o "$results/bunny"
      "$build/ellicast" compare "$samples/meshes/spot.obj" --burst 0,8 -o "$results/spot" ;;
    *) echo "bench: unknown benchmark '$what' (encode, decode, quality, broadcast, compare)" >&2; exit 2 ;;
  esac
done
