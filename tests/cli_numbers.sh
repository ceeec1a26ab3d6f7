#!/usr/bin/env bash
# cli_numbers.sh MASAV DATA_DIR
# Every numeric option of every command (read from its --help) is parsed by one checked rule:
# nan, inf, -inf and 2^64 are refused naming the option; 0 and -0 are refused naming it too, or
# the option's help states what 0 means. Runs `masav --parse-only`, which checks a command line
# without running it.
set -u
m=$1
data=$2
fails=0 checked=0
fail() { printf 'FAIL: %s\n' "$1"; fails=$((fails + 1)); }

# Commands with what each needs besides the option under test.
commands=()
while read -r name _; do
  [[ -n $name ]] && commands+=("$name")
done < <("$m" --help | sed -n '/^Subcommands:/,$p' | tail -n +2)
paths=()
for c in "${commands[@]}"; do
  if [[ $c == bench ]]; then
    while read -r sub _; do [[ -n $sub ]] && paths+=("bench $sub"); done \
      < <("$m" bench --help | sed -n '/^Subcommands:/,$p' | tail -n +2)
  else
    paths+=("$c")
  fi
done
extra_for() {  # extra arguments a command or an option needs
  case "$1" in
    volume) printf '%s\n' "$data/tiny_4x4x4.nrrd" ;;
    mesh) printf '%s\n' "$data/cube.obj" ;;
  esac
  case "$2" in
    --checkpoint-every) printf '%s\n' --checkpoint-dir "${TMPDIR:-/tmp}/cli_numbers_cp" ;;
    --shade-specular) printf '%s\n' --shade ;;
  esac
}

for path in "${paths[@]}"; do
  read -ra words <<<"$path"
  help=$("$m" "${words[@]}" --help)
  # "  [-x,]--name TYPE[...]  description" or the description on the next line.
  while IFS=$'\t' read -r opt desc; do
    mapfile -t extra < <(extra_for "${words[0]}" "$opt")
    for v in nan inf -inf 18446744073709551616 0 -0; do
      checked=$((checked + 1))
      out=$("$m" --parse-only "${words[@]}" "${extra[@]}" "$opt" "$v" 2>&1)
      rc=$?
      if [[ $rc -ne 0 ]]; then
        grep -q -- "$opt" <<<"$out" || fail "$path $opt $v: refused without naming $opt: $out"
        continue
      fi
      case "$v" in
        0 | -0)
          grep -Eq '(^|[^0-9.e])0([^0-9.]|$)|zero' <<<"$desc" ||
            fail "$path $opt $v: accepted, but its help does not say what 0 means: $desc" ;;
        *) fail "$path $opt $v: accepted" ;;
      esac
    done
  done < <(awk '
    function emit() { if (name != "") printf "%s\t%s\n", name, desc; name = "" }
    /^  +(-[a-zA-Z],)?--[a-z0-9-]+ (FLOAT|INT|UINT)/ {
      emit()
      line = $0; sub(/^ +(-[a-zA-Z],)?/, "", line)
      split(line, parts, " "); name = parts[1]
      # CLI11 starts the description at column 31, or on the next line when the option and its
      # type take that room (then the next line is indented: it wins).
      desc = ""
      if (substr($0, 30, 1) == " " && substr($0, 31, 1) != " ") desc = substr($0, 31)
      fresh = 1
      next
    }
    /^  +-/ { emit(); next }
    name != "" && fresh && /^                    +[^ ]/ { d = $0; sub(/^ +/, "", d); desc = d; fresh = 0; next }
    { fresh = 0 }
    END { emit() }' <<<"$help")
done
echo "cli numbers: $checked command lines checked over ${#paths[@]} commands, $fails failures"
exit $((fails > 0))
