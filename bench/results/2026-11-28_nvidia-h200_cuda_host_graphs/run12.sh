#!/bin/bash
set -u
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
tools/gpu-unpack .gl/ci.tar.xz -- bash .gl/inner12.sh; echo "gpu-unpack rc=$?"
tar czf "$OUT/r12.tgz" -C /tmp r12 2>/dev/null
