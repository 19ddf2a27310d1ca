#!/usr/bin/env bash
# The unit and library tests under AddressSanitizer and UndefinedBehaviorSanitizer, from the
# sanitizer build (scripts/sanitizer_build.sh: clang, build-sanitize/, shared with the fuzz
# harnesses). Any sanitizer report fails. The library tests' sweeps over every filter run
# here for pcf and evsm only (a comparison filter and a moment filter: the host code of the
# others is the same, and the main test suite runs them all); the tools' renderer and its
# image tests are left out of CI's run for its time budget: `scripts/sanitize.sh --gpu` adds
# a few of them. Leaks are checked in the unit tests; the Vulkan tests run without leak
# checking: the loader unloads lavapipe (whose LLVM JIT keeps allocations to process exit)
# when the instance is destroyed, so their stacks cannot be attributed or suppressed.
# Vulkan objects Penumbra leaks are caught by the validation layer at vkDestroyDevice and
# by the library's object-count test. CI runs it after the test suite (scripts/test.sh).
#   scripts/sanitize.sh [--gpu]
set -euo pipefail
cd "$(dirname "$0")/.."
build=build-sanitize
targets=(penumbra_unit_tests penumbra_library_tests)
[[ "${1:-}" == "--gpu" ]] && targets+=(penumbra_gpu_tests)
bash scripts/sanitizer_build.sh "${targets[@]}"

export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
export ASAN_OPTIONS=detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1
"$build/tests/penumbra_unit_tests" --gtest_brief=1
export ASAN_OPTIONS=detect_leaks=0:strict_string_checks=1:detect_stack_use_after_return=1
# The library tests spend their time on one core (the instrumented host code and the
# validation layer): one shard per core, each test in exactly one of them.
shards="$(nproc)"
pids=()
for ((shard = 0; shard < shards; ++shard)); do
  GTEST_TOTAL_SHARDS="$shards" GTEST_SHARD_INDEX="$shard" "$build/tests/library/penumbra_library_tests" \
    --gtest_brief=1 --gtest_filter='-*/hard*:*/poisson*:*/pcss*:*/vsm*:*/msm*' >"$build/library_tests.$shard.log" 2>&1 &
  pids+=($!)
done
failed=0
for ((shard = 0; shard < shards; ++shard)); do
  if ! wait "${pids[$shard]}"; then
    cat "$build/library_tests.$shard.log" >&2
    failed=1
  fi
done
[[ "$failed" == 0 ]] || { echo "sanitize: the library tests failed (logs above)" >&2; exit 1; }
grep -h "tests from .* ran" "$build"/library_tests.*.log
if [[ "${1:-}" == "--gpu" ]]; then
  "$build/tests/gpu/penumbra_gpu_tests" --gtest_brief=1 \
    --gtest_filter='ShadowFootprint.*:ShadowFilters.HardEdgeSpansAtMostTwoTexels:*SpotFilters.*:*PointLightRoom.*'
fi
echo "sanitize: ${targets[*]} clean under ASan + UBSan"
