#!/usr/bin/env bash
# demo_open_volume.sh MASAV OUT_DIR [DEMO ARGS...]
# Opening volume files in the demo (ctest cli.demo_open_volume): writes an 8x8x8 raw volume and an
# NRRD of the same data, then drives the demo under Xvfb (demo_xvfb.sh) to open the raw file, a
# raw file shorter than its dims, the NRRD with a raw-only option, a file that does not exist, and
# the NRRD, then drops two files as GLFW's drop callback would (the last, a copy of the NRRD,
# opens). Each refusal must read word for word as `masav volume` words it for the same file and
# options; the demo must keep running and quit with status 0. Skips (77) without xvfb-run.
set -u
masav=$1 out=$2
shift 2
here=$(cd "$(dirname "$0")" && pwd)
data=$out.data
rm -rf "$data"
mkdir -p "$data"
# 8x8x8 uint8, x fastest: a ramp along x and y, brighter with z.
for ((z = 0; z < 8; ++z)); do
  for ((y = 0; y < 8; ++y)); do
    for ((x = 0; x < 8; ++x)); do printf "\\$(printf '%03o' $((x * 8 + y * 8 + z * 16)))"; done
  done
done >"$data/ramp.raw"
head -c 100 "$data/ramp.raw" >"$data/short.raw"
{
  printf 'NRRD0004\ntype: uint8\ndimension: 3\nsizes: 8 8 8\nencoding: raw\n\n'
  cat "$data/ramp.raw"
} >"$data/ramp.nrrd"
cp "$data/ramp.nrrd" "$data/dropped.nrrd"
cat >"$data/script.txt" <<SCRIPT
wait 2
open $data/ramp.raw dims=8,8,8 type=uint8
wait 2
screenshot raw.png
open $data/short.raw dims=8,8,8 type=uint8
wait 1
screenshot kept.png
open $data/ramp.nrrd dims=8,8,8
open $data/missing.nrrd
open $data/ramp.nrrd
wait 2
screenshot nrrd.png
drop $data/missing.nrrd $data/dropped.nrrd
wait 2
screenshot dropped.png
quit
SCRIPT
demo_out=$("$here/demo_xvfb.sh" "$masav" "$data/script.txt" "$out" "$@" 2>&1)
rc=$?
printf '%s\n' "$demo_out"
echo "demo exit status $rc"
[[ $rc -eq 0 ]] || exit "$rc"
# The refusals, as `masav volume` words them for the same file and options.
same_as_cli() {
  local file=$1
  shift
  local cli
  cli=$("$masav" volume "$file" "$@" --backend cpu --out "$data/cli" 2>&1 | sed -n 's/^masav: error: //p')
  if [[ -n "$cli" ]] && grep -Fqx -- "masav demo: cannot open $file: $cli" <<<"$demo_out"; then
    echo "same message as masav volume: $(basename "$file")"
  else
    echo "the demo's refusal of $file differs from masav volume's: '$cli'"
  fi
}
same_as_cli "$data/short.raw" --dims 8,8,8 --type uint8
same_as_cli "$data/ramp.nrrd" --dims 8,8,8
same_as_cli "$data/missing.nrrd"
