#!/bin/bash
# Runs on the lent GPU machine from the repository root of the copy there.
set -u
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
R=$PWD
if [ "$R" != /work/main ]; then mkdir -p /work; [ -e /work/main ] || ln -s "$R" /work/main; fi
B=/work/main/build/ci
mkdir -p $B && tar -C $B -xJf .gl/ci.tar.xz || { echo "unpack failed"; exit 1; }
export LD_LIBRARY_PATH=$B/packed-lib VK_ADD_LAYER_PATH=$B/packed-layers MASAV_CACHE_DIR=/tmp/mcache
export __EGL_VENDOR_LIBRARY_FILENAMES=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
icd=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
[ -f $icd ] && export VK_DRIVER_FILES=$icd
M=$B/masav; L=/tmp/r2; mkdir -p $L; cd /work/main
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; $M --version; date -u
T=$B/tests/masav_kernel_tests
MASAV_VK_VALIDATION=1 timeout 130 $T --backend=vulkan "--test-case=*sph*,*SPH*,*dfsph*,*range*" > $L/kernels_vulkan_sph.log 2>&1; echo "vulkan sph/dfsph/range/ranks cases (auto: no wall split) rc=$?"
grep -E "^\[doctest\] (test cases|assertions)" $L/kernels_vulkan_sph.log; grep -m6 -B3 -A3 "ERROR" $L/kernels_vulkan_sph.log | head -30
MASAV_VK_SPH_WALL_SPLIT=on timeout 40 $T --backend=vulkan "--test-case=*over a particle range*" > $L/kernels_vulkan_range_split_on.log 2>&1; echo "range cases with MASAV_VK_SPH_WALL_SPLIT=on rc=$?"; grep -E "^\[doctest\] test cases" $L/kernels_vulkan_range_split_on.log
date -u
for rep in 1 2; do for s in off on; do
  MASAV_VK_SPH_WALL_SPLIT=$s timeout 40 $M bench sph --backend vulkan --particles 32768,1048576 --integrators euler,leapfrog,rk4 --steps 50 --skip-error --json $L/bench_sph_vk_split_${s}_$rep.json > $L/bench_sph_vk_split_${s}_$rep.log 2>&1; echo "bench sph vulkan split=$s rep $rep rc=$?"
done; done
for rep in 1 2; do for s in off on; do
  MASAV_VK_SPH_WALL_SPLIT=$s timeout 40 $M sph --backend vulkan --preset dambreak --pressure dfsph --particles 1048576 --steps 64 > $L/dfsph_1m_vk_split_${s}_$rep.log 2>&1; echo "dfsph 1M vulkan split=$s rep $rep rc=$?: $(grep -E 'steps/s' $L/dfsph_1m_vk_split_${s}_$rep.log | tail -1)"
done; done
timeout 40 $M sph --backend cuda --preset dambreak --pressure dfsph --particles 1048576 --steps 64 > $L/dfsph_1m_cuda.log 2>&1; echo "dfsph 1M cuda rc=$?: $(grep -E 'steps/s' $L/dfsph_1m_cuda.log | tail -1)"
for b in cuda vulkan; do timeout 30 $M sph --backend $b --preset dambreak --pressure dfsph --particles 32768 --steps 400 > $L/dfsph_32k_$b.log 2>&1; echo "dfsph 32k $b rc=$?: $(grep -E 'steps/s' $L/dfsph_32k_$b.log | tail -1)"; done
date -u
NCU=$(command -v ncu || ls /usr/local/cuda/bin/ncu /opt/nvidia/nsight-compute/*/ncu 2>/dev/null | head -1)
echo "ncu: $NCU"
[ -n "$NCU" ] && timeout 90 $NCU --clock-control none -k regex:'density_kernel|forces_kernel' --launch-skip 4 --launch-count 2 --section SpeedOfLight --section Occupancy --section LaunchStats --section MemoryWorkloadAnalysis --section WarpStateStats $M bench sph --backend cuda --particles 1048576 --integrators euler --steps 4 --skip-error > $L/ncu_sph_cuda.txt 2>&1; echo "ncu rc=$?"
grep -E "Duration|Registers Per|Achieved Occupancy|Theoretical Occupancy|Memory Throughput|L1/TEX Hit|L2 Hit|Compute \(SM\) Throughput|density_kernel|forces_kernel" $L/ncu_sph_cuda.txt | head -40
date -u
tar czf $OUT/r2.tgz -C /tmp r2
