#!/usr/bin/env bash
# The test command: set-up, build, then every test (CTest runs the GoogleTest suites and the script checks).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
build_dir=${WALK_BUILD_DIR:-build}
ctest --test-dir "$build_dir" --output-on-failure -j"$(nproc)" "$@"
