#!/usr/bin/env bash
# Installs everything Penumbra needs to build, render and test on Debian 12, from
# Debian's own packages. Non-interactive and idempotent: packages already present are
# not fetched again, and `apt-get update` runs only when something is missing.
set -euo pipefail

packages=(
  # toolchain
  g++ cmake ninja-build pkg-config clang-format
  # fuzzing: clang with libFuzzer and the sanitizers' runtimes (tests/fuzz)
  clang libclang-rt-14-dev
  # Vulkan: headers + loader, the GLSL compiler, Mesa's lavapipe CPU driver (used when no
  # GPU is present, and by CI), the Khronos validation layer (every test runs with it)
  libvulkan-dev glslc mesa-vulkan-drivers vulkan-validationlayers
  # libraries: math, glTF (with its stb/json dependencies), TOML, command line, PNG, tests
  libglm-dev libtinygltf-dev libstb-dev nlohmann-json3-dev libtomlplusplus-dev libcli11-dev
  libpng-dev googletest libgtest-dev
  # ray tracing: Embree 3 BVHs for `penumbra compare`'s ground-truth shadow rays
  libembree-dev
  # `penumbra view`: the window and its surface, the Dear ImGui panel (core library and the
  # GLFW/Vulkan backend sources), and a virtual X server for its tests (xvfb-run needs xauth)
  libglfw3-dev libimgui-dev xvfb xauth
  # real glTF 2.0 models (Khronos samples) for bench/quality_report.py's real-asset table
  assimp-testmodels
)

missing=()
for package in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$package")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages are installed"
  exit 0
fi

echo "setup: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
$SUDO apt-get update -q
$SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
