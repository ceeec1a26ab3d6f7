#!/bin/bash
set -u
export MASAV_CACHE_DIR=/tmp/mcache
B=/work/main/build/ci; L=/tmp/r7; mkdir -p $L
xz -dc .gl/masav_base_ci.xz > /tmp/masav_base; chmod +x /tmp/masav_base
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; $B/masav --version; /tmp/masav_base --version; date -u
for k in 1 2; do
  for v in base new; do
    bin=$B/masav; [ $v = base ] && bin=/tmp/masav_base
    timeout 100 $bin bench sph --backend vulkan --preset dambreak --particles 32768,1048576 --integrators euler,leapfrog --skip-error > $L/dambreak_${v}_$k.txt 2>&1
    echo "dambreak $v $k"; grep -E "^  vulkan " $L/dambreak_${v}_$k.txt
  done
done
for k in 1 2; do
  for v in base new; do
    bin=$B/masav; [ $v = base ] && bin=/tmp/masav_base
    timeout 100 $bin sph --backend vulkan --preset dambreak --pressure dfsph --particles 1048576 --steps 48 > $L/dfsph_${v}_$k.txt 2>&1
    echo "dfsph $v $k"; tail -1 $L/dfsph_${v}_$k.txt
  done
done
date -u
