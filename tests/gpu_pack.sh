#!/bin/sh
# gpu_pack.sh TOOL BUILD_DIR OUT: tools/gpu-pack makes an archive of BUILD_DIR whose masav, once
# extracted elsewhere, runs with only the archive's libraries added (debug information gone,
# the CTest files and CMakeCache.txt there).
set -eu
tool=$1 build=$2 out=$3
rm -rf "$out" && mkdir -p "$out/unpacked"
XZ_OPT=-0 "$tool" "$build" "$out/pack.tar.xz" >"$out/pack.log"
tar -C "$out/unpacked" -xJf "$out/pack.tar.xz"
u=$out/unpacked
for f in masav CMakeCache.txt CTestTestfile.cmake tests/CTestTestfile.cmake tests/masav_kernel_tests \
  packed-lib/libfmt.so.9 packed-lib/libvulkan.so.1; do
  [ -e "$u/$f" ] || { echo "FAILED: the archive has no $f"; cat "$out/pack.log"; exit 1; }
done
if readelf -S "$u/masav" | grep -q '\.debug_info'; then
  echo "FAILED: the packed masav still has debug information"
  exit 1
fi
LD_LIBRARY_PATH=$u/packed-lib "$u/masav" info --brief >"$out/info.txt" 2>&1 ||
  { echo "FAILED: the packed masav did not run:"; cat "$out/info.txt"; exit 1; }
grep -E '^cpu +available' "$out/info.txt" >/dev/null ||
  { echo "FAILED: the packed masav lists no CPU backend:"; cat "$out/info.txt"; exit 1; }
echo "gpu-pack: $(du -h "$out/pack.tar.xz" | cut -f1) archive; the packed masav runs"
