#!/bin/bash
set -u
touch /tmp/inner_started
export MASAV_CACHE_DIR=/tmp/mcache
B=$PWD/build/ci; [ -x $B/masav ] || B=/work/main/build/ci
M=$B/masav; L=/tmp/extra; mkdir -p $L
echo "in $PWD, build $B"; env | grep -E "^(LD_LIBRARY_PATH|VK_|__EGL)" 
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; $M --version; nproc; date -u
timeout 330 tools/gpu-report --build-dir $B --jobs 16 --step-limit 90 --out /tmp/report > /tmp/report.log 2>&1; echo "gpu-report rc=$?"
tail -45 /tmp/report.log
date -u
for b in cuda vulkan; do for n in 32768 1048576; do
  s=400; [ $n -gt 100000 ] && s=64
  for q in on off on off; do
    MASAV_DFSPH_QUEUE=$q timeout 40 $M sph --backend $b --preset dambreak --pressure dfsph --particles $n --steps $s > $L/dfsph_${b}_${n}_$q.log 2>&1
    echo "dfsph $b $n queue=$q rc=$?: $(grep -E 'steps/s' $L/dfsph_${b}_${n}_$q.log | tail -1) | $(grep -E 'residual reads' $L/dfsph_${b}_${n}_$q.log | tail -1)"
  done; done; done
date -u
