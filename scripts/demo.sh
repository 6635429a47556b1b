#!/usr/bin/env bash
# The main job: set-up, build, compile the sample building, then run walkd with simulated devices (a treadmill
# walk through doors and a dimmer sweep) for a fixed simulated time. Writes PNG frames and summary.json to
# out/demo/ (or $1). With a display (DISPLAY or WAYLAND_DISPLAY set) walkd opens a window instead of rendering
# headless.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-out/demo}
bash scripts/build.sh
build_dir=${WALK_BUILD_DIR:-build}
mkdir -p "$out"
"$build_dir/tools/walk" compile config/scenes/house.toml -o "$build_dir/house.walk"
"$build_dir/tools/walk" inspect "$build_dir/house.walk"
"$build_dir/firmware-host/walkd" --config config/kiosk/demo.toml --bundle "$build_dir/house.walk" --output "$out"
echo "demo: frames and summary in $out"
cat "$out/summary.json"
