#!/usr/bin/env bash
# One device call's runs of `penumbra bench --toggle` (docs/library.md "Changing settings"):
# what update_settings() costs per SettingEffect, against a run without a change, on one
# scene and image size. Writes one JSON per run and the bench tables to OUT.
#   bench/settings_toggle_runs.sh BINARY OUT
set -euo pipefail
binary="$1"
out="$2"
scene='builtin:forest?count=1000'
common=(--width 1920 --height 1080 --warmup 10 --frames 40 --camera-path still)
run() {
  local name="$1"
  shift
  echo "== $name: $*"
  "$binary" bench "$scene" "${common[@]}" "$@" --json "$out/toggle-$name.json" | tee "$out/toggle-$name.txt"
}
run none --filter poisson
run live --filter poisson --toggle shadow.slope_bias=3
run pipeline --filter poisson --toggle shadow.poisson_taps=32
run resource-filter --filter poisson --toggle 'shadow.filter="pcss"'
run resource-resolution --filter poisson --toggle shadow.resolution=1024
