#!/usr/bin/env bash
# The command line honours the cache variables (the libraries take the directory as an option):
# MASAV_CACHE_DIR holds the scattering table, read back on the second run; with it empty the
# table goes below HOME (XDG_CACHE_HOME unset); with neither nothing is cached.
# Usage: cli_cache_dir.sh MASAV WORKDIR
set -u
m=${1:?usage: cli_cache_dir.sh MASAV WORKDIR}
work=${2:?usage: cli_cache_dir.sh MASAV WORKDIR}
rm -rf "$work" && mkdir -p "$work" || exit 2
fail() { echo "FAILED: $*"; exit 1; }
run() {  # run OUT ENV...: a small cpu atom run with XDG_CACHE_HOME unset and ENV (env's words)
  local name=$1
  shift
  env -u XDG_CACHE_HOME "$@" "$m" atom --state state3 --particles 2000 --backend cpu \
    --photons 16 --dims 12 --density-dims 12 --width 32 --height 32 --out "$work/$name" 2>&1
}
out=$(run first MASAV_CACHE_DIR="$work/cache" HOME="$work/home") || fail "first run: $out"
ls "$work"/cache/scatter/*.bin >/dev/null 2>&1 || fail "no table in MASAV_CACHE_DIR: $out"
[ -e "$work/home/.cache" ] && fail "wrote below HOME although MASAV_CACHE_DIR was set"
out=$(run second MASAV_CACHE_DIR="$work/cache" HOME="$work/home") || fail "second run: $out"
grep -q "(from the cache)" <<<"$out" || fail "second run did not read MASAV_CACHE_DIR's table: $out"
out=$(run third MASAV_CACHE_DIR= HOME="$work/home") || fail "third run: $out"
ls "$work"/home/.cache/masav/scatter/*.bin >/dev/null 2>&1 ||
  fail "MASAV_CACHE_DIR empty: no table below HOME/.cache/masav: $out"
out=$(run fourth -u HOME MASAV_CACHE_DIR=) || fail "fourth run: $out"
grep -q "(from the cache)" <<<"$out" && fail "no cache directory named, yet a table was read: $out"
echo "MASAV_CACHE_DIR, then HOME/.cache/masav, then no cache"
