#!/usr/bin/env bash
# Installs every build, test and demo dependency from Debian 12's packages.
# Idempotent: packages already present are skipped by apt-get; safe to run on every CI start.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config git python3
  # math, GL, windowing: OpenGL 3.3 core via OSMesa/EGL headless (llvmpipe) and GLFW windowed
  libglm-dev libglfw3-dev libosmesa6-dev libegl-dev libegl1-mesa-dev libgl-dev libgbm-dev libdrm-dev
  python3-glad libgl1-mesa-dri xvfb xauth
  # devices: HID, GPIO (libgpiod v1), Modbus, systemd notify/journal
  libhidapi-dev libgpiod-dev libmodbus-dev libsystemd-dev socat systemd procps
  # config, CLI, logging, geometry, images
  libtomlplusplus-dev libcli11-dev libspdlog-dev libfmt-dev nlohmann-json3-dev libpolyclipping-dev libpng-dev libjpeg-dev
  # parallel loops of the compiler stages, and the inputs-unchanged hashes
  libtbb-dev libxxhash-dev
  # levels of detail of clusters for moving frames; the half-resolution level's CPU upscale
  libmeshoptimizer-dev libpixman-1-dev
  # tests and benchmarks
  libgtest-dev libgmock-dev libbenchmark-dev gnuplot-nox
  # the Debian package: man pages from --help, and its check; the source format check
  help2man lintian clang-format
  # reference ray caster compared side by side with ours (optional at build time)
  libembree-dev
  # model import: meshes (OBJ, glTF, 3DS...) through assimp; clang + compiler-rt for the libFuzzer targets
  libassimp-dev clang libclang-rt-14-dev
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]} == 0)); then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi
echo "install-deps: installing ${missing[*]}"
SUDO=""
[ "$(id -u)" -ne 0 ] && SUDO="sudo"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
