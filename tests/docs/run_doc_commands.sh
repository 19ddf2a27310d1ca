#!/usr/bin/env bash
# Runs every `build/penumbra ...` command in the code blocks of README.md and docs/*.md as
# printed (issue 16: the docs must run as written), at a small size, with the validation
# layer on, in a scratch folder that holds build/penumbra and examples/ as a fresh clone
# after the quick start does. `view` runs two frames under Xvfb (its own xvfb-run prefix
# in a doc gives way to ours; skipped without xvfb-run). A code line that calls the tool as
# plain `penumbra render|bench|compare|view|devices|inspect` (not on PATH after the quick start)
# fails the test, unless it is a synopsis with [optional] parts. Fails naming the file and
# the first command that fails.
#   tests/docs/run_doc_commands.sh REPOSITORY PENUMBRA_BINARY
set -euo pipefail
repo="$1"
binary="$2"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/build"
ln -s "$binary" "$work/build/penumbra"
ln -s "$repo/examples" "$work/examples"
cd "$work"

# "FILE<TAB>LINE" for every line inside a fenced code block of the docs.
code_lines() {
  for doc in "$repo/README.md" "$repo"/docs/*.md; do
    awk -v doc="${doc#"$repo"/}" '/^```/ { inside = !inside; next } inside { print doc "\t" $0 }' "$doc"
  done
}

bare="$(code_lines | grep -P '\t(\S+ )*penumbra (render|bench|compare|view|devices|inspect)\b' \
  | grep -vP '\tbuild/penumbra |\txvfb-run .* build/penumbra ' | grep -v '\[' || true)"
if [[ -n "$bare" ]]; then
  echo "docs call 'penumbra' without build/ (it is not on PATH after the quick start):" >&2
  echo "$bare" >&2
  exit 1
fi

count=0
while IFS=$'\t' read -r doc line; do
  line="build/penumbra ${line#*build/penumbra }"  # a doc's own xvfb-run prefix gives way to ours
  command="${line%%  #*}"  # the comment after two spaces
  prefix=""
  case "$command" in
    "build/penumbra devices"* | "build/penumbra inspect "*) extra="" ;;
    "build/penumbra view "*)
      if ! command -v xvfb-run >/dev/null; then echo "skipped (no xvfb-run): $command"; continue; fi
      prefix="xvfb-run -a -s '-screen 0 640x480x24'"
      extra="--width 64 --height 48 --frames 2 --validate" ;;
    "build/penumbra bench "*) extra="--width 64 --height 48 --warmup 1 --validate" ;;
    "build/penumbra compare "*) extra="--width 64 --height 48 --rays 2 --stability-frames 2 --validate" ;;
    *) extra="--width 64 --height 48 --validate" ;;
  esac
  # The doc's own size, frame count and --validate give way to the small ones above.
  command="$(sed -E 's/ --(width|height|frames) [0-9]+//g; s/ --validate//g' <<<"$command")"
  [[ "$command" == "build/penumbra bench "* ]] && extra="$extra --frames 2"
  if ! output="$(eval "$prefix $command $extra" 2>&1 </dev/null)"; then
    echo "$doc: command failed: $command" >&2
    echo "$output" >&2
    exit 1
  fi
  count=$((count + 1))
done < <(code_lines | grep -P '\t(xvfb-run .* )?build/penumbra ')
[ "$count" -gt 0 ] || { echo "no build/penumbra command found in the docs" >&2; exit 1; }
echo "docs: $count commands ran"
