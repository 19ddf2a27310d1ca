#!/usr/bin/env bash
# docs/library.md "Getting it", run as printed: the library-only build a new user follows.
#   1. copies the tree (its tracked files and the untracked ones git does not ignore, so
#      uncommitted work is checked too) into a fresh temporary folder;
#   2. runs the shell block under "## Getting it" there, line by line as printed, with one
#      substitution: the install prefix /opt/penumbra becomes WORK/prefix (the build folder
#      is the block's own relative `build`, inside the copy);
#   3. checks that the configure looked for nothing but the library's dependencies (no
#      GoogleTest, JSON, TOML, glTF, CLI, PNG, window or ray-tracing package in the
#      cache), and that the install holds the library and its package files and no scene
#      component or tool;
#   4. turns the library's own tests on in the same build folder (-DPENUMBRA_TESTS=ON,
#      tools still off), builds them and runs the unit tests: the library's tests build
#      without the scene component or the tools. (The library tests themselves run in the
#      main test suite; here they are only listed, which proves they link.)
# CI runs it from scripts/test.sh. Exits non-zero on the first failure.
#   scripts/check_library_build.sh [WORK]   (default: a new folder under /tmp, removed after)
set -euo pipefail
source_dir="$(cd "$(dirname "$0")/.." && pwd)"
if [[ $# -ge 1 ]]; then
  work="$1"
  rm -rf "$work"
  mkdir -p "$work"
  work="$(cd "$work" && pwd)"
else
  work="$(mktemp -d /tmp/penumbra-library-build.XXXXXX)"
  trap 'rm -rf "$work"' EXIT
fi
tree="$work/tree"
prefix="$work/prefix"
fail() {
  echo "check_library_build: $*" >&2
  exit 1
}

# 1. A fresh copy of the tree.
mkdir -p "$tree"
(cd "$source_dir" && git ls-files -z --cached --others --exclude-standard |
  while IFS= read -r -d '' file; do [[ -e "$file" ]] && printf '%s\0' "$file"; done |
  tar --null -T - -cf -) | tar -xf - -C "$tree"

# 2. The commands, as printed.
commands="$(awk '/^## Getting it/ { section = 1; next }
                 section && /^```sh/ { block = 1; next }
                 block && /^```/ { exit }
                 block' "$source_dir/docs/library.md")"
[[ "$commands" == *"cmake --install build --prefix /opt/penumbra"* ]] ||
  fail "docs/library.md \"Getting it\" no longer installs to /opt/penumbra: update this script"
while IFS= read -r line; do
  [[ -z "$line" ]] && continue
  line="${line//\/opt\/penumbra/$prefix}"
  echo "check_library_build: \$ $line"
  (cd "$tree" && bash -euo pipefail -c "$line") || fail "this command of docs/library.md failed: $line"
done <<<"$commands"

# 3. What the configure looked for, and what the install holds.
cache="$tree/build/CMakeCache.txt"
for package in GTest nlohmann_json tomlplusplus TinyGLTF CLI11 glfw3 embree PNG; do
  if grep -q "^${package}_\(DIR\|LIBRARY\|INCLUDE_DIR\)[:=]" "$cache"; then
    fail "the library-only configure looked for $package ($(grep -m1 "^${package}_" "$cache"))"
  fi
done
for file in lib/libpenumbra.a lib/cmake/Penumbra/PenumbraConfig.cmake lib/cmake/Penumbra/PenumbraTargets.cmake \
  include/penumbra/penumbra.hpp include/penumbra/version.hpp include/penumbra/shadow.glsl; do
  [[ -e "$prefix/$file" ]] || fail "the install lacks $file"
done
[[ ! -e "$prefix/include/penumbra/scene" ]] || fail "the library-only install holds the scene component's headers"
[[ ! -e "$prefix/bin" ]] || fail "the library-only install holds tools: $(ls "$prefix/bin")"

# 4. The library's own tests, without the tools.
cmake -S "$tree" -B "$tree/build" -DPENUMBRA_TESTS=ON >/dev/null
cmake --build "$tree/build" --target penumbra_unit_tests penumbra_library_tests
"$tree/build/tests/penumbra_unit_tests" --gtest_brief=1
library_tests="$("$tree/build/tests/library/penumbra_library_tests" --gtest_list_tests | grep -c '^  ')"
[[ "$library_tests" -gt 0 ]] || fail "the library tests list no test"
echo "check_library_build: \"Getting it\" ran as printed; the library's unit tests pass and its" \
  "$library_tests library tests build, without the tools"
