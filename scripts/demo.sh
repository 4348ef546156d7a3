#!/usr/bin/env bash
# The main job on the bundled sample: sets everything up (scripts/setup.sh), then sends
# samples/trefoil.obj through ellicast as a broadcast receiver would see it:
#   encode -> inspect -> validate -> decode everything -> lose 60% of the packets -> decode what is left
#   -> measure both reconstructions against the original -> draw them side by side.
# Everything it writes goes to out/demo/ (override with ELLICAST_DEMO_OUT).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${ELLICAST_BUILD_DIR:-$root/build}
out=${ELLICAST_DEMO_OUT:-$root/out/demo}
bash "$root/scripts/setup.sh" --no-checkers ellicast  # only the tool the demo runs
# out/demo is the demo's own folder and is started afresh; a folder given by the user must be new or empty.
if [ -z "${ELLICAST_DEMO_OUT:-}" ]; then
  rm -rf "$out"
elif [ -n "$(ls -A "$out" 2>/dev/null)" ]; then
  echo "demo: $out is not empty; choose a new folder for ELLICAST_DEMO_OUT" >&2
  exit 2
fi
mkdir -p "$out"
ellicast="$build/ellicast"
model="$root/samples/trefoil.obj"

step() { printf '\n== %s\n' "$*" >&2; }

step "encode $model"
"$ellicast" encode "$model" -o "$out/trefoil.ellc"
step "inspect the stream"
"$ellicast" inspect "$out/trefoil.ellc"
step "validate the stream"
"$ellicast" validate "$out/trefoil.ellc"
step "decode every packet (snapshots as points arrive)"
"$ellicast" decode "$out/trefoil.ellc" -o "$out/trefoil.glb" --snapshots 800
step "a lossy channel: 60% of the packets lost at random"
"$ellicast" simulate "$out/trefoil.ellc" -o "$out/trefoil-received.ellc" --loss 0.6 --seed 7
"$ellicast" decode "$out/trefoil-received.ellc" -o "$out/trefoil-lossy.glb"
step "distance to the original (percent of the bounding-box diagonal)"
"$ellicast" diff "$model" "$out/trefoil.glb"
"$ellicast" diff "$model" "$out/trefoil-lossy.glb"
step "pictures: base only, after 1,600 points, every point, after 60% loss -> $out/trefoil-progress.png"
"$ellicast" render "$out/trefoil.snap-o0-p0000000.glb" "$out/trefoil.snap-o0-p0001600.glb" "$out/trefoil.glb" \
  "$out/trefoil-lossy.glb" -o "$out/trefoil-progress.png" --width 320 --height 320 \
  --labels "base only (ellipsoids),1600 points,every packet (exact),60% of packets lost"
printf '\nwrote %s\n' "$out" >&2
ls -l "$out" >&2
