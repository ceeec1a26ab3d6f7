#!/bin/bash
set -u
export MASAV_CACHE_DIR=/tmp/mcache MASAV_REQUIRE_BACKENDS=cpu,vulkan,cuda
B=/work/main/build/ci; L=/tmp/r4; mkdir -p $L
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; $B/masav --version; date -u
timeout 400 ctest --test-dir $B -R "^kernels\." -j 8 --output-on-failure > $L/ctest_kernels.log 2>&1; echo "ctest kernels rc=$?"
grep -E "tests passed|tests failed|Test +#|\*\*\*" $L/ctest_kernels.log | tail -20
date -u
