#!/usr/bin/env bash
# Sets everything up (scripts/setup.sh) and runs the whole test suite under CTest.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${ELLICAST_BUILD_DIR:-$root/build}
bash "$root/scripts/setup.sh"
cd "$build"
ctest --output-on-failure -j "$(nproc)" --timeout 600
