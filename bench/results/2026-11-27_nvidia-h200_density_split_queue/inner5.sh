#!/bin/bash
set -u
export MASAV_CACHE_DIR=/tmp/mcache MASAV_REQUIRE_BACKENDS=cpu,vulkan,cuda
B=/work/main/build/ci; L=/tmp/r5; mkdir -p $L; T=$B/tests/masav_kernel_tests
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; $B/masav --version; date -u
for be in cuda vulkan; do
  timeout 100 $T --backend=$be "--test-case=*sort*,*stop slot*,*do nothing once*,*queues iterations*" > $L/kernels_${be}_mend.log 2>&1; echo "$be rc=$?: $(grep -E '^\[doctest\] test cases' $L/kernels_${be}_mend.log)"
done
timeout 60 $B/masav bench sort --backend all --pairs 16777216 --key-bits 24 --reps 10 > $L/bench_sort_24bit_mend.log 2>&1; echo "bench sort rc=$?"; grep -iE "ms|pairs/s" $L/bench_sort_24bit_mend.log | head -8
date -u
