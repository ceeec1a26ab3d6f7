#!/bin/bash
# Runs on the lent GPU machine from the repository root of the copy there: tools/gpu-unpack
# first (its first run on a GPU), the hand-written preamble if it fails before the work starts.
set -u
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
date -u
rm -f /tmp/inner_started
tools/gpu-unpack .gl/ci.tar.xz -- bash .gl/inner3.sh; rc=$?
echo "gpu-unpack rc=$rc"
if [ ! -e /tmp/inner_started ]; then
  echo "gpu-unpack did not start the work: manual preamble"
  R=$PWD
  if [ "$R" != /work/main ]; then mkdir -p /work; [ -e /work/main ] || ln -s "$R" /work/main; fi
  B=/work/main/build/ci
  mkdir -p $B && tar -C $B -xJf .gl/ci.tar.xz || { echo "unpack failed"; exit 1; }
  export LD_LIBRARY_PATH=$B/packed-lib VK_ADD_LAYER_PATH=$B/packed-layers
  export __EGL_VENDOR_LIBRARY_FILENAMES=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
  icd=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
  [ -f $icd ] && export VK_DRIVER_FILES=$icd
  cd /work/main && bash .gl/inner3.sh
fi
tar czf "$OUT/r3.tgz" -C /tmp report report.log extra 2>/dev/null
date -u
