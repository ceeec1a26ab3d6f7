#!/usr/bin/env bash
# cli_expect_all.sh ok|fail|either|exit=N REGEX... -- COMMAND...
# Runs COMMAND; checks its exit status (ok = 0, fail = non-zero, either = any, exit=N = N) and that each
# regex (grep -E) matches some line of its output, in any order (tables such as
# `masav run --stats`). Prints the output when a check fails.
set -u
want=$1
shift
regexes=()
while [[ $# -gt 0 && "$1" != "--" ]]; do
  regexes+=("$1")
  shift
done
[[ "${1:-}" == "--" ]] && shift
out=$("$@" 2>&1)
rc=$?
fail() { printf '%s\n--- output (exit %d) ---\n%s\n' "$1" "$rc" "$out"; exit 1; }
case "$want" in
  ok) [[ $rc -eq 0 ]] || fail "expected success" ;;
  fail) [[ $rc -ne 0 ]] || fail "expected a non-zero exit" ;;
  either) ;;
  exit=[0-9]*) [[ $rc -eq ${want#exit=} ]] || fail "expected exit status ${want#exit=}" ;;
  *) echo "cli_expect_all.sh: unknown expectation '$want'"; exit 2 ;;
esac
[[ $rc -lt 128 ]] || fail "crashed (signal $((rc - 128)))"
for r in "${regexes[@]}"; do
  grep -Eq -- "$r" <<<"$out" || fail "output does not match /$r/"
done
exit 0
