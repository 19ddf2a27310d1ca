#!/usr/bin/env bash
# Builds Penumbra the way an application gets it, then the examples against that:
#   1. the library alone (PENUMBRA_BUILD_TOOLS=OFF: no scene component, no tools), into
#      WORK/library, installed into WORK/prefix; or, when PENUMBRA_INSTALLED_PREFIX names
#      one, the library already installed there that way (scripts/test.sh passes the one
#      scripts/check_library_build.sh installed from docs/library.md's commands, so CI
#      compiles the library alone once);
#   2. checks the installed headers: exactly the public headers of include/penumbra/ (less
#      the scene component's) and the generated version.hpp, each compiling on its own;
#   3. configures and builds examples/minimal, examples/deferred and examples/engine from
#      clean folders with find_package(Penumbra) on WORK/prefix, into WORK/<example>,
#      and tests/examples/gpu_component (a client of the Vulkan helper component,
#      Penumbra::gpu) into WORK/gpu_component.
# The example tests (tests/examples) run the binaries; ctest runs this script first.
#   scripts/build_examples.sh WORK
set -euo pipefail
if [[ $# -ne 1 ]]; then
  echo "usage: scripts/build_examples.sh WORK" >&2
  exit 2
fi
source_dir="$(cd "$(dirname "$0")/.." && pwd)"
work="$1"
rm -rf "$work"
mkdir -p "$work"
work="$(cd "$work" && pwd)"
prefix="$work/prefix"

if [[ -n "${PENUMBRA_INSTALLED_PREFIX:-}" ]]; then
  [[ -f "$PENUMBRA_INSTALLED_PREFIX/lib/cmake/Penumbra/PenumbraConfig.cmake" ]] || {
    echo "build_examples: PENUMBRA_INSTALLED_PREFIX=$PENUMBRA_INSTALLED_PREFIX holds no installed Penumbra" >&2
    exit 1
  }
  prefix="$(cd "$PENUMBRA_INSTALLED_PREFIX" && pwd)"
  echo "build_examples: the library installed in $prefix"
else
  cmake -S "$source_dir" -B "$work/library" -G Ninja -DCMAKE_BUILD_TYPE=Release \
    -DPENUMBRA_BUILD_TOOLS=OFF -DPENUMBRA_TESTS=OFF >/dev/null
  cmake --build "$work/library"
  cmake --install "$work/library" --prefix "$prefix" >/dev/null
fi

expected="$( (cd "$source_dir/include" && find penumbra -path penumbra/scene -prune -o -type f \
  \( -name '*.hpp' -o -name '*.h' -o -name '*.glsl' -o -name '*.hlsl' \) -print; echo penumbra/version.hpp) | sort)"
installed="$(cd "$prefix/include" && find . -type f | sed 's|^\./||' | sort)"
if [[ "$expected" != "$installed" ]]; then
  echo "build_examples: the installed headers differ from the public ones:" >&2
  diff <(echo "$expected") <(echo "$installed") >&2 || true
  exit 1
fi
for header in $(cd "$prefix/include" && find penumbra -name '*.hpp'); do
  echo "#include <$header>" | c++ -std=c++20 -fsyntax-only -Wall -Wextra -Werror -I "$prefix/include" -x c++ - \
    || { echo "build_examples: $header does not compile on its own" >&2; exit 1; }
done

for example in minimal deferred engine; do
  cmake -S "$source_dir/examples/$example" -B "$work/$example" -G Ninja -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_COMPILE_WARNING_AS_ERROR=ON >/dev/null
  cmake --build "$work/$example"
done
cmake -S "$source_dir/tests/examples/gpu_component" -B "$work/gpu_component" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_COMPILE_WARNING_AS_ERROR=ON >/dev/null
cmake --build "$work/gpu_component"
echo "build_examples: the library, its installed headers, the examples and the gpu component client built in $work"
