#!/usr/bin/env bash
# Installs what ellicast needs on Debian 12 (as root, or through sudo) and builds it into build/.
# Safe to run again: it installs only what is missing and rebuilds incrementally.
# Usage: bash scripts/setup.sh [--no-checkers] [TARGET...]
#   TARGET...       build only these CMake targets (default: everything, the tests included);
#                   scripts/demo.sh builds only the `ellicast` tool
#   --no-checkers   skip what only the tests use: the npm glTF checkers (glTF-Validator, glTF-Transform),
#                   ws and the headless Chromium of the browser test
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

# npm packages, kept in .cache/node: three.js (the page of `ellicast view` and `receive --view`),
# and, for the tests, the Khronos glTF-Validator, glTF-Transform and ws (the browser test's
# DevTools client).
node_dir="$root/.cache/node"
npm_packages=(three@0.187.0)
[ "$checkers" = 1 ] && npm_packages+=(gltf-validator@2.0.0-dev.3.10 @gltf-transform/cli@4 ws@8.23.0)
npm_missing=()
for p in "${npm_packages[@]}"; do
  name=${p%@*}
  [ -d "$node_dir/node_modules/$name" ] || npm_missing+=("$p")
done
if [ ${#npm_missing[@]} -gt 0 ]; then
  echo "setup: installing ${npm_missing[*]} (npm) into .cache/node" >&2
  mkdir -p "$node_dir"
  (cd "$node_dir" && [ -f package.json ] || echo '{"name":"ellicast-checkers","private":true}' > package.json)
  (cd "$node_dir" && npm install --no-audit --no-fund --loglevel=error "${npm_missing[@]}" >/dev/null) \
    || echo "setup: warning: npm install failed; \`ellicast view\` needs three.js, and the glTF validation and browser tests will be skipped" >&2
fi

# The browser test of the live view runs a headless Chromium (Debian's chromium-headless-shell);
# it is skipped with a message where that cannot be installed.
if [ "$checkers" = 1 ] && ! command -v chromium-headless-shell >/dev/null && ! command -v chromium >/dev/null; then
  echo "setup: installing chromium-headless-shell (the live view's browser test)" >&2
  sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  { $sudo apt-get update -qq && DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq chromium-headless-shell >/dev/null; } \
    || echo "setup: warning: chromium-headless-shell could not be installed; the browser test will be skipped" >&2
fi

cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release ${ELLICAST_CMAKE_ARGS:-} >/dev/null
cmake --build "$build" -j "$(nproc)" ${targets[@]+"${targets[@]}"}
