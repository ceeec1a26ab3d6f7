#!/usr/bin/env bash
# sph_restart.sh MASAV DIR
# `masav sph --restart` continues the run bit for bit on the CPU backend: 200 steps in one go
# against 100 steps with checkpoints every 50, then 100 more from the checkpoint; and a run
# stopped by SIGTERM after its first checkpoint, restarted to the same end time. The last CSV
# rows must be equal, and the checkpoints both runs write at their end (the whole state, every
# value at full precision) byte for byte. And the run is the same whatever it writes on the way.
set -u
masav=$1 dir=$2
rm -rf "$dir"
mkdir -p "$dir"
fail() { printf '%s\n' "$1"; exit 1; }
run() {
  local log
  log=$("$masav" "$@" 2>&1)
  local rc=$?
  [[ $rc -eq 0 ]] || fail "$(printf 'masav %s failed (exit %d):\n%s' "$*" "$rc" "$log")"
  printf '%s\n' "$log"
}
scene=(sph --backend cpu --preset dambreak --particles 1000)

# Split at step 100 (the README's commands).
run "${scene[@]}" --steps 200 --csv "$dir/A.csv" --checkpoint-dir "$dir/A" -q >/dev/null
run "${scene[@]}" --steps 100 --csv "$dir/A1.csv" --checkpoint-every 50 --checkpoint-dir "$dir/D" -q \
  | grep -q "checkpoint $dir/D/checkpoint.masav: step 100," || fail "no checkpoint at step 100"
log=$(run sph --backend cpu --restart "$dir/D" --steps 100 --csv "$dir/B.csv" -q)
run sph --backend cpu --restart "$dir/D" --steps 100 --csv "$dir/B2.csv" --checkpoint-dir "$dir/B" -q >/dev/null
cmp "$dir/A/checkpoint.masav" "$dir/B/checkpoint.masav" || fail "the states at step 200 differ"
grep -q "resumed from $dir/D/checkpoint.masav (written by masav .*): step 100" <<<"$log" \
  || fail "no resume line: $log"
[[ "$(tail -n 1 "$dir/A.csv")" == "$(tail -n 1 "$dir/B.csv")" ]] \
  || fail "$(printf 'step 200 differs:\n%s\n%s' "$(tail -n 1 "$dir/A.csv")" "$(tail -n 1 "$dir/B.csv")")"
[[ "$(head -n 2 "$dir/B.csv" | tail -n 1)" == "$(sed -n 102p "$dir/A.csv")" ]] \
  || fail "the restart's first row is not step 100's"
ls "$dir/D" | grep -qv '^checkpoint.masav$' && fail "files besides checkpoint.masav in $dir/D"

# What is written on the way does not move the adaptive dt's blocks: the same state at step 200
# without a CSV, with a row every step (A) and with a row and a checkpoint every 3 and 50 steps.
run "${scene[@]}" --steps 200 --checkpoint-dir "$dir/N" -q >/dev/null
cmp "$dir/A/checkpoint.masav" "$dir/N/checkpoint.masav" || fail "a CSV row every step changed the run"
run "${scene[@]}" --steps 200 --csv "$dir/N3.csv" --diag-every 3 --checkpoint-every 50 \
  --checkpoint-dir "$dir/N3" -q >/dev/null
cmp "$dir/N/checkpoint.masav" "$dir/N3/checkpoint.masav" || fail "rows every 3 steps changed the run"

# A checkpoint directory another process holds is refused, naming it, before any step.
mkdir -p "$dir/L"
(exec 9>"$dir/L/.masav.lock" && flock 9 && exec sleep 30) &
holder=$!
for _ in $(seq 100); do flock -n "$dir/L/.masav.lock" true || break; sleep 0.05; done
log=$("$masav" "${scene[@]}" --steps 10 --checkpoint-dir "$dir/L" -q 2>&1) && fail "locked --checkpoint-dir accepted: $log"
kill $holder
wait $holder 2>/dev/null
grep -q -- "--checkpoint-dir.*'$dir/L' is in use by another masav process" <<<"$log" ||
  fail "locked --checkpoint-dir: $log"
[[ -e "$dir/L/checkpoint.masav" ]] && fail "a checkpoint written into a locked directory"
# The same directory for --out and --checkpoint-dir is one lock, held once.
run "${scene[@]}" --steps 10 --vtp-every 10 --out "$dir/O" --checkpoint-dir "$dir/O" -q >/dev/null
[[ -e "$dir/O/checkpoint.masav" ]] || fail "no checkpoint in the shared --out directory"

# Killed after the first checkpoint: SIGTERM stops it at a step boundary with a checkpoint.
end=(--time 0.4)
run "${scene[@]}" "${end[@]}" --csv "$dir/T.csv" --checkpoint-dir "$dir/T" -q >/dev/null
"$masav" "${scene[@]}" "${end[@]}" --csv "$dir/K1.csv" --checkpoint-every 20 --checkpoint-dir "$dir/K" -q \
  >"$dir/killed.log" 2>&1 &
pid=$!
for _ in $(seq 600); do
  [[ -e "$dir/K/checkpoint.masav" ]] && break
  sleep 0.05
done
kill -TERM "$pid" 2>/dev/null
wait "$pid"
rc=$?
# 130: interrupted (the usual case); 0: it finished before the signal came.
[[ $rc -eq 130 || $rc -eq 0 ]] || fail "$(printf 'killed run: exit %d\n%s' "$rc" "$(cat "$dir/killed.log")")"
if [[ $rc -eq 130 ]]; then
  grep -q "interrupted after step" "$dir/killed.log" || fail "no interrupt message"
  grep -q "checkpoint $dir/K/checkpoint.masav: step" "$dir/killed.log" || fail "no checkpoint at the interrupt"
fi
run sph --backend cpu --restart "$dir/K" "${end[@]}" --csv "$dir/K2.csv" --checkpoint-dir "$dir/K2" -q >/dev/null
cmp "$dir/T/checkpoint.masav" "$dir/K2/checkpoint.masav" || fail "the restarted run's end state differs"
[[ "$(tail -n 1 "$dir/T.csv")" == "$(tail -n 1 "$dir/K2.csv")" ]] \
  || fail "$(printf 'the restarted run ends elsewhere:\n%s\n%s' "$(tail -n 1 "$dir/T.csv")" "$(tail -n 1 "$dir/K2.csv")")"

# Killed hard (SIGKILL: no checkpoint at the stop, perhaps a half-written temporary file): the
# restart goes on from the last whole checkpoint, at most 20 steps back, to the same end.
"$masav" "${scene[@]}" "${end[@]}" --csv "$dir/H1.csv" --checkpoint-every 20 --checkpoint-dir "$dir/H" -q \
  >"$dir/hard.log" 2>&1 &
pid=$!
for _ in $(seq 600); do
  [[ -e "$dir/H/checkpoint.masav" ]] && break
  sleep 0.05
done
kill -KILL "$pid" 2>/dev/null
wait "$pid" 2>/dev/null  # without bash's "Killed" line
hard=$?
run sph --backend cpu --restart "$dir/H" "${end[@]}" --csv "$dir/H2.csv" --checkpoint-dir "$dir/H2" -q >/dev/null
cmp "$dir/T/checkpoint.masav" "$dir/H2/checkpoint.masav" || fail "the run restarted after SIGKILL ends elsewhere"
echo "restart: bit for bit (SIGTERM run exit $rc, SIGKILL run exit $hard)"
exit 0
