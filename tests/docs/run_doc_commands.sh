#!/usr/bin/env bash
# Checks every command that README.md and docs/*.md print, so that a reader can paste it:
# the lines of ```sh/```bash blocks, command lines in ```text blocks, and inline code spans
# that are a command with arguments (`build/penumbra ...`, `penumbra <subcommand> ...`,
# `bash ...`, `python3 ...`, `scripts/*.sh ...`, `bench/*.py ...`, `cmake ...`, `ctest ...`,
# `xvfb-run ...`; a bare tool name only names it). Each command is one of:
#   - a template: its variable parts are visible, <placeholders> or [--optional] parts; it
#     is not run, and must not also hold a bare placeholder (SCENE, N, ..., pcf|poisson);
#   - listed in tests/docs/doc_command_exceptions.txt with the reason it is not run here
#     (builds the project, needs the GPU machine, takes many minutes, ...);
#   - a `build/penumbra ...` command, which runs as printed, shrunk only by the flags added
#     below (a small size, few frames, the validation layer on), in a scratch folder that
#     holds build/penumbra, examples/ and bench/ as a fresh clone does after the quick
#     start. `view` runs two frames under Xvfb (a doc's own xvfb-run prefix gives way to
#     ours; skipped without xvfb-run).
# Anything else fails, as does plain `penumbra ...` outside a template (the tool is not on
# PATH after the quick start), a code block without a language, an exception that no
# command uses, and a `file.md#anchor` link to a heading that does not exist.
# Fails naming the file, the line and the command.
#   tests/docs/run_doc_commands.sh REPOSITORY PENUMBRA_BINARY
set -euo pipefail
repo="$1"
binary="$2"
exceptions_file="$repo/tests/docs/doc_command_exceptions.txt"
docs=("$repo/README.md" "$repo"/docs/*.md)
problems=()

# "FILE<TAB>LINE<TAB>KIND<TAB>TEXT" for the code of every doc (see doc_code.awk).
doc_code() {
  for doc in "${docs[@]}"; do
    awk -v doc="${doc#"$repo"/}" -f "$repo/tests/docs/doc_code.awk" "$doc"
  done
}

is_command() {  # an inline span or text line that is a command with arguments
  [[ "$1" =~ ^(xvfb-run\ .*\ )?(build/penumbra\ |penumbra\ [a-z]+\ )|^(bash|python3|cmake|ctest|xvfb-run)\ |^(scripts/[^\ ]+\.sh|bench/[^\ ]+\.py)\  ]]
}

# The exceptions: "COMMAND OR PREFIX  # reason", one a line.
exception_prefixes=()
exception_used=()
while IFS= read -r entry; do
  [[ -z "$entry" || "$entry" == "#"* ]] && continue
  prefix="${entry%%  # *}"
  if [[ "$prefix" == "$entry" || -z "${entry#*  # }" ]]; then
    problems+=("doc_command_exceptions.txt: no reason given: $entry")
    continue
  fi
  exception_prefixes+=("$prefix")
  exception_used+=(0)
done <"$exceptions_file"

listed() {  # sets $listed_index when the command is an exception
  local i
  for i in "${!exception_prefixes[@]}"; do
    if [[ "$1" == "${exception_prefixes[$i]}"* ]]; then listed_index=$i; return 0; fi
  done
  return 1
}

to_run=()
templates=0
excepted=0
while IFS=$'\t' read -r doc line kind command; do
  where="$doc:$line"
  if [[ "$kind" == unlabelled ]]; then
    problems+=("$where: a code block without a language (sh for commands, text for output, ...)")
    continue
  fi
  if [[ "$kind" != sh ]] && ! is_command "$command"; then continue; fi
  # What stays of the command outside its <placeholders> and quoted strings.
  literal="$(sed -E "s/<[A-Za-z][^<>]*>//g; s/'[^']*'//g; s/\"[^\"]*\"//g" <<<"$command")"
  if grep -qP '(^|[\s\[|])[A-Z][A-Z0-9_]*($|[\s\]|])|(^|[\s=\[])\.\.\.|[\w-]\|[\w-]' <<<"$literal"; then
    problems+=("$where: a placeholder outside <angle brackets>: $command")
    continue
  fi
  if [[ "$command" =~ \<[A-Za-z][^\<\>]*\> || "$command" == *"[-"* ]]; then
    templates=$((templates + 1))
    continue
  fi
  if [[ "$command" =~ ^(xvfb-run\ .*\ )?penumbra\  ]]; then
    problems+=("$where: calls 'penumbra' without build/ (it is not on PATH after the quick start): $command")
    continue
  fi
  if listed "$command"; then
    exception_used[listed_index]=1
    excepted=$((excepted + 1))
    continue
  fi
  if [[ "$command" =~ ^(xvfb-run\ .*\ )?build/penumbra\  ]]; then
    to_run+=("$where"$'\t'"$command")
    continue
  fi
  problems+=("$where: neither run by this test, nor a <template>, nor in doc_command_exceptions.txt: $command")
done < <(doc_code)

for i in "${!exception_prefixes[@]}"; do
  if [[ "${exception_used[$i]}" == 0 ]]; then
    problems+=("doc_command_exceptions.txt: matches no command of the docs: ${exception_prefixes[$i]}")
  fi
done

# Every `file.md#anchor` (or `#anchor`) link must name a heading of that file, by GitHub's
# rule: lower case, punctuation but '-' and '_' dropped, spaces as '-', a repeat gets -1, -2.
anchors() {
  awk '/^ *```/ { inside = !inside; next }
       !inside && /^#+ / {
         h = tolower($0); sub(/^#+ +/, "", h); sub(/ +#* *$/, "", h)
         gsub(/[!-,.\/:-@[-^`{-~]/, "", h); gsub(/ /, "-", h)
         if (h in seen) { seen[h]++; h = h "-" seen[h] } else seen[h] = 0
         print h
       }' "$1"
}
for doc in "${docs[@]}"; do
  while IFS=: read -r line link; do
    target="${link%%#*}"
    anchor="${link#*#}"
    file="$doc"
    [[ -n "$target" ]] && file="$(dirname "$doc")/$target"
    if [[ ! -f "$file" ]]; then
      problems+=("${doc#"$repo"/}:$line: a link to a missing file: $link")
    elif ! anchors "$file" | grep -qxF -- "$anchor"; then
      problems+=("${doc#"$repo"/}:$line: a link to a heading that does not exist: $link")
    fi
  done < <(grep -noP '\]\(\K[^)\s]*#[^)\s]+(?=\))' "$doc" | grep -v '^[0-9]*:[a-z]*://' || true)
done

if [[ ${#problems[@]} -gt 0 ]]; then
  printf '%s\n' "${problems[@]}" >&2
  exit 1
fi

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/build"
ln -s "$binary" "$work/build/penumbra"
ln -s "$repo/examples" "$work/examples"
ln -s "$repo/bench" "$work/bench"
cd "$work"

failed=0
for entry in "${to_run[@]}"; do
  where="${entry%%$'\t'*}"
  line="${entry#*$'\t'}"
  command="build/penumbra ${line#*build/penumbra }"  # a doc's own xvfb-run prefix gives way to ours
  prefix=""
  case "$command" in
    *" --help"* | "build/penumbra devices"* | "build/penumbra inspect "*) extra="" ;;
    "build/penumbra view "*)
      if ! command -v xvfb-run >/dev/null; then echo "skipped (no xvfb-run): $command"; continue; fi
      prefix="xvfb-run -a -s '-screen 0 640x480x24'"
      extra="--width 64 --height 48 --frames 2 --validate" ;;
    "build/penumbra bench "*) extra="--width 64 --height 48 --warmup 1 --validate --frames 2" ;;
    "build/penumbra compare "*) extra="--width 64 --height 48 --rays 2 --stability-frames 2 --validate" ;;
    *) extra="--width 64 --height 48 --validate" ;;
  esac
  # The doc's own size, frame counts, rays and --validate give way to the small ones above.
  shrunk="$(sed -E 's/ --(width|height|frames|warmup|rays|stability-frames) [0-9]+//g; s/ --validate//g' <<<"$command")"
  if ! output="$(eval "$prefix $shrunk $extra" 2>&1 </dev/null)"; then
    echo "$where: command failed: $command" >&2
    echo "$output" >&2
    failed=$((failed + 1))
  fi
done
[ "${#to_run[@]}" -gt 0 ] || { echo "no build/penumbra command found in the docs" >&2; exit 1; }
echo "docs: ${#to_run[@]} commands ran ($failed failed), $templates templates, $excepted listed exceptions"
[ "$failed" -eq 0 ]
