#!/usr/bin/env bash
# The CPU raymarch's eight-lane march is compiled for AVX2 inside one file; every symbol that file
# lets the rest of the program bind to (global or weak: an inline header function the linker may
# pick from it) must stay baseline x86-64, or a CPU without AVX2 would fault outside the lanes.
# Usage: cpu_lanes_isa.sh LIBMASAV_CPU.a. Exit 77 (skipped) where the build has no AVX2 march.
set -euo pipefail
lib=$1
if [[ ! -f $lib ]]; then
  # tools/gpu-pack carries programs, not static libraries; the check ran where it was built.
  echo "skipped: $lib is not here (a build packed by tools/gpu-pack has no static libraries)"
  exit 77
fi
member=cpu_raymarch_lanes.cpp.o
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"
ar x "$lib" "$member"
avx='%ymm|[[:space:]]v(mov|add|mul|sub|div|sqrt|cvt|xor|and|or|perm|insert|extract|shuf|unpck|blend|max|min|cmp|broadcast|gather|pxor|padd|psub|pmul)'
march8=$(nm --defined-only "$member" | awk '$3 ~ /march8/ {print $3}' | head -1)
if [[ -z "$march8" ]]; then
  echo "skipped: this build has no AVX2 lane march (not GCC on x86-64)"
  exit 77
fi
# The check can see AVX: the eight-lane entry point itself is full of it.
objdump -d --no-show-raw-insn --disassemble="$march8" "$member" >march8.s
if ! grep -qE "$avx" march8.s; then
  echo "FAIL: no AVX instruction found in $march8: the check cannot see what it looks for"
  exit 1
fi
bad=0
checked=0
while read -r sym; do
  checked=$((checked + 1))
  objdump -d --no-show-raw-insn --disassemble="$sym" "$member" >sym.s
  if grep -qE "$avx" sym.s; then
    echo "FAIL: AVX instructions in $(echo "$sym" | c++filt), which other files may call"
    bad=1
  fi
done < <(nm --defined-only "$member" | awk '$2 == "T" || $2 == "W" {print $3}')
echo "checked $checked global and weak symbols of $member: $([[ $bad == 0 ]] && echo "baseline only" || echo "AVX found")"
exit $bad
