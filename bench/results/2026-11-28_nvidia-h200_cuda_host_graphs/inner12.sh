#!/bin/bash
set -u
export MASAV_CACHE_DIR=/tmp/mcache
B=/work/main/build/ci
R=/tmp/r12; mkdir -p $R
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; $B/masav --version; date -u
MASAV_REQUIRE_BACKENDS=cpu,vulkan,cuda timeout 150 ctest --test-dir $B -R 'kernels.cuda|tools.gpu_pack' --output-on-failure -j4 > $R/ctest.log 2>&1; echo "ctest rc=$?"
grep -E 'tests passed|Failed|ERROR|test cases|assertions' $R/ctest.log | head -20
date -u
for s in water dambreak; do timeout 30 $B/masav verify scenes/sph_$s.toml --backend cuda --reference vulkan --json $R/verify_$s.json > $R/verify_$s.log 2>&1; echo "verify $s rc=$?"; tail -2 $R/verify_$s.log; done
for round in 1 2; do for g in 1 0; do
  MASAV_CUDA_GRAPHS=$g timeout 40 $B/masav bench sph --backend cuda --particles 1024,32768 --integrators euler,rk4 --skip-error --json $R/small_g${g}_$round.json > $R/small_g${g}_$round.txt 2>&1; echo "small g=$g r=$round rc=$?"
  MASAV_CUDA_GRAPHS=$g timeout 40 $B/masav bench sph --backend cuda --particles 1048576 --integrators euler,rk4 --steps 64 --skip-error --json $R/big_g${g}_$round.json > $R/big_g${g}_$round.txt 2>&1; echo "big g=$g r=$round rc=$?"
done; done
for f in $R/small_g*_1.txt $R/big_g*_1.txt; do echo "== $f"; grep -E '^  cuda|per step' $f | cut -c1-200; done
timeout 40 $B/masav bench sph --backend vulkan --particles 1024,32768 --integrators euler --skip-error --json $R/small_vk.json > $R/small_vk.txt 2>&1; echo "vk rc=$?"
date -u
