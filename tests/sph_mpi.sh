#!/usr/bin/env bash
# sph_mpi.sh MASAV MPIEXEC DIR
# `mpirun -np N masav sph` against one process on the CPU backend: the state after 200 steps of
# the dam break is the same bit for bit on 1, 2, 3 and 4 ranks (the checkpoints, which hold every
# value at full precision, compared byte for byte) and so are the CSV diagnostics; a checkpoint
# written on 2 ranks continues on 3; a rank killed mid-run loses at most the steps since the last
# checkpoint, and the restart ends at the uninterrupted run's state. The dfsph model's solves
# give the same bits on 2 and 3 ranks too, and continue across rank counts from a checkpoint.
# Other commands are refused on several ranks. A count one process's buffers cannot hold runs on
# 2 ranks. The ranks oversubscribe the machine's cores (as root too: CI).
set -u
masav=$1 mpiexec=$2 dir=$3
[[ -x $mpiexec ]] || { echo "SKIPPED: no MPI launcher at $mpiexec on this machine"; exit 77; }
rm -rf "$dir"
mkdir -p "$dir"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
fail() { printf 'FAIL: %s\n' "$1"; exit 1; }
run() {
  local log rc
  log=$("$@" 2>&1)
  rc=$?
  [[ $rc -eq 0 ]] || fail "$(printf '%s failed (exit %d):\n%s' "$*" "$rc" "$log")"
  printf '%s\n' "$log"
}
scene=(sph --backend cpu --preset dambreak --particles 2000)

run "$masav" "${scene[@]}" --steps 200 --checkpoint-dir "$dir/P1" --csv "$dir/P1.csv" -q >/dev/null
run "$masav" "${scene[@]}" --steps 200 --checkpoint-dir "$dir/Q1" -q >/dev/null
for n in 2 3 4; do
  log=$(run "$mpiexec" -np $n "$masav" "${scene[@]}" --steps 200 --checkpoint-dir "$dir/P$n" -q)
  grep -q " x $n ranks" <<<"$log" || fail "no ranks in the header on $n ranks: $log"
  grep -qE "^ +$((n - 1)) +[0-9]+ +[0-9]+ " <<<"$log" || fail "no rank table on $n ranks: $log"
  grep -qE "^ranks: .*; exchanges staged through host memory \(this MPI is (not )?CUDA-aware" \
    <<<"$log" || fail "no exchange path on $n ranks: $log"
  cmp "$dir/Q1/checkpoint.masav" "$dir/P$n/checkpoint.masav" \
    || fail "the state after 200 steps on $n ranks differs from one process's"
  printf '%d ranks: the same state as one process\n%s\n' $n "$(grep -A$((n + 1)) '^ranks:' <<<"$log")"
done
run "$mpiexec" -np 3 "$masav" "${scene[@]}" --steps 200 --csv "$dir/P3.csv" -q \
  --vtp-every 100 --out "$dir/V3" >/dev/null
cmp "$dir/P1.csv" "$dir/P3.csv" || fail "the CSV diagnostics on 3 ranks differ from one process's"
# Snapshots: a piece per rank and the index naming them, every particle in one piece.
for tag in 000000 000100 000200; do
  index="$dir/V3/dambreak_$tag.pvtp"
  [[ -f $index ]] || fail "no $index"
  total=0
  for r in 0 1 2; do
    grep -q "<Piece Source=\"dambreak_${tag}_r$r.vtp\"/>" "$index" || fail "$index lacks piece $r"
    points=$(grep -o 'NumberOfPoints="[0-9]*"' "$dir/V3/dambreak_${tag}_r$r.vtp" | grep -o '[0-9]*')
    [[ -n "$points" ]] || fail "no piece $r of step $tag"
    total=$((total + points))
  done
  [[ $total -eq 2000 ]] || fail "the pieces of step $tag hold $total particles, not 2000"
done

# A checkpoint written on 2 ranks at step 100, continued on 3 ranks to step 200.
run "$mpiexec" -np 2 "$masav" "${scene[@]}" --steps 100 --checkpoint-every 50 \
  --checkpoint-dir "$dir/R2" -q >/dev/null
run "$mpiexec" -np 3 "$masav" sph --backend cpu --restart "$dir/R2" --steps 100 \
  --checkpoint-dir "$dir/R3" -q >/dev/null
cmp "$dir/Q1/checkpoint.masav" "$dir/R3/checkpoint.masav" \
  || fail "2 ranks, then 3 from the checkpoint, differ from one process"

# A rank killed after the first checkpoint (every 50 steps, of 4000): mpirun stops the run; the
# restart from the last checkpoint ends at the uninterrupted run's step 200.
"$mpiexec" -np 2 "$masav" "${scene[@]}" --steps 4000 --checkpoint-every 50 \
  --checkpoint-dir "$dir/K" >"$dir/K.log" 2>&1 &
job=$!
for _ in $(seq 600); do grep -q "wrote checkpoint" "$dir/K.log" && break; sleep 0.05; done
grep -q "wrote checkpoint" "$dir/K.log" || { kill $job; fail "no checkpoint before the kill"; }
victim=$(pgrep -f -n -- "--checkpoint-dir $dir/K") || fail "no rank process to kill"
kill -9 "$victim"
wait $job && fail "the run with a killed rank exited 0"
log=$(run "$masav" sph --backend cpu --restart "$dir/K" --steps 1 -q --checkpoint-dir "$dir/K1")
step=$(sed -n 's/^resumed from .*: step \([0-9]*\),.*/\1/p' <<<"$log")
[[ -n "$step" && $step -ge 50 && $step -le 4000 ]] || fail "no resume step: $log"
if [[ $step -le 200 ]]; then
  run "$mpiexec" -np 2 "$masav" sph --backend cpu --restart "$dir/K" --steps $((200 - step)) \
    --checkpoint-dir "$dir/K2" -q >/dev/null
  cmp "$dir/Q1/checkpoint.masav" "$dir/K2/checkpoint.masav" \
    || fail "the restart after the killed rank differs from the uninterrupted run"
fi
printf 'killed rank: restarted from step %s\n' "$step"

# dfsph: the solves' kernels over each rank's own particles, halos from their owners, the
# residual summed over the ranks: the state after 40 steps is one process's on 2 and 3 ranks,
# and 20 steps on 2 ranks, then 20 on 3 from the checkpoint, end there too.
dfsph=(sph --backend cpu --preset dambreak --particles 2000 --pressure dfsph)
run "$masav" "${dfsph[@]}" --steps 40 --checkpoint-dir "$dir/D1" -q >/dev/null
for n in 2 3; do
  run "$mpiexec" -np $n "$masav" "${dfsph[@]}" --steps 40 --checkpoint-dir "$dir/D$n" -q >/dev/null
  cmp "$dir/D1/checkpoint.masav" "$dir/D$n/checkpoint.masav" \
    || fail "the dfsph state after 40 steps on $n ranks differs from one process's"
done
run "$mpiexec" -np 2 "$masav" "${dfsph[@]}" --steps 20 --checkpoint-dir "$dir/DR2" -q >/dev/null
run "$mpiexec" -np 3 "$masav" sph --backend cpu --restart "$dir/DR2" --steps 20 \
  --checkpoint-dir "$dir/DR3" -q >/dev/null
cmp "$dir/D1/checkpoint.masav" "$dir/DR3/checkpoint.masav" \
  || fail "dfsph on 2 ranks, then 3 from the checkpoint, differs from one process"
printf 'dfsph: the same state as one process on 2 and 3 ranks, and across a restart\n'

# The simulation's own checks stop every rank at one step: the CFL guard (a fixed dt the flow
# outgrows) ends one process and 3 ranks at the same step, and the ranks write the last good
# state together, a piece each holding every particle once.
guard=(sph --backend cpu --preset dambreak --particles 2000 --steps 3000 --dt 0.00035
  --cfl-guard stop -q)
log1=$("$masav" "${guard[@]}" --out "$dir/G1" 2>&1) && fail "the guard did not stop one process"
log3=$("$mpiexec" -np 3 "$masav" "${guard[@]}" --out "$dir/G3" 2>&1) && fail "the guard did not stop 3 ranks"
stop1=$(grep -o "last good state (step [0-9]*)" <<<"$log1")
stop3=$(grep -o "last good state (step [0-9]*)" <<<"$log3")
[[ -n "$stop1" && "$stop1" == "$stop3" ]] || fail "3 ranks stopped at '$stop3', one process at '$stop1'"
total=0
for r in 0 1 2; do
  points=$(grep -o 'NumberOfPoints="[0-9]*"' "$dir/G3/dambreak_last_good_r$r.vtp" | grep -o '[0-9]*')
  [[ -n "$points" ]] || fail "no last good piece of rank $r"
  total=$((total + points))
done
[[ $total -eq 2000 ]] || fail "the last good pieces hold $total particles, not 2000"
grep -q 'Source="dambreak_last_good_r2.vtp"' "$dir/G3/dambreak_last_good.pvtp" \
  || fail "no last good index"
printf '3 ranks stopped by the guard at the %s, as one process\n' "$stop3"

# Refusals, naming what runs on several ranks.
log=$("$mpiexec" -np 2 "$masav" info 2>&1) && fail "info on 2 ranks accepted"
grep -q "only \`masav sph\` runs on several ranks" <<<"$log" || fail "no refusal of info: $log"
# A rank's buffers hold its share and its halos, not every particle: with buffers of 1 MiB
# (65,536 positions), 90,000 particles are refused in one process and run on 2 ranks.
big=(sph --backend vulkan --preset dambreak --particles 90000 --steps 2 -q
     --tune vulkan.max_buffer_mib=1)
log=$("$masav" "${big[@]}" 2>&1) && fail "90,000 particles in 1 MiB buffers"
grep -q "particles = 90000 .*at most 65536 on" <<<"$log" || fail "no refusal naming the limit: $log"
log=$(run "$mpiexec" -np 2 "$masav" "${big[@]}")
grep -qE "^ +1 +[0-9]+ +[0-9]+ +[0-9.]+% +[0-9]+ " <<<"$log" || fail "no rank table: $log"
printf '90,000 particles on 2 ranks with 1 MiB buffers:\n%s\n' "$(grep -A3 '^ranks:' <<<"$log")"
echo "sph_mpi: ok"
