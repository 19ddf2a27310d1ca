#!/usr/bin/env bash
# Builds Penumbra's libFuzzer harnesses (clang, AddressSanitizer + UndefinedBehaviorSanitizer)
# in the sanitizer build (scripts/sanitizer_build.sh, build-sanitize/) and runs each for
# SECONDS (default 30) from its seed corpus: the repros
# of tests/fuzz/corpus/ plus the project's own scenes and glTF fixtures. Fails on the first
# crash, sanitizer report, leak, timeout (an input over 10 s) or out-of-memory (2 GiB), and
# says where the input that did it was written. README.md beside this script has the longer
# run. CI runs `bash tests/fuzz/run.sh 15` (scripts/test.sh).
#   tests/fuzz/run.sh [SECONDS [HARNESS...]]   (default: every harness)
set -euo pipefail
seconds="${1:-30}"
cd "$(dirname "$0")/../.."
build=build-sanitize
harnesses=(fuzz_scene_toml fuzz_settings_toml fuzz_gltf fuzz_glb fuzz_shadow_system)
if [ $# -gt 1 ]; then harnesses=("${@:2}"); fi

bash scripts/sanitizer_build.sh "${harnesses[@]}"

# Seeds: committed repros, then the project's own inputs of each kind.
seeds="$build/seeds"
rm -rf "$seeds" "$build/artifacts"
mkdir -p "$seeds" "$build/artifacts"
for kind in scene settings gltf glb shadow_system; do cp -r "tests/fuzz/corpus/$kind" "$seeds/$kind"; done
cp tests/data/scenes/*.toml bench/scenes/*.toml "$seeds/scene/"
cp tests/data/scenes/*.toml "$seeds/settings/"
cp tests/data/gltf/*.gltf "$seeds/gltf/"
cp tests/data/gltf/*.glb "$seeds/glb/"

declare -A corpus=([fuzz_scene_toml]=scene [fuzz_settings_toml]=settings [fuzz_gltf]=gltf [fuzz_glb]=glb
                   [fuzz_shadow_system]=shadow_system)
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
for harness in "${harnesses[@]}"; do
  # lavapipe (LLVM's JIT) keeps allocations to process exit: leak checks are for the parsers.
  leaks=1
  [ "$harness" = fuzz_shadow_system ] && leaks=0
  work="$build/work/$harness"
  mkdir -p "$work"
  echo "fuzz: $harness for ${seconds} s"
  if ! ASAN_OPTIONS="detect_leaks=$leaks" "$build/tests/fuzz/$harness" "$work" "$seeds/${corpus[$harness]}" \
      -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
      -artifact_prefix="$build/artifacts/$harness-" >"$build/$harness.log" 2>&1; then
    tail -n 40 "$build/$harness.log" >&2
    echo "fuzz: $harness failed; its input is in $build/artifacts/ (log: $build/$harness.log)" >&2
    exit 1
  fi
  grep -E "^stat::(number_of_executed_units|new_units_added)" "$build/$harness.log" | sed "s/^/fuzz: $harness /" || true
done
echo "fuzz: ${#harnesses[@]} harnesses ran ${seconds} s each without a finding"
