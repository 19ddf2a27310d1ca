#!/usr/bin/env bash
# Renders every .gltf and .glb found under FOLDER (a local copy of a model collection, such
# as the Khronos glTF-Sample-Models; nothing is fetched) and prints one Markdown table row
# per model file: "rendered", or the one-line refusal penumbra gave. Then, for a collection
# laid out as the Khronos samples are (MODEL/VARIANT/file: glTF, glTF-Binary,
# glTF-Embedded, glTF-Draco, glTF-pbrSpecularGlossiness, any other variant folder gets a
# column too), one row per model and one column per variant: ✓ rendered, n/o when a file
# the model names is absent from the copy (a buffer or an image), else penumbra's refusal;
# and the totals. Not part of CI: the models are not shipped. docs/scene-format.md holds
# the table for the Khronos sample models.
#   scripts/gltf_survey.sh FOLDER [PENUMBRA_BINARY]
set -uo pipefail
folder="${1:?usage: scripts/gltf_survey.sh FOLDER [PENUMBRA_BINARY]}"
penumbra="${2:-build/penumbra}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
results="$work/results.tsv"
: > "$results"
echo "| model | result |"
echo "|---|---|"
while read -r model; do
  # The model placed at the origin under the default camera and sun; only loading and
  # rendering are surveyed, so the image is tiny.
  printf '[[objects]]\ntype = "gltf"\nfile = "%s"\n' "$(realpath "$model")" > "$work/scene.toml"
  if output="$(timeout 300 "$penumbra" render "$work/scene.toml" --width 64 --height 48 -o "$work/out.png" 2>&1)"; then
    result="rendered"
  else
    result="$(printf '%s' "$output" | grep -v '^$' | tail -n 1 | sed "s|$work/scene.toml: objects\[0\].file: ||; s|$(realpath "$folder")/||g")"
  fi
  echo "| ${model#"$folder"/} | ${result//|/\\|} |"
  printf '%s\t%s\n' "${model#"$folder"/}" "$result" >> "$results"
done < <(find "$folder" -type f \( -name '*.gltf' -o -name '*.glb' \) | LC_ALL=C sort)

# The per-model table: MODEL/VARIANT/FILE paths only; a cell is the variant's file's result.
echo
awk -F '\t' '
  function cell(result) {
    if (result == "rendered") return "✓"
    if (result ~ /no such file relative to the model|could not be read or decoded/) return "n/o"
    gsub(/\|/, "\\|", result)
    return result
  }
  {
    count = split($1, part, "/")
    if (count != 3) next
    model = part[1]; variant = part[2]
    if (!(model in seen_model)) { seen_model[model] = 1; models[++model_count] = model }
    if (!(variant in seen_variant)) { seen_variant[variant] = 1; variants[++variant_count] = variant }
    value = cell($2)
    if ((model, variant) in cells) cells[model, variant] = cells[model, variant] "; " value
    else cells[model, variant] = value
    if (value == "✓") rendered++; else if (value == "n/o") absent++; else refused++
  }
  END {
    if (model_count == 0) exit
    # The Khronos variants first, in the order of their folder names, then the rest.
    order_count = 0
    split("glTF glTF-Binary glTF-Embedded glTF-Draco glTF-pbrSpecularGlossiness", known, " ")
    for (k = 1; k <= 5; ++k) if (known[k] in seen_variant) { order[++order_count] = known[k]; placed[known[k]] = 1 }
    for (v = 1; v <= variant_count; ++v) if (!(variants[v] in placed)) order[++order_count] = variants[v]
    header = "| model |"; rule = "|---|"
    for (v = 1; v <= order_count; ++v) { name = order[v]; sub(/^glTF-/, "", name); if (name == "pbrSpecularGlossiness") name = "SpecGloss"; header = header " " name " |"; rule = rule "---|" }
    print header; print rule
    for (m = 1; m <= model_count; ++m) {
      row = "| " models[m] " |"
      for (v = 1; v <= order_count; ++v) row = row " " ((models[m], order[v]) in cells ? cells[models[m], order[v]] : "") " |"
      print row
    }
    printf "\n%d model files: %d rendered, %d refused, %d not obtainable (n/o)\n", rendered + refused + absent, rendered, refused, absent
  }' "$results"
