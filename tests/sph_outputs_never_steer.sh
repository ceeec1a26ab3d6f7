#!/usr/bin/env bash
# sph_outputs_never_steer.sh MASAV SAME_TRAJECTORY DIR
# Reading diagnostics never changes the trajectory: every preset, pressure model and integrator
# (DFSPH with its one integrator), run on the CPU reference with no output on the way and with
# each output option (--csv, --csv with --diag-every, --vtp-every, --checkpoint-every), ends in
# the same state bit for bit. The state compared is the checkpoint each run writes at its end
# (every value at full precision, the step counters and the block schedule with it), compared
# by SAME_TRAJECTORY (tests/sph_same_trajectory.cpp) without the fields a read recomputes. The sizes
# are ones where the CFL guard rejects blocks, which is where outputs used to move the replays.
set -u
masav=$1 same=$2 dir=$3
rm -rf "$dir"
mkdir -p "$dir/state"
failures=0
run() {  # run NAME ARGS...: the run's end state in $dir/NAME/checkpoint.masav
  local name=$1
  shift
  local log
  if ! log=$("$masav" sph --backend cpu -q "$@" --checkpoint-dir "$dir/state/$name" 2>&1); then
    printf 'masav sph %s failed:\n%s\n' "$*" "$log"
    failures=$((failures + 1))
    return 1
  fi
}
combos=0
for preset in water dambreak explosion mud obstacle; do
  for pressure in wcsph thesis dfsph; do
    for integrator in euler symplectic-euler leapfrog rk4; do
      [[ $pressure == dfsph && $integrator != symplectic-euler ]] && continue
      # An incompressible fluid cannot start compressed: no dfsph explosion.
      [[ $preset == explosion && $pressure == dfsph ]] && continue
      # The thesis explosion blows up before step 90 at this size (the watchdog stops it).
      steps=90
      [[ $preset == explosion && $pressure == thesis ]] && steps=60
      case=(--preset "$preset" --pressure "$pressure" --integrator "$integrator"
            --particles 600 --steps "$steps")
      id=${preset}_${pressure}_${integrator}
      run "$id" "${case[@]}" || continue
      run "$id.csv" "${case[@]}" --csv "$dir/$id.csv" || continue
      run "$id.diag" "${case[@]}" --csv "$dir/$id.diag.csv" --diag-every 7 || continue
      run "$id.vtp" "${case[@]}" --vtp-every 13 -o "$dir/$id.vtp.out" || continue
      run "$id.ckpt" "${case[@]}" --checkpoint-every 11 || continue
      for v in csv diag vtp ckpt; do
        if ! what=$("$same" "$dir/state/$id/checkpoint.masav" "$dir/state/$id.$v/checkpoint.masav"); then
          printf '%s: with the %s output, the end state %s\n' "$id" "$v" "$what"
          failures=$((failures + 1))
        fi
      done
      combos=$((combos + 1))
    done
  done
done
[[ $combos -eq 44 ]] || { echo "ran $combos of 44 combinations"; failures=$((failures + 1)); }
[[ $failures -eq 0 ]] || { echo "$failures failures"; exit 1; }
echo "44 runs, each the same bit for bit with --csv, --diag-every, --vtp-every and --checkpoint-every"
