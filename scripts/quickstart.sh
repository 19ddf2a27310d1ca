#!/usr/bin/env bash
# README command 1: install dependencies, build, and render the built-in default scene.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
# Only the command-line tool (the test suite is built by scripts/test.sh: minutes on 2 cores),
# with CMake's configure output shown.
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo
cmake --build build --target penumbra
./build/penumbra render builtin:default -o build/penumbra.png
echo "Rendered the default scene to $(pwd)/build/penumbra.png"
