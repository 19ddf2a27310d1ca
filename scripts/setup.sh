#!/usr/bin/env bash
# Installs everything Penumbra needs to build, render and test on Debian 12, from
# Debian's own packages. Non-interactive and idempotent: packages already present are
# not fetched again, and `apt-get update` runs only when something is missing.
#   scripts/setup.sh            everything: the library, the tools, the tests, CI
#   scripts/setup.sh --library  only what the library alone needs to build and install
#                               (docs/library.md, "Getting it"): the toolchain, Vulkan's
#                               headers and loader, glslc and glm
set -euo pipefail

library_packages=(
  # toolchain
  g++ cmake ninja-build pkg-config
  # Vulkan: headers + loader and the GLSL compiler; math inside the library (build only)
  libvulkan-dev glslc libglm-dev
)
other_packages=(
  clang-format
  # fuzzing: clang with libFuzzer and the sanitizers' runtimes (tests/fuzz)
  clang libclang-rt-14-dev
  # Mesa's lavapipe CPU driver (used when no GPU is present, and by CI) and the Khronos
  # validation layer (every test runs with it)
  mesa-vulkan-drivers vulkan-validationlayers
  # libraries: glTF (with its stb/json dependencies), TOML, command line, PNG, tests
  libtinygltf-dev libstb-dev nlohmann-json3-dev libtomlplusplus-dev libcli11-dev
  libpng-dev googletest libgtest-dev
  # compressed glTF geometry, decoded by the scene component only (never the library):
  # KHR_draco_mesh_compression (Draco) and EXT_meshopt_compression (meshoptimizer)
  libdraco-dev libmeshoptimizer-dev
  # ray tracing: Embree 3 BVHs for `penumbra compare`'s ground-truth shadow rays
  libembree-dev
  # `penumbra view`: the window and its surface, the Dear ImGui panel (core library and the
  # GLFW/Vulkan backend sources), and a virtual X server for its tests (xvfb-run needs xauth)
  libglfw3-dev libimgui-dev xvfb xauth
  # real glTF 2.0 models (Khronos samples) for bench/quality_report.py's real-asset table
  assimp-testmodels
)

case "${1:-}" in
  "") packages=("${library_packages[@]}" "${other_packages[@]}") ;;
  --library) packages=("${library_packages[@]}") ;;
  *)
    echo "usage: scripts/setup.sh [--library]" >&2
    exit 2
    ;;
esac

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
