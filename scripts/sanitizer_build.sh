#!/usr/bin/env bash
# The sanitizer build, build-sanitize/: clang, every target instrumented with
# AddressSanitizer, UndefinedBehaviorSanitizer and libFuzzer's coverage (-DPENUMBRA_FUZZ=ON),
# at -O1 with line tables and NDEBUG (Debian's toml++ 3.3.0 asserts on input the release
# build rejects with a clear error: tests/fuzz/README.md). One compile of the library serves
# scripts/sanitize.sh (the unit and library tests) and tests/fuzz/run.sh (the harnesses).
#   scripts/sanitizer_build.sh TARGET...
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build-sanitize -G Ninja -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_CXX_FLAGS_RELEASE="-O1 -gline-tables-only -DNDEBUG" -DPENUMBRA_FUZZ=ON -DPENUMBRA_TESTS=ON >/dev/null
cmake --build build-sanitize --target "$@"
