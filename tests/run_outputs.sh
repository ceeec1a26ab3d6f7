#!/usr/bin/env bash
# run_outputs.sh MASAV OUT_DIR ARGS...
# Runs `masav run ... --out OUT_DIR` and checks what it leaves: every frame as a complete PNG,
# the cross-check report (passed), the resolved scene, no temporary files; an MP4 when ffmpeg
# is on PATH, else the note that there are only frames.
set -u
masav=$1 out=$2
shift 2
rm -rf "$out"
log=$("$masav" run "$@" --out "$out" 2>&1)
rc=$?
fail() { printf '%s\n--- output (exit %d) ---\n%s\n' "$1" "$rc" "$log"; ls -la "$out" 2>&1; exit 1; }
[[ $rc -eq 0 ]] || fail "masav run failed"
frames=$(ls "$out"/frame_*.png 2>/dev/null | wc -l)
want=$(grep -Eo 'wrote [0-9]+ frames' <<<"$log" | grep -Eo '[0-9]+')
[[ -n "$want" && "$frames" -eq "$want" ]] || fail "expected $want frames, found $frames"
for f in "$out"/frame_*.png; do
  [[ "$(head -c 8 "$f" | od -An -tx1 | tr -d ' \n')" == "89504e470d0a1a0a" ]] || fail "$f is not a PNG"
done
grep -q '"pass": true' "$out/verify.json" || fail "verify.json missing or not passed"
grep -q '^\[particles\]' "$out/scene.toml" || fail "scene.toml missing"
if ls -a "$out" | grep -q '\.tmp'; then fail "temporary files left behind"; fi
if command -v ffmpeg >/dev/null; then
  [[ -s "$out/particles.mp4" ]] || fail "ffmpeg is present but no MP4 was written"
else
  grep -q "ffmpeg not found: PNG frames only" <<<"$log" || fail "no note about ffmpeg"
fi
printf '%s\n' "$log"
exit 0
