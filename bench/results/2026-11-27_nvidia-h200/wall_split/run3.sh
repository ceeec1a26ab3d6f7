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
M=$B/masav; L=/tmp/r3; mkdir -p $L; cd /work/main
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; $M --version; date -u
T=$B/tests/masav_kernel_tests
MASAV_VK_VALIDATION=1 timeout 110 $T --backend=vulkan "--test-case=*sph*,*SPH*,*dfsph*,*range*" > $L/kernels_vulkan_sph.log 2>&1; echo "vulkan sph/dfsph/range/ranks cases (auto: density split, precise) rc=$?"
grep -E "^\[doctest\] (test cases|assertions)" $L/kernels_vulkan_sph.log; grep -m6 -B3 -A3 "ERROR" $L/kernels_vulkan_sph.log | head -30
date -u
for s in auto off auto off; do
  MASAV_VK_SPH_WALL_SPLIT=$s timeout 30 $M bench sph --backend vulkan --particles 32768,1048576 --integrators euler,leapfrog,rk4 --steps 50 --skip-error --json $L/bench_sph_vk_split_${s}_$SECONDS.json > /dev/null 2>&1; echo "bench sph vulkan split=$s rc=$?"
done
date -u
tar czf $OUT/r3.tgz -C /tmp r3
