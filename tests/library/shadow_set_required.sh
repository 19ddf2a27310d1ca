#!/usr/bin/env bash
# penumbra/shadow.glsl and penumbra/shadow.hlsl refuse to compile without PENUMBRA_SHADOW_SET
# (a silent set 0 would collide with the caller's own set 0), naming the define; with it the
# same shaders compile. Usage: shadow_set_required.sh GLSLC INCLUDE_DIR
set -euo pipefail
glslc="$1"
include_dir="$2"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

printf '#version 460\n#extension GL_GOOGLE_include_directive : require\n#include "penumbra/shadow.glsl"\n%s\n' \
  'layout(local_size_x = 1) in; void main() {}' >"$work/probe.comp"
printf '#include "penumbra/shadow.hlsl"\n%s\n' '[numthreads(1, 1, 1)] void main() {}' >"$work/probe.comp.hlsl"

check() {
  local name="$1"
  shift
  if "$glslc" "$@" -I "$include_dir" -o "$work/out.spv" 2>"$work/errors"; then
    echo "FAIL: $name compiled without PENUMBRA_SHADOW_SET" >&2
    exit 1
  fi
  if ! grep -q 'define PENUMBRA_SHADOW_SET' "$work/errors"; then
    echo "FAIL: $name's error does not name PENUMBRA_SHADOW_SET:" >&2
    cat "$work/errors" >&2
    exit 1
  fi
  if ! "$glslc" "$@" -DPENUMBRA_SHADOW_SET=2 -I "$include_dir" -o "$work/out.spv"; then
    echo "FAIL: $name does not compile with PENUMBRA_SHADOW_SET" >&2
    exit 1
  fi
  echo "ok: $name"
}

check GLSL "$work/probe.comp"
check HLSL -x hlsl -fshader-stage=comp --target-env=vulkan1.2 --target-spv=spv1.3 "$work/probe.comp.hlsl"
