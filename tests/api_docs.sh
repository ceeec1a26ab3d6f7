#!/usr/bin/env bash
# api_docs.sh DOXYFILE OUT_DIR: builds the API reference of include/masav/ with Doxygen and fails
# on any warning (an undocumented public symbol, a broken reference). Without doxygen (Debian
# `doxygen`, which tools/setup installs) it exits 77, skipped, saying so.
set -u
[[ $# -eq 2 ]] || { echo "usage: api_docs.sh DOXYFILE OUT_DIR"; exit 2; }
doxyfile=$1 out=$2
if ! command -v doxygen >/dev/null; then
  echo "skipped: doxygen is not installed (apt-get install doxygen; tools/setup installs it)"
  exit 77
fi
mkdir -p "$out"
log="$out/warnings.log"
rm -f "$log"
(cd "$out" && doxygen "$doxyfile" >"$out/doxygen.out" 2>&1) || {
  echo "FAILED: doxygen exited non-zero:"; cat "$out/doxygen.out"; exit 1; }
if [[ -s "$log" ]]; then
  echo "FAILED: doxygen warned ($(wc -l <"$log") lines):"
  cat "$log"
  exit 1
fi
[[ -f "$out/html/index.html" ]] || { echo "FAILED: no $out/html/index.html"; exit 1; }
echo "API reference: $out/html/index.html ($(ls "$out/html" | wc -l) files), no warnings"
