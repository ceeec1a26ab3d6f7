#!/usr/bin/env bash
# atom_clip_shade.sh MASAV WORKDIR
# `masav atom --clip/--shade` reach its raymarch: the same small state rendered without them, with
# a plane that keeps the whole box (x:0:above), with one that removes it (x:1:above), and shaded.
# The whole-box clip leaves the image byte-equal, the empty one and the shading change it, and the
# cloud image (not raymarched) never changes.
set -u
m=$1
work=$2
rm -rf "$work"
mkdir -p "$work"
fails=0
fail() { printf 'FAIL: %s\n' "$1"; [[ $# -gt 1 ]] && printf '%s\n' "$2"; fails=$((fails + 1)); }
render() {  # NAME [FLAGS...]
  local name=$1
  shift
  out=$("$m" atom --state state3 --particles 3000 --backend cpu --photons 16 --dims 16 \
    --density-dims 16 --width 32 --height 32 --out "$work/$name" "$@" 2>&1) ||
    fail "atom $*: exit status" "$out"
}
render plain
render keep_all --clip x:0:above
render keep_none --clip x:1:above
render shaded --shade --shade-specular 0.5
cmp -s "$work/plain/raymarch.png" "$work/keep_all/raymarch.png" ||
  fail "--clip x:0:above changed the image"
cmp -s "$work/plain/raymarch.png" "$work/keep_none/raymarch.png" &&
  fail "--clip x:1:above left the image as it was"
cmp -s "$work/plain/raymarch.png" "$work/shaded/raymarch.png" &&
  fail "--shade left the image as it was"
for v in keep_none shaded; do
  cmp -s "$work/plain/cloud.png" "$work/$v/cloud.png" || fail "$v changed cloud.png"
done
out=$("$m" atom --state state3 --clip y:0.5:left --out "$work/bad" 2>&1) &&
  fail "--clip y:0.5:left was accepted" "$out"
grep -q "masav atom: invalid --clip side = left" <<<"$out" || fail "--clip side message" "$out"
[[ -e "$work/bad" ]] && fail "a refused --clip still made the output directory"
if ((fails)); then
  printf '%d check(s) failed\n' "$fails"
  exit 1
fi
echo "atom clip and shade: all checks passed"
