#!/bin/bash
set -u
export MASAV_CACHE_DIR=/tmp/mcache MASAV_REQUIRE_BACKENDS=cpu,vulkan,cuda
B=/work/main/build/ci; L=/tmp/r6; mkdir -p $L
xz -dc .gl/masav_base_ci.xz > /tmp/masav_base; chmod +x /tmp/masav_base
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; $B/masav --version; /tmp/masav_base --version; date -u
ab() {  # $1 tag, rest: bench args
  local tag=$1; shift
  for k in 1 2; do
    for v in base new; do
      local bin=$B/masav; [ $v = base ] && bin=/tmp/masav_base
      timeout 90 $bin bench sph "$@" --skip-error > $L/${tag}_${v}_$k.txt 2>&1
      echo "$tag $v $k"; grep -E "^  (vulkan|cuda) " $L/${tag}_${v}_$k.txt
    done
  done
}
ab sph --backend vulkan --particles 32768,1048576 --integrators euler,leapfrog
date -u
timeout 300 ctest --test-dir $B -R "^kernels\." -j 8 --output-on-failure > $L/ctest_kernels.log 2>&1; echo "ctest kernels rc=$?"
grep -E "tests passed|tests failed|Test +#|\*\*\*" $L/ctest_kernels.log | tail -20
date -u
