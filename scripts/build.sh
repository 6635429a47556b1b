#!/usr/bin/env bash
# Installs dependencies (Debian 12 packages) and builds everything into build/ (or $WALK_BUILD_DIR).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
build_dir=${WALK_BUILD_DIR:-build}
cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=${WALK_BUILD_TYPE:-RelWithDebInfo} >/dev/null
ninja -C "$build_dir" -j"$(nproc)"
