#!/bin/sh
# gpu_report_summary.sh SCRIPT OUT: tools/gpu_report_summary.py on a GPU-mode report made up
# here. A row of a variant run (CUDA graphs on, Vulkan replays off, RK4 reach masks off, Vulkan
# forces' wall images inside the walk, the forces without the neighbour state) must be paired with the backend's default run of the same
# integrator, particles and timed steps, and must never stand for the backend's throughput in the
# targets or the SPH table.
set -eu
script=$1 out=$2
rm -rf "$out" && mkdir -p "$out"
printf 'mode=gpu\nquick=0\nmachine=fixture-gpu\nbackends=cuda,vulkan\n' >"$out/run.txt"
printf 'bench sph on cuda\tok\t1\tlogs/bench_sph_cuda.log\n' >"$out/steps.tsv"
row() {  # backend integrator particles steps wall_ms graphs host_ms
  printf '{"backend": "%s", "integrator": "%s", "particles": %s, "timed_steps": %s,
    "device_ms_per_step": %s, "wall_ms_per_step": %s, "steps_per_s": %s,
    "particle_steps_per_s": %s, "stage_ms_per_step": {"density": 0.1},
    "per_step": {"launches": 10, "host_syncs": 0.02, "async_reads": 0.12, "graphs": %s,
                 "host_cpu_ms": %s}}' \
    "$1" "$2" "$3" "$4" "$5" "$5" "$(awk -v ms="$5" 'BEGIN { print 1000 / ms }')" \
    "$(awk -v ms="$5" -v n="$3" 'BEGIN { print 1000 / ms * n }')" "$6" "$7"
}
printf '{"benchmark": "sph", "throughput": [%s, %s]}\n' \
  "$(row cuda leapfrog 1048576 50 0.9 0 0.08)" "$(row cuda rk4 1048576 50 3.7 0 0.15)" \
  >"$out/bench_sph_cuda.json"
# The graphs' run is the faster one here: were it taken as the throughput, the targets would say so.
printf '{"benchmark": "sph", "throughput": [%s, %s]}\n' \
  "$(row cuda leapfrog 1048576 50 0.45 0.125 0.06)" "$(row cuda rk4 1048576 64 1.8 0.125 0.1)" \
  >"$out/bench_sph_graphs_cuda.json"
# Vulkan replays by default; its variant run records each block anew (and is faster here too).
printf '{"benchmark": "sph", "throughput": [%s]}\n' \
  "$(row vulkan euler 1024 512 0.12 0.125 0.05)" >"$out/bench_sph_small_vulkan.json"
printf '{"benchmark": "sph", "throughput": [%s]}\n' \
  "$(row vulkan euler 1024 512 0.06 0 0.1)" >"$out/bench_sph_noreplay_small_vulkan.json"
# RK4 with its reach masks off, against the default RK4 run.
printf '{"benchmark": "sph", "throughput": [%s]}\n' \
  "$(row cuda rk4 1048576 50 4.4 0 0.15)" >"$out/bench_sph_noreach_cuda.json"
# Vulkan's forces with the wall images inside the walk, against the default (replayed) run.
printf '{"benchmark": "sph", "throughput": [%s]}\n' \
  "$(row vulkan euler 1048576 50 0.95 0.125 0.02)" >"$out/bench_sph_imagesinside_vulkan.json"
# CUDA's forces over the four arrays instead of the neighbour state, against the default run.
printf '{"benchmark": "sph", "throughput": [%s]}\n' \
  "$(row cuda rk4 1048576 50 3.9 0 0.15)" >"$out/bench_sph_nostate_cuda.json"
printf '{"benchmark": "sph", "throughput": [%s]}\n' \
  "$(row vulkan euler 1048576 50 0.8 0.125 0.02)" >"$out/bench_sph_vulkan.json"
python3 "$script" "$out" >/dev/null
s=$out/summary.md
fail() {
  echo "FAILED: $1"
  cat "$s"
  exit 1
}
grep -q '^| SPH 1,048,576 particles: symplectic (leapfrog) step <= 1 ms | cuda | 0.9 ms/step' "$s" ||
  fail "the leapfrog target is not the kernel-by-kernel run's 0.9 ms"
grep -q '^| SPH 1,048,576 particles: RK4 step <= 4 ms | cuda | 3.7 ms/step' "$s" ||
  fail "the RK4 target is not the kernel-by-kernel run's 3.7 ms"
grep -q '^## Captured blocks' "$s" || fail "no table of captured blocks"
grep -q '^| 1,048,576 | leapfrog | cuda | CUDA graphs | 50 | 0.45 | 0.9 | 0.5 | 0.06 | 0.08 |' "$s" ||
  fail "the leapfrog graph row is not paired with its 50-step run"
grep -q '^| 1,048,576 | rk4 | cuda | CUDA graphs | 64 | 1.8 | - | no run to compare |' "$s" ||
  fail "the 64-step RK4 graph row is paired with a run of another length"
grep -q '^| 1,024 | euler | vulkan | no replays | 512 | 0.06 | 0.12 | 0.5 | 0.1 | 0.05 |' "$s" ||
  fail "the Vulkan run without replays is not paired with its default run"
grep -q '^| 1,048,576 | rk4 | cuda | no reach masks | 50 | 4.4 | 3.7 | 1.19 | 0.15 | 0.15 |' "$s" ||
  fail "the RK4 run without reach masks is not paired with its default run"
grep -q '^| 1,048,576 | euler | vulkan | wall images inside the walk | 50 | 0.95 | 0.8 | 1.19 | 0.02 | 0.02 |' "$s" ||
  fail "the Vulkan run with the wall images inside the walk is not paired with its default run"
grep -q '^| 1,048,576 | rk4 | cuda | no neighbour state | 50 | 3.9 | 3.7 | 1.05 | 0.15 | 0.15 |' "$s" ||
  fail "the CUDA run without the neighbour state is not paired with its default run"
if grep -q '^| 1,048,576 | rk4 | cuda | 3.9 ' "$s"; then
  fail "a row without the neighbour state is listed as SPH throughput"
fi
if grep -q '^| 1,048,576 | euler | vulkan | 0.95 ' "$s"; then
  fail "a row with the wall images inside the walk is listed as SPH throughput"
fi
if grep -q '^| 1,048,576 | rk4 | cuda | 4.4 ' "$s"; then
  fail "a row without reach masks is listed as SPH throughput"
fi
if grep -q '^| 1,048,576 | leapfrog | cuda | 0.45 ' "$s"; then
  fail "a graph row is listed as SPH throughput"
fi
if grep -q '^| 1,024 | euler | vulkan | 0.06 ' "$s"; then
  fail "a row without replays is listed as SPH throughput"
fi
grep -q '^| 1,024 | euler | vulkan | 0.12 ' "$s" || fail "Vulkan's replayed run is not in the SPH table"
echo "gpu_report_summary: variant rows paired, never taken as throughput"
