#!/usr/bin/env bash
# The test command: set-up, build, then every test (CTest runs the GoogleTest suites and the script checks).
# CTest runs under a virtual X display so the GLFW window test runs too instead of being skipped.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
build_dir=${WALK_BUILD_DIR:-build}
if [ -z "${DISPLAY:-}" ] && command -v xvfb-run >/dev/null; then
  exec xvfb-run -a -s "-screen 0 1280x1024x24" ctest --test-dir "$build_dir" --output-on-failure -j"$(nproc)" "$@"
fi
exec ctest --test-dir "$build_dir" --output-on-failure -j"$(nproc)" "$@"
