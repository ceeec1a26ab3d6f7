#!/usr/bin/env bash
# sph_restart_checks.sh MASAV DIR
# A checkpoint whose checksums match but whose time is NaN (issue 45: the run printed
# "t = nan s" and wrote the same CSV row forever) or negative is refused by `masav sph --restart`
# with the field, the value and the allowed range, a non-zero exit, in bounded time, and without
# touching the CSV. The checkpoint is patched here with its STAT section's FNV-1a 64 recomputed
# (format: engine/sph/sph_checkpoint.h), in bash alone.
set -u
masav=$1 dir=$2
rm -rf "$dir"
mkdir -p "$dir"
fail() { printf '%s\n' "$1"; exit 1; }

"$masav" sph --backend cpu --preset water --particles 300 --steps 10 --checkpoint-dir "$dir/D" -q \
  >"$dir/first.log" 2>&1 || fail "$(printf 'the first run failed:\n%s' "$(cat "$dir/first.log")")"
ckpt=$dir/D/checkpoint.masav

u32() { od -An -tu4 -j "$2" -N 4 "$1" | tr -d ' '; }
u64() { od -An -tu8 -j "$2" -N 8 "$1" | tr -d ' '; }
# Writes the 8 bytes of the signed 64-bit value $3 little-endian at offset $2 of file $1.
put64() {
  local v=$3 bytes="" i
  for ((i = 0; i < 8; i++)); do
    bytes+=$(printf '\\x%02x' $(((v >> (8 * i)) & 0xff)))
  done
  printf "$bytes" | dd of="$1" bs=1 seek="$2" conv=notrunc status=none
}
# FNV-1a 64 of $3 bytes at offset $2 of file $1 (bash's 64-bit arithmetic wraps like uint64).
fnv() {
  local h=-3750763034362895579 b  # 0xcbf29ce484222325
  for b in $(od -An -tu1 -v -j "$2" -N "$3" "$1"); do
    h=$(((h ^ b) * 1099511628211))
  done
  printf '%s' "$h"
}

# The sections: header (magic, version, count, writer), then SCEN and STAT, each a 24-byte
# header (tag, 0, payload bytes, checksum) and its payload. STAT's payload: u64 particles, then
# the time (f64).
writer=$(u32 "$ckpt" 16)
scen=$((20 + writer))
stat=$((scen + 24 + $(u64 "$ckpt" $((scen + 8)))))
stat_bytes=$(u64 "$ckpt" $((stat + 8)))
[[ $(u64 "$ckpt" $((stat + 16))) == "$(printf '%u' "$(fnv "$ckpt" $((stat + 24)) "$stat_bytes")")" ]] \
  || fail "the script's FNV-1a 64 does not match the writer's (layout changed?)"

# $1: name, $2: the time's 64 bits as a signed integer, $3: the message expected.
refused() {
  local bad=$dir/$1
  mkdir -p "$bad"
  cp "$ckpt" "$bad/checkpoint.masav"
  put64 "$bad/checkpoint.masav" $((stat + 24 + 8)) "$2"
  put64 "$bad/checkpoint.masav" $((stat + 16)) "$(fnv "$bad/checkpoint.masav" $((stat + 24)) "$stat_bytes")"
  printf 'old rows\n' >"$dir/$1.csv"
  # The issue's command as it was given.
  local log rc
  log=$(cd "$dir" && timeout 60 "$masav" sph --restart "$1" --steps 20 --csv "$1.csv" 2>&1)
  rc=$?
  [[ $rc -ne 124 ]] || fail "$1: still running after 60 s: $log"
  [[ $rc -ne 0 ]] || fail "$1: accepted (exit 0): $log"
  grep -q -- "$3" <<<"$log" || fail "$(printf '%s: no message matching %s:\n%s' "$1" "$3" "$log")"
  grep -q "checkpoint.masav" <<<"$log" || fail "$1: the message does not name the file: $log"
  grep -q "resumed" <<<"$log" && fail "$1: resumed: $log"
  [[ "$(cat "$dir/$1.csv")" == "old rows" ]] || fail "$1: the CSV was touched"
  return 0
}
refused nan_time $((0x7ff8000000000000)) "invalid time = nan; time must be finite"
refused negative_time $((0xbff0000000000000)) "invalid time = -1; time must be finite and in (0, "

# The untouched checkpoint still resumes.
"$masav" sph --backend cpu --restart "$dir/D" --steps 5 -q >"$dir/ok.log" 2>&1 ||
  fail "$(printf 'the intact checkpoint was refused:\n%s' "$(cat "$dir/ok.log")")"
grep -q "resumed from $ckpt" "$dir/ok.log" || fail "no resume line: $(cat "$dir/ok.log")"
exit 0
