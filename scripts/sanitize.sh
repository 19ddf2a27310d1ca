#!/usr/bin/env bash
# The sanitizer build (README, "Tests"): every target compiled with AddressSanitizer and
# UndefinedBehaviorSanitizer (-DPENUMBRA_SANITIZE=ON) in build-sanitize/, then the unit
# tests and the library tests (the public API and every pass on lavapipe with the
# validation layer). The tools' renderer and its image tests are left out of CI's run to
# keep it within its time budget (they add a second build of the apps); run them with
# `scripts/sanitize.sh --gpu`. Any sanitizer report fails. Leaks are checked in the unit tests; the Vulkan tests run without leak
# checking: the loader unloads lavapipe (whose LLVM JIT keeps allocations to process exit)
# when the instance is destroyed, so their stacks cannot be attributed or suppressed.
# Vulkan objects Penumbra leaks are caught by the validation layer at vkDestroyDevice and
# by the library's object-count test. CI runs it after the test suite (scripts/test.sh).
#   scripts/sanitize.sh
set -euo pipefail
cd "$(dirname "$0")/.."
build=build-sanitize
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g" \
  -DPENUMBRA_SANITIZE=ON >/dev/null
targets=(penumbra_unit_tests penumbra_library_tests)
[[ "${1:-}" == "--gpu" ]] && targets+=(penumbra_gpu_tests)
cmake --build "$build" --target "${targets[@]}"

export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
export ASAN_OPTIONS=detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1
"$build/tests/penumbra_unit_tests" --gtest_brief=1
export ASAN_OPTIONS=detect_leaks=0:strict_string_checks=1:detect_stack_use_after_return=1
"$build/tests/library/penumbra_library_tests" --gtest_brief=1
if [[ "${1:-}" == "--gpu" ]]; then
  "$build/tests/gpu/penumbra_gpu_tests" --gtest_brief=1 \
    --gtest_filter='ShadowFootprint.*:ShadowFilters.HardEdgeSpansAtMostTwoTexels:*SpotFilters.*:*PointLightRoom.*'
fi
echo "sanitize: ${targets[*]} clean under ASan + UBSan"
