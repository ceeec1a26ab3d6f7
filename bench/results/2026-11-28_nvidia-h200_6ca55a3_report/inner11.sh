#!/bin/bash
set -u
export MASAV_CACHE_DIR=/tmp/mcache
B=/work/main/build/ci
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; $B/masav --version; nproc; date -u
timeout 380 tools/gpu-report --build-dir $B --jobs 16 --step-limit 90 --out /tmp/report > /tmp/report.log 2>&1; echo "gpu-report rc=$?"
tail -50 /tmp/report.log
date -u
mkdir -p /tmp/report/extra
for b in cuda vulkan; do
  timeout 60 $B/masav bench sph --backend $b --particles 1024,8192 --integrators euler,rk4 --skip-error --json /tmp/report/extra/sph_small_$b.json > /tmp/report/extra/sph_small_$b.txt 2>&1; echo "small $b rc=$?"; grep -E 'ms|launch' /tmp/report/extra/sph_small_$b.txt | tail -12
done
date -u
