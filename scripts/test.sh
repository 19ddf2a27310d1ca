#!/usr/bin/env bash
# README command 2 (and CI): install dependencies, build, check formatting, and run the
# whole test suite. GPU tests run on whatever Vulkan device is present (lavapipe on CI)
# with the Khronos validation layer; any validation message fails them.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
bash scripts/check-format.sh
# docs/library.md "Getting it" as printed, in a fresh copy of the tree: the library alone,
# installed, then its own tests built without the tools. The test suite's examples build
# against that install (scripts/build_examples.sh) instead of compiling the library again.
bash scripts/check_library_build.sh build/library-check
PENUMBRA_INSTALLED_PREFIX="$PWD/build/library-check/prefix" ctest --test-dir build --output-on-failure -j "$(nproc)"
# Unit and library tests again under ASan + UBSan (build-sanitize/).
bash scripts/sanitize.sh
# Every fuzz harness for 15 s (clang, ASan + UBSan) from its seed corpus: tests/fuzz/README.md.
bash tests/fuzz/run.sh 15
