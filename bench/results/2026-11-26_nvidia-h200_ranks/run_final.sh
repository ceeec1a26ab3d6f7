#!/bin/bash
# Runs on the lent GPU machine, from the repository root of the copy there.
set -u
R=$PWD
if [ "$R" != /work/main ]; then mkdir -p /work; [ -e /work/main ] || ln -s "$R" /work/main; fi
B=/work/main/build/ci
mkdir -p $B && tar -C $B -xJf .devcarry/ci.tar.xz || { echo "unpack failed"; exit 1; }
export LD_LIBRARY_PATH=$B/packed-lib:/work/main/.devcarry/gl VK_ADD_LAYER_PATH=$B/packed-layers MASAV_CACHE_DIR=/tmp/mcache
export __EGL_VENDOR_LIBRARY_FILENAMES=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
icd=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
[ -f $icd ] && export VK_DRIVER_FILES=$icd
M=$B/masav; L=$OUT/logs; mkdir -p $L; cd /work/main
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; $M --version; nproc
(timeout 150 $B/tests/masav_kernel_tests --backend=cuda > $L/kernels_cuda.log 2>&1; echo "kernels.cuda rc=$?") &
(MASAV_VK_VALIDATION=1 timeout 150 $B/tests/masav_kernel_tests --backend=vulkan "--test-case=*sph*,*grid*,*range*" > $L/kernels_vulkan.log 2>&1; echo "kernels.vulkan (sph, grid, ranges, ranks) rc=$?") &
wait
for f in $L/kernels_cuda.log $L/kernels_vulkan.log; do grep -E "^\[doctest\] (test cases|assertions)|^SKIPPED|^backend" $f; grep -m8 -A4 "ERROR\|CRASH" $f; done
for b in cuda vulkan; do timeout 60 $M bench sph --backend $b --particles 32768,1048576 --integrators euler,leapfrog,rk4 --steps 50 --skip-error --json $L/bench_sph_$b.json > $L/bench_sph_$b.log 2>&1; echo "bench sph $b rc=$?"; done
for b in cuda vulkan; do timeout 60 $M sph --backend $b --preset dambreak --particles 1048576 --steps 64 -q > $L/sph_1m_$b.log 2>&1; echo "sph 1M $b rc=$?"; tail -1 $L/sph_1m_$b.log; done
tar czf $OUT/run9.tgz -C $OUT logs; rm -rf $L
