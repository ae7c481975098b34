#!/usr/bin/env bash
# Installs the Debian 12 packages brdfit needs. Idempotent: when everything is present it
# only runs dpkg-query and returns in well under a second.
set -euo pipefail

PACKAGES=(
  build-essential cmake ninja-build ccache pkg-config git unzip
  libceres-dev libeigen3-dev libgoogle-glog-dev libgflags-dev
  libopenexr-dev libhdf5-dev libzip-dev libpng-dev
  libcli11-dev nlohmann-json3-dev libfmt-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libegl-dev libgl-dev libegl1-mesa-dev libgl1-mesa-dri libglfw3-dev libtinyobjloader-dev
  libjs-chart.js chromium xvfb xauth time
  python3-dev python3-pybind11 pybind11-dev python3-numpy python3-pytest  # python/ (docs/python.md)
  python3-venv python3-pip python3-setuptools python3-wheel dpkg-dev  # pip install ., cpack -G DEB
  parallel slurmctld slurmd slurm-client  # the sharded-batch recipes and their tests (docs/scale.md)
  blender  # Blender 3.4: export.blender_render renders the Blender exports (docs/exports.md)
  libopengl0 libglx0  # ../shared/tools/pbrt-v4's run-time libraries beside OpenEXR (export.pbrt_render)
)
# Extra packages for the sanitizer / fuzzing build (clang's runtimes).
if [[ "${BRDFIT_WITH_CLANG:-0}" == 1 ]]; then
  PACKAGES+=(clang libclang-rt-14-dev)
fi
# node + npm for the Khronos glTF-Validator of tests/export (pinned in tools/gltf/package-lock.json,
# installed by the test with `npm ci`): Debian's, unless a node with npm is already installed.
if ! command -v npm >/dev/null 2>&1; then
  PACKAGES+=(nodejs npm)
fi

missing=()
for p in "${PACKAGES[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  [[ "$status" == "install ok installed" ]] || missing+=("$p")
done
if ((${#missing[@]} == 0)); then
  exit 0
fi
echo "setup-deps: installing ${missing[*]}" >&2
SUDO=""
if [[ $(id -u) -ne 0 ]]; then SUDO=sudo; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
