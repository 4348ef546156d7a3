#!/usr/bin/env bash
# The live view's browser test (live_view.mjs) on the bundled trefoil: encodes it, then plays the
# recording at 30% loss to a headless Chromium. Exit 77 (skipped, with a message) without node,
# Chromium or the ws module.
# usage: run_live_view.sh ELLICAST SOURCE_DIR SCRATCH_DIR
set -euo pipefail
ellicast=$1 source=$2 scratch=$3
command -v node >/dev/null || { echo "SKIP: node is not installed (scripts/setup.sh installs it)"; exit 77; }
mkdir -p "$scratch"
"$ellicast" encode "$source/samples/trefoil.obj" -o "$scratch/trefoil.ellc" >/dev/null 2>&1
exec node "$source/tests/browser/live_view.mjs" "$ellicast" "$scratch/trefoil.ellc" "$source/samples/trefoil.obj" \
  "$scratch" "$source/.cache/node/node_modules"
