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
M=$B/masav; L=/tmp/extra; mkdir -p $L; cd /work/main
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; $M --version; nproc; date -u
timeout 330 tools/gpu-report --build-dir $B --jobs 16 --step-limit 90 --out /tmp/report > /tmp/report.log 2>&1; echo "gpu-report rc=$?"
tail -60 /tmp/report.log
date -u
for b in cuda vulkan; do for n in 32768 1048576; do
  s=200; [ $n -gt 100000 ] && s=64
  for p in dfsph wcsph; do
    timeout 60 $M sph --backend $b --preset dambreak --pressure $p --integrator symplectic-euler --particles $n --steps $s --csv $L/sph_${p}_${b}_$n.csv > $L/sph_${p}_${b}_$n.log 2>&1; echo "sph $p $b $n rc=$?: $(tail -1 $L/sph_${p}_${b}_$n.log)"
  done; done; done
date -u
timeout 150 tools/dfsph-vs-wcsph --masav $M --backends cuda,vulkan --particles 65536 --integrators symplectic-euler,leapfrog --out $L/pm > $L/dfsph_vs_wcsph.log 2>&1; echo "dfsph-vs-wcsph rc=$?"; tail -25 $L/dfsph_vs_wcsph.log
date -u
tar czf $OUT/report.tgz -C /tmp report report.log
tar czf $OUT/extra.tgz -C /tmp extra
