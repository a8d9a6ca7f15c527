#!/usr/bin/env bash
# Installs the Debian 12 packages gisandbox needs, by name, only those that are missing.
# Idempotent: on a machine that has everything it installs nothing and does not touch the network.
set -euo pipefail

PACKAGES=(
  # toolchain
  build-essential cmake pkg-config clang libclang-rt-14-dev
  # GL: EGL + OSMesa (headless), GLFW (window), Mesa's llvmpipe driver, glad loader generator
  libegl-dev libopengl-dev libgl-dev libosmesa6-dev libgl1-mesa-dri libegl-mesa0 libglfw3-dev
  python3-glad glslang-tools
  # libraries
  libglm-dev libimgui-dev libtinygltf-dev libstb-dev libtinyexr-dev libcli11-dev nlohmann-json3-dev libembree-dev
  # SHA-256 for bench content ids (libcrypto)
  libssl-dev
  # bench sweeps over local cores or machines (docs/bench.md)
  parallel
  # tests (xvfb: the GLFW window backend runs under a virtual X server)
  libgtest-dev xvfb xauth
)

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "deps: installing ${missing[*]}" >&2
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -q
$SUDO apt-get install -y --no-install-recommends "${missing[@]}"
