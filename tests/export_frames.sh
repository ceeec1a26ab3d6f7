#!/usr/bin/env bash
# export_frames.sh MASAV OUT_DIR SCENE ARRAY ARGS...
# `masav export` of a stepped scene at frames 0, 1 and 30: each file is the state after that
# many frames (three different files, the simulated time growing), and the point array is the
# colouring scalar ARRAY.
set -u
masav=$1 out=$2 scene=$3 array=$4
shift 4
rm -rf "$out"
fail() { printf '%s\n' "$1"; [[ -n "${log:-}" ]] && printf -- '--- output ---\n%s\n' "$log"; exit 1; }
declare -A vtp sim
for frame in 0 1 30; do
  log=$("$masav" export "$scene" --frame "$frame" --out "$out/f$frame" "$@" 2>&1) ||
    fail "masav export --frame $frame failed"
  file=$(ls "$out/f$frame"/*_frame$(printf '%05d' "$frame").vtp 2>/dev/null) ||
    fail "no .vtp for frame $frame"
  vtp[$frame]=$file
  sim[$frame]=$(grep -Eo 'simulated time [0-9.e+-]+' <<<"$log" | awk '{print $3}')
  [[ -n "${sim[$frame]}" ]] || fail "frame $frame: no simulated time printed"
  grep -q "Name=\"$array\"" "$file" || fail "frame $frame: no point array named '$array' in $file"
  grep -q 'Name="w"' "$file" && fail "frame $frame: the position's w is exported as 'w'"
  grep -q "point array '$array'" <<<"$log" || fail "frame $frame: the array is not reported"
done
log=""
cmp -s "${vtp[0]}" "${vtp[1]}" && fail "frames 0 and 1 wrote the same particles"
cmp -s "${vtp[1]}" "${vtp[30]}" && fail "frames 1 and 30 wrote the same particles"
awk -v a="${sim[0]}" -v b="${sim[1]}" -v c="${sim[30]}" 'BEGIN { exit !(a == 0 && a < b && b < c) }' ||
  fail "simulated times do not grow from 0: ${sim[0]}, ${sim[1]}, ${sim[30]}"
echo "export frames 0, 1, 30: different files, simulated t = ${sim[0]}, ${sim[1]}, ${sim[30]} s, array '$array'"
