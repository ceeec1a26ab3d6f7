#!/usr/bin/env bash
# cli_expect.sh ok|fail|either REGEX -- COMMAND...
# Runs COMMAND; checks its exit status (ok = 0, fail = non-zero, either = any) and that its
# output matches REGEX (grep -E). Prints the output when a check fails.
set -u
want=$1 regex=$2
shift 2
[[ "${1:-}" == "--" ]] && shift
out=$("$@" 2>&1)
rc=$?
fail() { printf '%s\n--- output (exit %d) ---\n%s\n' "$1" "$rc" "$out"; exit 1; }
case "$want" in
  ok) [[ $rc -eq 0 ]] || fail "expected success" ;;
  fail) [[ $rc -ne 0 ]] || fail "expected a non-zero exit" ;;
  either) ;;
  *) echo "cli_expect.sh: unknown expectation '$want'"; exit 2 ;;
esac
[[ $rc -lt 128 ]] || fail "crashed (signal $((rc - 128)))"
grep -Eq -- "$regex" <<<"$out" || fail "output does not match /$regex/"
exit 0
