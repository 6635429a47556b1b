#!/usr/bin/env bash
# Installs dependencies (Debian 12 packages) and builds everything into build/ (or $WALK_BUILD_DIR).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
build_dir=${WALK_BUILD_DIR:-build}
# CI (WALK_CI set, as .ci/run does) fails on any compiler warning; a developer's build only shows them.
werror=OFF
[ -n "${WALK_CI:-}" ] && werror=ON
# Line tables only (file:line in backtraces and sanitizer reports) build a quarter faster than full debug
# information; WALK_DEBUG_INFO=full for a debugger's view of variables.
cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=${WALK_BUILD_TYPE:-RelWithDebInfo} \
  -DWALK_WARNINGS_AS_ERRORS=$werror -DWALK_DEBUG_INFO=${WALK_DEBUG_INFO:-lines} >/dev/null
ninja -C "$build_dir" -j"$(nproc)"
