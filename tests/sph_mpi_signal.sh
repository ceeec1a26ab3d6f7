#!/usr/bin/env bash
# sph_mpi_signal.sh MASAV MPIEXEC DIR
# A signal on any rank is the run's interrupt: SIGTERM sent to rank 1 alone (not to mpirun)
# ends `mpirun -np 2 masav sph` as SIGTERM to rank 0 does -- every rank stops at one step, the
# checkpoint of that step is written, rank 0 prints the "interrupted" line, and mpirun exits 130
# (and every rank exits 130, as rank 0 does).
set -u
masav=$1 mpiexec=$2 dir=$3
[[ -x $mpiexec ]] || { echo "SKIPPED: no MPI launcher at $mpiexec on this machine"; exit 77; }
rm -rf "$dir"
mkdir -p "$dir"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
fails=0
fail() { printf 'FAIL: %s\n' "$1"; [[ $# -gt 1 ]] && printf '%s\n' "$2"; fails=$((fails + 1)); }
# One block of 64 steps after the start's CSV row: the run's only poll of the interrupt flag is
# before it, so a signal during it is the case the ranks used to disagree on (rank 0's counted,
# another rank's was lost and mpirun exited 0).
scene=(sph --backend cpu --preset dambreak --particles 8000 --steps 64 --block-steps 64
  --diag-every 64 -q)
declare -A status
for rank in 0 1; do
  d=$dir/r$rank
  "$mpiexec" -np 2 "$masav" "${scene[@]}" --csv "$d.csv" --checkpoint-dir "$d" >"$d.log" 2>&1 &
  job=$!
  partial=$dir/.r$rank.csv.masav-partial  # rows reach it as the steps end: the run is stepping
  for _ in $(seq 400); do
    [[ -f $partial && $(wc -l <"$partial") -ge 2 ]] && break  # the header and step 0's row
    sleep 0.05
  done
  sleep 0.1  # past the poll right after that row (immediate), well inside the block (~1 s idle)
  # The rank's own process (mpirun's command line names the directory too, but not its rank).
  pid=""
  for p in $(pgrep -f -- "--checkpoint-dir $d"); do
    grep -qz "^OMPI_COMM_WORLD_RANK=$rank\$" "/proc/$p/environ" 2>/dev/null && pid=$p
  done
  if [[ -z $pid ]]; then
    fail "rank $rank: no process found" "$(cat "$d.log")"
    kill $job
    wait $job
    continue
  fi
  kill -TERM "$pid" || fail "rank $rank: the run ended before the signal (too fast for this test)"
  wait $job
  status[$rank]=$?
  log=$(cat "$d.log")
  [[ ${status[$rank]} -eq 130 ]] || fail "SIGTERM on rank $rank: mpirun exited ${status[$rank]}, want 130" "$log"
  grep -q "^masav: interrupted after step [0-9]*;" <<<"$log" ||
    fail "SIGTERM on rank $rank: no 'interrupted' line" "$log"
  [[ $(grep -c "interrupted after step" <<<"$log") -eq 1 ]] ||
    fail "SIGTERM on rank $rank: the 'interrupted' line is not printed once" "$log"
  [[ -s $d/checkpoint.masav ]] || fail "SIGTERM on rank $rank: no checkpoint" "$log"
  grep -q "^checkpoint .*checkpoint.masav: step [0-9]*," <<<"$log" ||
    fail "SIGTERM on rank $rank: the checkpoint is not reported" "$log"
  printf 'SIGTERM on rank %s: exit %s, %s\n' "$rank" "${status[$rank]}" \
    "$(grep -o 'interrupted after step [0-9]*' <<<"$log")"
done
[[ $fails -eq 0 ]] && echo "sph_mpi_signal: ok"
exit $((fails > 0))
