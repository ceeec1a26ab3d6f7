#!/usr/bin/env bash
# verify_bounds.sh MASAV SCENES_DIR BACKEND [JOBS]
# `masav verify` at the minimum and the maximum of every numeric scene parameter, read from
# `masav schema` (a new parameter is covered without touching this script), at small sizes.
# Each run must pass its cross-check (a correct build never fails it at a legal setting) or
# refuse the setting with a message naming the key, or leave kernels "not compared" (exit 3)
# naming the device limit they exceed and the largest size that fits; never crash or hang. The common tables that no check reads
# (scene, render, camera, run) are swept once, with the particle scene.
set -u
m=$1
scenes=$2
backend=$3
jobs=${4:-2}
common="scene render camera run"  # swept once; `verify` (the check sizes) with every type

# "TYPE TABLE KEY LO HI" for every integer and real parameter of TYPE (tables in $2 skipped).
bounds() {
  "$m" schema "$1" | awk -v skip=" $2 " '
    /^\[/ { table = substr($0, 2, length($0) - 2); next }
    match($0, /\((an integer|a number) in \[[^]]*\]/) {
      r = substr($0, RSTART, RLENGTH); sub(/.*\[/, "", r); sub(/\]$/, "", r)
      split(r, b, ", "); lo = b[1]; hi = b[2]; want = 1; next
    }
    want && /^[a-z_0-9]+ = / {
      want = 0
      if (index(skip, " " table " ") == 0) print table, $1, lo, hi
    }'
}

small_particles=(--set particles.count=3000)
small_atom=(--set atom.count=3000 --set verify.max_points=2048 --set nebula.density_dims=16
  --set scatter.photons=64 --set scatter.rows=200 --set volume.dims=16)
small_sph=(--set sph.count=800 --set verify.max_points=800)

cases=()
while read -r table key lo hi; do cases+=("particles $table.$key $lo $hi"); done < <(bounds particles "")
while read -r table key lo hi; do cases+=("atom-volume $table.$key $lo $hi"); done < <(bounds atom-volume "$common")
while read -r table key lo hi; do cases+=("sph $table.$key $lo $hi"); done < <(bounds sph "$common")

run_case() {
  local type=$1 path=$2 value=$3 small file
  case $type in
    particles) small=("${small_particles[@]}") file=particles.toml ;;
    atom-volume) small=("${small_atom[@]}") file=atom_volume.toml ;;
    sph) small=("${small_sph[@]}") file=sph_water.toml ;;
  esac
  local out rc
  out=$(timeout 120 "$m" verify "$scenes/$file" --backend "$backend" "${small[@]}" \
    --set "$path=$value" --json "" 2>&1)
  rc=$?
  if [[ $rc -eq 0 ]]; then return 0; fi
  if [[ $rc -lt 124 ]]; then
    # Refused, naming the key.
    grep -q "invalid .*${path#*.}" <<<"$out" && ! grep -q "cross-check FAILED" <<<"$out" &&
      return 0
    # A size the device cannot hold: nothing disagrees (exit 3), and every kernel not compared
    # names the limit and what fits (the largest count, or the scene setting).
    local skipped device
    skipped=$(grep -c " not compared: " <<<"$out")
    device=$(grep " not compared: " <<<"$out" |
      grep -Ec "(over this device's|exceeds the) .* per buffer.*(use at most|<= [0-9]+|use fewer)")
    [[ $rc -eq 3 && $skipped -gt 0 && $skipped -eq $device ]] && return 0
  fi
  printf 'FAIL: %s %s=%s (exit %d)\n%s\n' "$type" "$path" "$value" "$rc" \
    "$(grep -E 'FAIL|error|not compared' <<<"$out" | head -5)"
  return 1
}
export -f run_case
export m backend scenes
export small_particles_s="${small_particles[*]}" small_atom_s="${small_atom[*]}" small_sph_s="${small_sph[*]}"

# Two runs (min, max) per parameter, `jobs` at a time.
printf '%s\n' "${cases[@]}" | awk '{ print $1, $2, $3; print $1, $2, $4 }' >"${TMPDIR:-/tmp}/verify_bounds.$$"
n=$(wc -l <"${TMPDIR:-/tmp}/verify_bounds.$$")
failed=$(xargs -P "$jobs" -L 1 bash -c '
  small_particles=($small_particles_s); small_atom=($small_atom_s); small_sph=($small_sph_s)
  run_case "$@" || echo "case failed"' _ <"${TMPDIR:-/tmp}/verify_bounds.$$")
rm -f "${TMPDIR:-/tmp}/verify_bounds.$$"
if [[ -n "$failed" ]]; then
  printf '%s\n' "$failed"
  echo "verify bounds: $(grep -c '^case failed' <<<"$failed") of $n runs failed"
  exit 1
fi
echo "verify bounds: $n runs ($((n / 2)) parameters at min and max) passed on $backend"
