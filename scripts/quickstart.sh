#!/usr/bin/env bash
# README command 1: install dependencies, build, and render the built-in default scene.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
./build/penumbra render builtin:default -o penumbra.png
echo "Rendered the default scene to $(pwd)/penumbra.png"
