#!/usr/bin/env bash
# Runs every `build/penumbra ...` line of README.md as printed (issue 16: the docs must run
# as written), at a small size, with the validation layer on, in a scratch folder that holds
# build/penumbra and examples/ as a fresh clone after the quick start does. `view` runs two
# frames under Xvfb (skipped without xvfb-run). Fails naming the first command that fails.
#   tests/docs/run_readme_commands.sh REPOSITORY PENUMBRA_BINARY
set -euo pipefail
repo="$1"
binary="$2"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/build"
ln -s "$binary" "$work/build/penumbra"
ln -s "$repo/examples" "$work/examples"
cd "$work"

count=0
while IFS= read -r line; do
  command="${line%%  #*}"  # the comment after two spaces
  prefix=""
  case "$command" in
    "build/penumbra devices"*) extra="" ;;
    "build/penumbra view "*)
      if ! command -v xvfb-run >/dev/null; then echo "skipped (no xvfb-run): $command"; continue; fi
      prefix="xvfb-run -a -s '-screen 0 640x480x24'"
      extra="--width 64 --height 48 --frames 2 --validate" ;;
    "build/penumbra bench "*) extra="--width 64 --height 48 --warmup 1 --validate" ;;
    "build/penumbra compare "*) extra="--width 64 --height 48 --rays 2 --stability-frames 2 --validate" ;;
    *) extra="--width 64 --height 48 --validate" ;;
  esac
  # The README's own size, frame count and --validate give way to the small ones above.
  command="$(sed -E 's/ --(width|height|frames) [0-9]+//g; s/ --validate//g' <<<"$command")"
  [[ "$command" == "build/penumbra bench "* ]] && extra="$extra --frames 2"
  if ! output="$(eval "$prefix $command $extra" 2>&1)"; then
    echo "README command failed: $command" >&2
    echo "$output" >&2
    exit 1
  fi
  count=$((count + 1))
done < <(grep -E '^build/penumbra ' "$repo/README.md")
[ "$count" -gt 0 ] || { echo "no build/penumbra command found in README.md" >&2; exit 1; }
echo "README: $count commands ran"
