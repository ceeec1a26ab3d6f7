#!/bin/bash
set -u
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
tools/gpu-unpack .gl/ci.tar.xz -- bash .gl/inner13.sh; echo "gpu-unpack rc=$?"
tar czf "$OUT/r13.tgz" -C /tmp report report.log 2>/dev/null
