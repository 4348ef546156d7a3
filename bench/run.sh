#!/usr/bin/env bash
# Reruns the benchmarks whose figures the README quotes and writes their output to bench/results/.
#   bash bench/run.sh [amplification|encode|decode|quality|gallery|first-picture|full-quality|broadcast|compare|corpus|point-share|speed|live|region ...]   (default: encode decode quality)
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
    amplification)
      # Hostile recordings (bench_hostile) and an honest one, through every command that reads a
      # recording: seconds and peak resident memory against the input's bytes (issue 29).
      echo "== amplification: hostile recordings through validate, inspect, decode, and as datagrams through receive" >&2
      tmp=$(mktemp -d)
      "$build/bench/bench_hostile" "$tmp"
      "$build/ellicast" encode -q "$samples/meshes/bunny.ply" -o "$tmp/honest-bunny.ellc" > /dev/null
      out="$results/amplification.md"
      {
        echo "# Amplification: input bytes against seconds and memory"
        echo
        echo "Made by \`bash bench/run.sh amplification\` ($(date -u +%Y-%m-%d), $(nproc) cores). Peak resident"
        echo "memory of the whole process (\`/usr/bin/time\`), every command with a 120 s timeout. The receiver's"
        echo "byte budget is 64 MiB plus 8 times the bytes taken (spec 11.2). \`receive\` gets the recording's packets as"
        echo "UDP datagrams on 127.0.0.1 (about 19 MB/s) and writes what it took as a stream file (no reconstruction);"
        echo "its seconds are the time it listened (until complete, or a deadline after the last datagram)."
        echo
        echo "| input | bytes | command | exit | seconds | peak MB | within 64 MB + 8x |"
        echo "|---|---:|---|---:|---:|---:|---|"
      } > "$out"
      for f in "$tmp"/*.ellc; do
        size=$(stat -c %s "$f")
        for cmd in validate inspect decode receive; do
          args=("$f"); [ "$cmd" = decode ] && args=("$f" -o "$tmp/out.glb" -q)
          set +e
          if [ "$cmd" = receive ]; then
            port=$((47000 + RANDOM % 2000))
            until_s=$((3 + size / 8000000))
            /usr/bin/time -f "%e %M" -o "$tmp/time.txt" timeout 120 "$build/ellicast" receive --from "127.0.0.1:$port" \
              -o "$tmp/rx.ellc" --until "$until_s" -q > /dev/null 2> "$tmp/err.txt" &
            rx=$!
            sleep 0.5
            python3 "$root/bench/send_datagrams.py" "$f" "127.0.0.1:$port"
            wait $rx
            code=$?
          else
            /usr/bin/time -f "%e %M" -o "$tmp/time.txt" timeout 120 "$build/ellicast" "$cmd" "${args[@]}" > /dev/null 2> "$tmp/err.txt"
            code=$?
          fi
          set -e
          read -r secs kb < <(tail -1 "$tmp/time.txt")
          python3 - "$f" "$size" "$cmd" "$code" "$secs" "$kb" >> "$out" <<'PY'
import os, sys
f, size, cmd, code, secs, kb = sys.argv[1:]
mb = int(kb) / 1024
within = mb <= 64 + 8 * int(size) / 1048576
print(f"| {os.path.basename(f)} | {int(size):,} | {cmd} | {code} | {float(secs):.2f} | {mb:.1f} | {'yes' if within else 'no'} |")
PY
          echo "$(basename "$f") $cmd: exit $code, $secs s, $kb KB" >&2
        done
      done
      rm -rf "$tmp"
      cat "$out" ;;
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
    gallery)
      # Pictures of the reconstructions: original | ellipsoids only | after a quarter of the points |
      # every packet | what one carousel cycle through a 50%-loss channel delivers.
      echo "== gallery: reconstructions as pictures (bench/results/gallery/*.png)" >&2
      tmp=$(mktemp -d)
      mkdir -p "$results/gallery"
      : > "$results/gallery/README.md"
      echo "# Reconstructions" >> "$results/gallery/README.md"
      echo >> "$results/gallery/README.md"
      echo "Made by \`bash bench/run.sh gallery\`. Panels, left to right: the original; the base from the ellipsoids" >> "$results/gallery/README.md"
      echo "alone; after the first quarter of the points; every packet; what a receiver holds after listening" >> "$results/gallery/README.md"
      echo "to one carousel cycle through a channel losing 50% of the packets (seed 1)." >> "$results/gallery/README.md"
      echo >> "$results/gallery/README.md"
      for spec in meshes/spot.obj:30:15 meshes/fandisk.obj:200:20 meshes/woody.obj:0:0 meshes/bunny.ply:20:10 \
                  gltf/Fox/Fox.gltf:60:15 gltf/Box-glb/Box.glb:35:25; do
        IFS=: read -r m az el <<< "$spec"
        n=$(basename "$m"); n=${n%.*}
        "$build/ellicast" encode -q "$samples/$m" -o "$tmp/$n.ellc" > /dev/null
        points=$("$build/ellicast" inspect --json "$tmp/$n.ellc" | python3 -c 'import json,sys; print(sum(o["point_count"] for o in json.load(sys.stdin)["objects"]))')
        quarter=$(( (points + 3) / 4 ))
        "$build/ellicast" decode -q "$tmp/$n.ellc" -o "$tmp/$n.full.ply" --snapshots "$quarter" > /dev/null
        "$build/ellicast" simulate "$tmp/$n.ellc" -o "$tmp/$n.lossy.ellc" --loss 0.5 --seed 1 > "$tmp/$n.sim.txt" 2>&1
        "$build/ellicast" decode -q "$tmp/$n.lossy.ellc" -o "$tmp/$n.lossy.ply" > /dev/null
        "$build/ellicast" render "$samples/$m" "$tmp/$n.full.snap-o0-p0000000.ply" "$(printf '%s/%s.full.snap-o0-p%07d.ply' "$tmp" "$n" "$quarter")" \
          "$tmp/$n.full.ply" "$tmp/$n.lossy.ply" -o "$results/gallery/$n.png" --width 360 --height 360 \
          --azimuth "$az" --elevation "$el" --frame-from "$samples/$m" > /dev/null
        received=$(grep -o 'points: [0-9,]* of [0-9,]*' "$tmp/$n.sim.txt" | head -1 | sed 's/points: //')
        lost=$(grep -o 'channel did: [0-9]* lost ([0-9.]*%)' "$tmp/$n.sim.txt" | sed 's/channel did: //')
        echo "- \`$n.png\`: $m, $points points; the lossy channel's cycle: $lost packets, $received points received." >> "$results/gallery/README.md"
        echo "  gallery: $n ($points points; 50% loss: $received)" >&2
      done
      rm -rf "$tmp" ;;
    first-picture)
      echo "== first picture: share of receivers holding a stream info and an ellipsoid packet (bench_first_picture)" >&2
      tmp=$(mktemp -d)
      : > "$results/first_picture.txt"
      # Signed streams (spec 16): the rows marked "key" are a receiver that checks the signatures.
      "$build/ellicast" keygen "$tmp/bench" > /dev/null
      for m in bunny.ply spot.obj; do
        "$build/ellicast" encode -q "$samples/meshes/$m" -o "$tmp/${m%.*}.ellc" --sign "$tmp/bench.key" > /dev/null
        for loss in 0.1 0.3 0.5 0.7; do
          "$build/bench/bench_first_picture" "$tmp/${m%.*}.ellc" --loss "$loss" --trials 20000 --key "$tmp/bench.pub" |
            tee -a "$results/first_picture.txt"
        done
      done
      rm -rf "$tmp" ;;
    full-quality)
      echo "== every point: cycles until a receiver holds every point, with and without repair packets (bench_full_quality)" >&2
      tmp=$(mktemp -d)
      out="$results/full_quality.txt"
      : > "$out"
      for m in bunny.ply spot.obj; do
        for ratio in 1 0; do
          "$build/ellicast" encode -q "$samples/meshes/$m" -o "$tmp/${m%.*}-repair$ratio.ellc" --repair "$ratio" > /dev/null
          "$build/bench/bench_full_quality" "$tmp/${m%.*}-repair$ratio.ellc" --loss 0.1,0.3,0.5,0.7 --trials 20 | tee -a "$out"
        done
      done
      # The price: fewer points early. RMS (% of the diagonal, the larger direction) of the decoded model
      # after 0.25, 0.5 and 1 cycle, 5 tune-ins each (ellicast simulate + decode + diff).
      echo "RMS after a time, bunny, 5 random tune-ins (ellicast simulate --tune-in-random; decode; diff):" | tee -a "$out"
      for loss in 0.1 0.5; do
        for cycles in 0.25 0.5 1; do
          for ratio in 1 0; do
            values=""
            for seed in 1 2 3 4 5; do
              "$build/ellicast" simulate "$tmp/bunny-repair$ratio.ellc" -o "$tmp/rx.ellc" --loss "$loss" --cycles "$cycles" \
                --seed "$seed" --tune-in-random > /dev/null 2>&1
              if "$build/ellicast" decode -q "$tmp/rx.ellc" -o "$tmp/rx.ply" > /dev/null 2>&1; then
                values="$values $("$build/ellicast" diff "$samples/meshes/bunny.ply" "$tmp/rx.ply" --samples 20000 2>/dev/null |
                  awk '/^A -> B|^B -> A/ {gsub(/[()%]/, ""); print $7}' | sort -g | tail -1)"
              else
                values="$values none"
              fi
            done
            echo "loss $loss, $cycles cycles, --repair $ratio:$values" | tee -a "$out"
          done
        done
      done
      rm -rf "$tmp" ;;
    broadcast)
      echo "== broadcast on loopback (bench_broadcast, bunny, 2 Mbit/s)" >&2
      "$build/bench/bench_broadcast" "$samples/meshes/bunny.ply" --trials 20 --loss 0,0.05,0.1,0.2,0.3,0.5,0.7 --out "$results/broadcast" 2>&1 |
        tee "$results/broadcast/broadcast.txt" ;;
    compare)
      echo "== ellicast against Draco baselines (bunny and spot; independent loss and bursts of 8 and 32 slots)" >&2
      rm -rf "$results/bunny" "$results/spot" && mkdir -p "$results/bunny" "$results/spot"
      "$build/ellicast" compare "$samples/meshes/bunny.ply" -o "$results/bunny" | tee "$results/bunny/stdout.txt"
      "$build/ellicast" compare "$samples/meshes/spot.obj" -o "$results/spot" | tee "$results/spot/stdout.txt" ;;
    corpus)
      # Real glTF assets through convert (issue 16): the shared samples, the small Khronos ones committed
      # in samples/khronos, the lightmapped box of samples/multiuv (TEXCOORD_1), and $ELLICAST_CORPUS when set
      # (e.g. a checkout of KhronosGroup/glTF-Sample-Assets/Models).
      echo "== corpus: glTF assets through ellicast convert and the Khronos validator (bench/corpus.py)" >&2
      folders=("$samples/gltf" "$root/samples/khronos" "$root/samples/multiuv")
      [ -n "${ELLICAST_CORPUS:-}" ] && folders+=("$ELLICAST_CORPUS")
      originals=("${folders[@]}")  # the bytes table below takes each asset once, not its variants
      # The Draco, quantized and meshopt files a user would make of some of them (glTF-Transform, from
      # npm like the validator), so that "written like the input" is measured on each encoding.
      variants="$results/corpus-variants"
      rm -rf "$variants" && mkdir -p "$variants"
      gt="$root/.cache/node/node_modules/.bin/gltf-transform"
      if [ -x "$gt" ]; then
        for a in "$samples/gltf/Duck/Duck.gltf" "$samples/gltf/CesiumMilkTruck/CesiumMilkTruck.gltf" \
                 "$samples/gltf/Fox/Fox.gltf" "$root/samples/multiuv/MultiUVBox.gltf" \
                 "$root/samples/khronos/RiggedFigure/RiggedFigure.gltf" \
                 "$root/samples/khronos/AnimatedMorphCube/AnimatedMorphCube.gltf"; do
          [ -f "$a" ] || continue
          n=$(basename "${a%.*}")
          for v in draco quantize meshopt; do
            node "$gt" "$v" "$a" "$variants/$n-$v.glb" > /dev/null 2>&1 || echo "gltf-transform $v failed on $a" >&2
          done
        done
        folders+=("$variants")
      else
        echo "(no Draco / quantized / meshopt variants: glTF-Transform is not installed under .cache/node)" >&2
      fi
      python3 "$root/bench/corpus.py" "$build/ellicast" "$root/.cache/node/node_modules" "$results/corpus" "${folders[@]}" > /dev/null
      rm -rf "$results/corpus/out" "$variants"
      cat "$results/corpus/corpus.md"
      # What the exact asset costs against Draco and gltfpack (issue 27): the same assets and the
      # shared meshes. gltfpack (npm, a WebAssembly build) is only needed here.
      node_bin="$root/.cache/node/node_modules/.bin"
      [ -x "$node_bin/gltfpack" ] || (cd "$root/.cache/node" && npm install --no-audit --no-fund --loglevel=error gltfpack@0.25.0 >/dev/null) ||
        echo "bench: gltfpack could not be installed; its column stays empty" >&2
      echo "== corpus bytes: ellicast content against Draco and gltfpack (bench/corpus_bytes.py)" >&2
      python3 "$root/bench/corpus_bytes.py" "$build/ellicast" "$node_bin" "$results/corpus" "$samples/meshes" "${originals[@]}" > /dev/null
      rm -rf "$results/corpus/work"
      cat "$results/corpus/bytes.md" ;;
    point-share)
      # Format 1.11 (spec 27, issue 27): the exact asset's bytes against Draco and the picture at 50%
      # loss as the exact layer carries more of the vertices (--point-share 1, 0.5, 0.25, 0).
      echo "== point share: carried vertices against Draco (bench/point_share.py)" >&2
      mkdir -p "$results/point_share"
      python3 "$root/bench/point_share.py" "$build/ellicast" "$root/.cache/node/node_modules/.bin" "$results/point_share" \
        "$samples/meshes/bunny.ply" "$samples/meshes/fandisk.obj" "$samples/meshes/spot.obj" "$samples/meshes/teapot.obj" \
        "$samples/meshes/suzanne.obj" "$root/samples/trefoil.obj" > /dev/null
      rm -rf "$results/point_share/work"
      cat "$results/point_share/point_share.md" ;;
    speed)
      # Issue 30: encode, exact decode and reconstruction side by side with Draco in one run, on the
      # bunny, a 50k-vertex closed torus and (ELLICAST_SPEED_LARGE=0 leaves it out) the same torus at
      # 500k vertices, and low-poly glTF assets (the Box, the Duck, the milk truck); best of
      # ELLICAST_SPEED_RUNS (default 3) wall times each. ELLICAST_SPEED_BASELINE=PATH adds the same
      # steps with another build (an earlier commit's tool) and says whether its bytes are the same.
      echo "== speed: ellicast against draco_encoder/draco_decoder (bench/speed.py)" >&2
      large=--large
      [ "${ELLICAST_SPEED_LARGE:-1}" = 0 ] && large=
      gltf=()
      lowpoly=""
      for g in "$samples/gltf/Box-glb/Box.glb" "$samples/gltf/Duck-glb/Duck.glb" "$samples/gltf/CesiumMilkTruck/CesiumMilkTruck.gltf"; do
        [ -f "$g" ] && lowpoly="${lowpoly:+$lowpoly,}$g"
      done
      [ -n "$lowpoly" ] && gltf=(--gltf "$lowpoly")
      baseline=()
      [ -n "${ELLICAST_SPEED_BASELINE:-}" ] && baseline=(--baseline "$ELLICAST_SPEED_BASELINE")
      # ELLICAST_SPEED_INSTRUCTIONS=1: the decodes counted in instructions too (valgrind; deterministic).
      count=()
      [ "${ELLICAST_SPEED_INSTRUCTIONS:-0}" = 1 ] && count=(--instructions)
      python3 "$root/bench/speed.py" "$build/ellicast" "$samples/meshes" "$results/speed.txt" $large \
        --runs "${ELLICAST_SPEED_RUNS:-3}" "${gltf[@]}" "${baseline[@]}" "${count[@]}" ;;
    live)
      # The live view in headless Chromium (issue 33): the bunny at 1 Mbit/s with no loss and at 30%
      # loss: when the first picture is drawn after tune-in, the time from a model's event to its
      # first frame, frames a second while orbiting the exact model, the page's JS heap.
      echo "== live view: the bunny at 1 Mbit/s in headless Chromium (tests/browser/live_view.mjs)" >&2
      tmp=$(mktemp -d)
      "$build/ellicast" encode -q "$samples/meshes/bunny.ply" -o "$tmp/bunny.ellc" > /dev/null
      mkdir -p "$results/live_view"
      : > "$results/live_view.txt"
      for loss in 0 0.3; do
        echo "-- the bunny at 1 Mbit/s, loss $loss, tuned in at slot 0 ($(uptime | sed 's/.*load/load/'))" | tee -a "$results/live_view.txt"
        LIVE_VIEW_FIGURES_ONLY=1 LIVE_VIEW_RATE=1000000 LIVE_VIEW_LOSS=$loss node "$root/tests/browser/live_view.mjs" "$build/ellicast" \
          "$tmp/bunny.ellc" "$samples/meshes/bunny.ply" "$tmp/shots-$loss" "$root/.cache/node/node_modules" 2>&1 |
          grep -v '^ok' | sed "s|$tmp/shots-$loss/|bench/results/live_view/|" | tee -a "$results/live_view.txt" || true
      done
      cp "$tmp/shots-0.3/"*.png "$results/live_view/" 2>/dev/null || true
      rm -rf "$tmp" ;;
    region)
      # Refinement where the viewer looks (issue 33): insertion time and error inside a region when
      # only the points there are inserted, against inserting every point; the bunny, and the bunny
      # Loop-subdivided twice (575k vertices).
      echo "== region of interest: bench_region on the bunny and the bunny subdivided twice" >&2
      tmp=$(mktemp -d)
      "$build/bench/bench_region" subdivide "$samples/meshes/bunny.ply" "$tmp/bunny_x16.ply" 2 | tee "$results/region.txt"
      for m in "$samples/meshes/bunny.ply" "$tmp/bunny_x16.ply"; do
        timed "$build/ellicast" encode -q "$m" -o "$tmp/region.ellc" --repair 0 2>&1 | sed 's/^/encode: /' | tee -a "$results/region.txt"
        "$build/bench/bench_region" "$tmp/region.ellc" "$m" | tee -a "$results/region.txt"
      done
      rm -rf "$tmp" ;;
    *) echo "bench: unknown benchmark '$what' (encode, decode, quality, gallery, first-picture, full-quality, broadcast, compare, corpus, point-share, speed, live, region)" >&2; exit 2 ;;
  esac
done
