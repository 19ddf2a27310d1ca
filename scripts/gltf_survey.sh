#!/usr/bin/env bash
# Renders every .gltf and .glb found under FOLDER (a local copy of a model collection, such
# as the Khronos glTF-Sample-Models; nothing is fetched) and prints one Markdown table row
# per model: "rendered", or the one-line refusal penumbra gave. Not part of CI: the models
# are not shipped. docs/scene-format.md holds the table for the Khronos sample models.
#   scripts/gltf_survey.sh FOLDER [PENUMBRA_BINARY]
set -uo pipefail
folder="${1:?usage: scripts/gltf_survey.sh FOLDER [PENUMBRA_BINARY]}"
penumbra="${2:-build/penumbra}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
echo "| model | result |"
echo "|---|---|"
find "$folder" -type f \( -name '*.gltf' -o -name '*.glb' \) | LC_ALL=C sort | while read -r model; do
  # The model placed at the origin under the default camera and sun; only loading and
  # rendering are surveyed, so the image is tiny.
  printf '[[objects]]\ntype = "gltf"\nfile = "%s"\n' "$(realpath "$model")" > "$work/scene.toml"
  if output="$(timeout 300 "$penumbra" render "$work/scene.toml" --width 64 --height 48 -o "$work/out.png" 2>&1)"; then
    result="rendered"
  else
    result="$(printf '%s' "$output" | grep -v '^$' | tail -n 1 | sed "s|$work/scene.toml: objects\[0\].file: ||; s|$(realpath "$folder")/||g")"
  fi
  echo "| ${model#"$folder"/} | ${result//|/\\|} |"
done
