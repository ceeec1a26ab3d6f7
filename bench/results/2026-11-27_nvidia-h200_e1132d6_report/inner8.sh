#!/bin/bash
set -u
export MASAV_CACHE_DIR=/tmp/mcache
B=/work/main/build/ci
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; $B/masav --version; date -u
timeout 300 tools/gpu-report --build-dir $B --jobs 16 --step-limit 90 --out /tmp/report > /tmp/report.log 2>&1; echo "gpu-report rc=$?"
tail -45 /tmp/report.log
date -u
