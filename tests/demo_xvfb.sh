#!/usr/bin/env bash
# demo_xvfb.sh MASAV SCRIPT SHOTS_DIR [ARGS...]
# Runs the desktop demo under a virtual X server, driven by SCRIPT, writing its screenshots into
# SHOTS_DIR (which the "demo screenshots" test then inspects). Skips (77) without xvfb-run.
set -u
masav=$1 script=$2 shots=$3
shift 3
if ! command -v xvfb-run >/dev/null; then
  echo "SKIPPED: xvfb-run is not installed (tools/setup installs xvfb and xauth)"
  exit 77
fi
rm -rf "$shots"
mkdir -p "$shots"
cd "$shots" || exit 1
xvfb-run -a -s "-screen 0 1280x800x24" "$masav" demo "$@" --script "$script"
