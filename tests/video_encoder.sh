#!/usr/bin/env bash
# video_encoder.sh MASAV SCENES_DIR WORK_DIR: `masav run` encodes its MP4 through ffmpeg without a
# shell and with a time limit. With a fake ffmpeg first on PATH:
#  - one that hangs is killed after --video-timeout; the run warns, exits 0 with its frames
#    whole, and releases its output lock (a second run into the same directory starts at once);
#  - one that exits 3 is reported as "exit status 3" (not a raw wait status such as 768);
#  - one that records its arguments gets an output directory with a quote and a `$(...)` in its
#    name as one argument, verbatim (no shell reads it).
set -u
[[ $# -eq 3 ]] || { echo "usage: video_encoder.sh MASAV SCENES_DIR WORK_DIR"; exit 2; }
m=$1 scenes=$2 work=$3
rm -rf "$work"
mkdir -p "$work/bin"
fail() { echo "FAILED: $*"; exit 1; }
run() {  # run OUT [extra args]: 2 small frames of the particles scene on the CPU
  local out=$1; shift
  "$m" run "$scenes/particles.toml" --frames 2 --backend cpu --no-verify \
       --set particles.count=2000 --set render.width=64 --set render.height=48 --out "$out" "$@"
}
fake() { printf '#!/usr/bin/env bash\n%s\n' "$1" >"$work/bin/ffmpeg"; chmod +x "$work/bin/ffmpeg"; }
export PATH=$work/bin:$PATH

# 1. A hung encoder.
fake 'exec sleep 600'
start=$(date +%s)
out=$(timeout 120 bash -c "$(declare -f run); m='$m' scenes='$scenes'; run '$work/hang' --video-timeout 1" 2>&1)
rc=$?
took=$(( $(date +%s) - start ))
echo "$out" | tail -3
[[ $rc -eq 0 ]] || fail "the run with a hung ffmpeg exited $rc (124: it hung)"
grep -q "ffmpeg could not encode the video (killed after 1 s" <<<"$out" || fail "no time-limit warning"
[[ -f "$work/hang/frame_00001.png" ]] || fail "the frames are not complete"
[[ $took -lt 60 ]] || fail "the run took $took s"
pgrep -f "sleep 600" >/dev/null && { pkill -f "sleep 600"; fail "the hung ffmpeg was left running"; }
fake 'exit 0'
out=$(run "$work/hang" --no-video --overwrite 2>&1) || fail "a second run into the same directory (lock held?) failed: $out"
echo "after the hang, a second run into $work/hang: ok"

# 2. A failing encoder.
fake 'exit 3'
out=$(run "$work/exit3" 2>&1) || fail "the run with a failing ffmpeg exited non-zero: $out"
grep -q "ffmpeg could not encode the video (exit status 3)" <<<"$out" ||
  fail "ffmpeg's exit was not reported as 'exit status 3': $(grep ffmpeg <<<"$out")"
echo "a failing ffmpeg: exit status 3 reported"

# 3. Arguments verbatim.
fake 'printf "%s\n" "$@" >"'"$work"'/args.txt"; for a; do last=$a; done; echo mp4 >"$last"'
odd="$work/it's \$(touch pwned)"
out=$(run "$odd" 2>&1) || fail "the run into '$odd' failed: $out"
grep -qxF "$odd/frame_%05d.png" "$work/args.txt" || { cat "$work/args.txt"; fail "the input pattern was not passed verbatim"; }
[[ ! -e pwned && ! -e "$work/pwned" ]] || fail "a shell ran the output name"
[[ -f "$odd/particles.mp4" ]] || fail "the video was not renamed into place: $(ls "$odd")"
echo "the output directory reached ffmpeg verbatim; video written"
echo "video_encoder: all passed"
