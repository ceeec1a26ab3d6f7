#!/bin/bash
set -u
export MASAV_CACHE_DIR=/tmp/mcache
B=/work/main/build/ci
date -u
timeout 320 tools/gpu-report --build-dir $B --jobs 16 --step-limit 90 --out /tmp/report > /tmp/report.log 2>&1; echo "gpu-report rc=$?"
grep -E 'FAILED|steps failed|met, ' /tmp/report.log | head; tail -3 /tmp/report.log
date -u
