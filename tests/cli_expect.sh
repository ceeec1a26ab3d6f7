#!/usr/bin/env bash
# cli_expect.sh ok|fail|either REGEX -- COMMAND...
# Runs COMMAND; checks its exit status (ok = 0, fail = non-zero, either = any) and that its
# output matches REGEX (grep -E): cli_expect_all.sh with one regex.
exec "$(dirname "$0")/cli_expect_all.sh" "$@"
