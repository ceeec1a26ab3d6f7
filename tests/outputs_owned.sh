#!/usr/bin/env bash
# outputs_owned.sh MASAV WORKDIR SCENE ARGS...
# A run owns its output directory (engine/io/run_outputs.h), for `run` (SCENE rendered with ARGS),
# `sph --out` and `export`: a second, shorter run into a directory holding an earlier run's
# numbered files is refused, naming them and --overwrite, and changes nothing; with --overwrite
# only the new run's files remain, with a manifest listing them; a foreign file survives, and a
# link named like a frame is removed itself, never what it points to. An interrupted run's
# manifest says so.
set -u
m=$1 work=$2 scene=$3
shift 3
rm -rf "$work"
mkdir -p "$work"
fails=0
fail() { printf 'FAIL: %s\n' "$1"; [[ $# -gt 1 ]] && printf '%s\n' "$2"; fails=$((fails + 1)); }
count() { ls "$1" 2>/dev/null | grep -cE "$2"; }
# plant DIR NAME: a foreign file, and a link named NAME pointing at a file outside DIR.
plant() {
  echo keep >"$1/notes.txt"
  echo precious >"$work/target_$2"
  ln -s "$work/target_$2" "$1/$2"
}
# kept DIR NAME: the foreign file and the link's target are whole; the link is gone.
kept() {
  [[ "$(cat "$1/notes.txt" 2>/dev/null)" == keep ]] || fail "$1: the foreign file was removed"
  [[ "$(cat "$work/target_$2" 2>/dev/null)" == precious ]] || fail "$1: the link $2 was followed"
  [[ -L "$1/$2" ]] && fail "$1: the stale link $2 is still there"
}
# refused WHAT PATTERN LOG RC: the refusal names the earlier files, their pattern and the flag.
refused() {
  [[ $4 -ne 0 && $4 -lt 128 ]] || fail "$1 into an earlier run's directory: exit $4" "$3"
  grep -q "files of an earlier run (.*$2" <<<"$3" || fail "$1: the refusal names no '$2'" "$3"
  grep -q -- "--overwrite" <<<"$3" || fail "$1: the refusal does not name --overwrite" "$3"
}
manifest_lists() {  # DIR N PATTERN: complete, N files of PATTERN listed with sizes
  local f=$1/manifest.json
  [[ -f $f ]] || { fail "$1: no manifest.json" "$(ls -A "$1")"; return; }
  grep -q '"complete": true' "$f" || fail "$1: the manifest says incomplete" "$(cat "$f")"
  [[ $(python3 -c 'import json, re, sys
m = json.load(open(sys.argv[1]))
print(sum(1 for f in m["files"] if re.fullmatch(sys.argv[2], f["name"]) and f["bytes"] > 0))' "$f" "$3") -eq $2 ]] ||
    fail "$1: the manifest does not list $2 files of $3" "$(cat "$f")"
}

# --- run: 30 frames, then 5.
R=$work/run
log=$("$m" run "$scene" --no-video "$@" --frames 30 --out "$R" 2>&1) || fail "run 30 frames" "$log"
[[ $(count "$R" '^frame_[0-9]{5}\.png$') -eq 30 ]] || fail "run: 30 frames not written" "$(ls "$R")"
plant "$R" frame_00040.png
before=$(ls -A "$R" | md5sum)
log=$("$m" run "$scene" --no-video "$@" --frames 5 --out "$R" 2>&1)
refused "run" 'frame_\*\.png' "$log" $?
[[ $(ls -A "$R" | md5sum) == "$before" ]] || fail "run: a refused run changed the directory" "$(ls -A "$R")"
log=$("$m" run "$scene" --no-video "$@" --frames 5 --out "$R" --overwrite 2>&1) || fail "run --overwrite" "$log"
frames=$(ls "$R" | grep -E '^frame_' | tr '\n' ' ')
[[ $frames == "frame_00000.png frame_00001.png frame_00002.png frame_00003.png frame_00004.png " ]] ||
  fail "run --overwrite: frames left: $frames"
manifest_lists "$R" 5 'frame_[0-9]{5}\.png'
grep -q '"command": "run"' "$R/manifest.json" || fail "run: the manifest names no command"
kept "$R" frame_00040.png
# Interrupted: the manifest says so, and lists the frames written.
"$m" run "$scene" --no-video "$@" --frames 100000 --out "$R" --overwrite >"$work/int.log" 2>&1 &
pid=$!
# Frame 10: past the 5 the run before left (removed first), so this run is rendering.
for _ in $(seq 400); do [[ -f "$R/frame_00010.png" ]] && break; sleep 0.05; done
kill -INT $pid
wait $pid
rc=$?
[[ $rc -eq 130 ]] || fail "run interrupted: exit $rc" "$(cat "$work/int.log")"
grep -q '"complete": false' "$R/manifest.json" && grep -q '"ended": "interrupted"' "$R/manifest.json" ||
  fail "run interrupted: the manifest does not say so" "$(cat "$R/manifest.json")"
n=$(count "$R" '^frame_[0-9]{5}\.png$')
[[ $(grep -c '"name": "frame_' "$R/manifest.json") -eq $n ]] ||
  fail "run interrupted: $n frames, the manifest lists others" "$(cat "$R/manifest.json")"

# --- sph --out with --vtp-every: 30 steps, then 5.
S=$work/sph
sph=(sph --backend cpu --particles 300 --vtp-every 1 --out "$S" -q)
log=$("$m" "${sph[@]}" --steps 30 2>&1) || fail "sph 30 steps" "$log"
[[ $(count "$S" '^water_[0-9]{6}\.vtp$') -eq 31 ]] || fail "sph: 31 snapshots not written" "$(ls "$S")"
plant "$S" water_000040.vtp
before=$(ls -A "$S" | md5sum)
log=$("$m" "${sph[@]}" --steps 5 2>&1)
refused "sph" 'water_\*\.vtp' "$log" $?
[[ $(ls -A "$S" | md5sum) == "$before" ]] || fail "sph: a refused run changed the directory" "$(ls -A "$S")"
log=$("$m" "${sph[@]}" --steps 5 --overwrite 2>&1) || fail "sph --overwrite" "$log"
snaps=$(ls "$S" | grep -E '^water_' | tr '\n' ' ')
[[ $snaps == "water_000000.vtp water_000001.vtp water_000002.vtp water_000003.vtp water_000004.vtp water_000005.vtp " ]] ||
  fail "sph --overwrite: snapshots left: $snaps"
manifest_lists "$S" 6 'water_[0-9]{6}\.vtp'
kept "$S" water_000040.vtp

# --- export: frame 3, then frame 1.
E=$work/export
exp=(export "$scene" --backend cpu "$@" --out "$E")
log=$("$m" "${exp[@]}" --frame 3 2>&1) || fail "export frame 3" "$log"
plant "$E" particles_frame00009.vtp
log=$("$m" "${exp[@]}" --frame 1 2>&1)
refused "export" 'particles_frame\*\.vtp' "$log" $?
[[ -f "$E/particles_frame00003.vtp" && ! -f "$E/particles_frame00001.vtp" ]] ||
  fail "export: a refused export changed the directory" "$(ls -A "$E")"
log=$("$m" "${exp[@]}" --frame 1 --overwrite 2>&1) || fail "export --overwrite" "$log"
[[ $(ls "$E" | grep -E '_frame' | tr '\n' ' ') == "particles_frame00001.vtp " ]] ||
  fail "export --overwrite: frames left" "$(ls -A "$E")"
manifest_lists "$E" 1 'particles_frame00001\.vtp'
kept "$E" particles_frame00009.vtp

[[ $fails -eq 0 ]] && echo "outputs owned: all checks passed"
exit $((fails > 0))
