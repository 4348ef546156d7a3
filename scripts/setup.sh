#!/usr/bin/env bash
# Installs what ellicast needs on Debian 12 (as root, or through sudo) and builds it into build/.
# Safe to run again: it installs only what is missing and rebuilds incrementally.
# Usage: bash scripts/setup.sh [--no-checkers] [TARGET...]
#   TARGET...       build only these CMake targets (default: everything, the tests included);
#                   scripts/demo.sh builds only the `ellicast` tool
#   --no-checkers   skip the npm glTF checkers (glTF-Validator, glTF-Transform) the tests use
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${ELLICAST_BUILD_DIR:-$root/build}
checkers=1
targets=()
for arg in "$@"; do
  case "$arg" in
    --no-checkers) checkers=0 ;;
    -*) echo "setup: unknown option $arg (usage: setup.sh [--no-checkers] [TARGET...])" >&2; exit 2 ;;
    *) targets+=(--target "$arg") ;;
  esac
done

packages=(build-essential cmake pkg-config libtinygltf-dev libdraco-dev libopenmesh-dev libeigen3-dev
          libcli11-dev doctest-dev nlohmann-json3-dev libstb-dev libisal-dev libmeshoptimizer-dev libsodium-dev draco gnuplot-nox nodejs npm)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  # node and npm may come from elsewhere (nvm, nodesource): only install them when absent.
  filtered=()
  for p in "${missing[@]}"; do
    case "$p" in
      nodejs) command -v node >/dev/null || filtered+=("$p") ;;
      npm) command -v npm >/dev/null || filtered+=("$p") ;;
      *) filtered+=("$p") ;;
    esac
  done
  missing=("${filtered[@]}")
fi
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}" >&2
  sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "${missing[@]}" >/dev/null
fi

# glTF checkers used by the tests: the Khronos validator and glTF-Transform, kept in .cache/node.
node_dir="$root/.cache/node"
if [ "$checkers" = 1 ] && { [ ! -d "$node_dir/node_modules/gltf-validator" ] || [ ! -d "$node_dir/node_modules/@gltf-transform/cli" ]; }; then
  echo "setup: installing gltf-validator and @gltf-transform/cli (npm) into .cache/node" >&2
  mkdir -p "$node_dir"
  (cd "$node_dir" && [ -f package.json ] || echo '{"name":"ellicast-checkers","private":true}' > package.json)
  (cd "$node_dir" && npm install --no-audit --no-fund --loglevel=error gltf-validator@2.0.0-dev.3.10 @gltf-transform/cli@4 >/dev/null) \
    || echo "setup: warning: npm install failed; glTF validation tests will be skipped" >&2
fi

cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release ${ELLICAST_CMAKE_ARGS:-} >/dev/null
cmake --build "$build" -j "$(nproc)" ${targets[@]+"${targets[@]}"}
