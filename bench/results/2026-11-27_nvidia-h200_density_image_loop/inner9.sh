#!/bin/bash
set -u
export MASAV_CACHE_DIR=/tmp/mcache MASAV_REQUIRE_BACKENDS=cpu,vulkan,cuda
B=/work/main/build/ci; L=/tmp/r9; mkdir -p $L
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; $B/masav --version; date -u
timeout 60 $B/tests/masav_kernel_tests --backend=vulkan -tc="*row*,*loop*,sph_density*,sph_forces*,*dfsph*" > $L/vulkan_sph.log 2>&1; echo "vulkan sph cases rc=$?"; tail -3 $L/vulkan_sph.log
MASAV_VK_SPH_COOP=on timeout 60 $B/tests/masav_kernel_tests --backend=vulkan -tc="*row*,sph_density*,sph_forces*" > $L/vulkan_sph_coop.log 2>&1; echo "vulkan sph coop cases rc=$?"; tail -3 $L/vulkan_sph_coop.log
timeout 40 $B/masav bench sph --backend vulkan --preset dambreak --particles 32768,1048576 --integrators leapfrog --skip-error > $L/bench.txt 2>&1; echo "bench rc=$?"; grep -E "^  vulkan" $L/bench.txt
date -u
