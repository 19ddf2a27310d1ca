# tests/docs/run_doc_commands.sh's reader of one Markdown file (awk -v doc=NAME; mawk is enough).
# Prints "FILE<TAB>LINE<TAB>KIND<TAB>TEXT" for each piece of code:
#   sh        a command line of a ```sh or ```bash block (continuations joined, comment dropped)
#   text      a line of a ```text block (a command there is checked too)
#   unlabelled  a fence without a language (the test refuses it)
#   inline    an inline code span (one that wraps over lines is joined)
function flush(   text, i, n, run, close_at, span, line) {
  text = para
  i = 1
  n = length(text)
  while (i <= n) {
    if (substr(text, i, 1) != "`") { i++; continue }
    run = 1
    while (substr(text, i + run, 1) == "`") run++
    close_at = find_run(text, i + run, run)
    if (close_at == 0) { i += run; continue }
    span = substr(text, i + run, close_at - i - run)
    line = para_start + count_newlines(substr(text, 1, i))
    gsub(/\n/, " ", span)
    gsub(/  +/, " ", span)
    gsub(/^ +| +$/, "", span)
    print doc "\t" line "\tinline\t" span
    i = close_at + run
  }
  para = ""
}
function find_run(text, from, run,   j, k) {
  for (j = from; j <= length(text); j++) {
    if (substr(text, j, 1) != "`") continue
    k = 1
    while (substr(text, j + k, 1) == "`") k++
    if (k == run) return j
    j += k - 1
  }
  return 0
}
function count_newlines(s,   m) { m = gsub(/\n/, "", s); return m }
/^ *```/ {
  if (!inside) {
    flush()
    inside = 1
    lang = $0
    sub(/^ *```/, "", lang)
    gsub(/ /, "", lang)
    if (lang == "") print doc "\t" NR "\tunlabelled\t"
    pending = ""
  } else inside = 0
  next
}
inside && (lang == "sh" || lang == "bash") {
  line = $0
  if (pending == "") pending_line = NR
  if (line ~ /\\$/) { sub(/\\$/, "", line); pending = pending line; next }
  line = pending line
  pending = ""
  sub(/(^|[ \t])#.*$/, "", line)    # a comment (none of the docs' commands quotes a #)
  sub(/^ +/, "", line); sub(/ +$/, "", line)
  gsub(/  +/, " ", line)            # a continuation's indent
  if (line == "" || line ~ /^#/) next
  print doc "\t" pending_line "\tsh\t" line
  next
}
inside && lang == "text" { line = $0; sub(/^ +/, "", line); sub(/[ \t]+#.*$/, "", line); print doc "\t" NR "\ttext\t" line; next }
inside { next }
/^ *$/ || /^#/ || /^ *\|/ || /^<!--/ {
  flush()
  if ($0 ~ /^#/ || $0 ~ /^ *\|/) { para_start = NR; para = $0; flush() }
  next
}
{ if (para == "") { para_start = NR; para = $0 } else para = para "\n" $0 }
END { flush() }
