#!/usr/bin/env bash
# outputs_safe.sh MASAV WORKDIR
# Outputs that cannot be lost or mixed, driven through the command line:
#  - `sph --csv`: rows are in a partial file as soon as each step ran, moved over the old file
#    when the run ends (SIGINT keeps every completed row and exits 130); a run refused before its
#    first step leaves the old file whole; a write failure stops at that row with the file named
#    (a private full device, and a file size limit standing in for a disk that fills up mid-run);
#  - an output naming a device, a pipe or a link writes through it: the device stays a device,
#    the link a link (private nodes and links in WORKDIR, never the machine's own);
#  - an output directory locked by another process is refused, naming it; a lock file left
#    behind by a dead process is taken over;
#  - `export` and `atom` leave the old set whole when a write fails (a file size limit again);
#  - `atom --out FILE` is refused before any computing.
set -u
m=$1
work=$2
rm -rf "$work"
mkdir -p "$work"
fails=0
fail() { printf 'FAIL: %s\n' "$1"; [[ $# -gt 1 ]] && printf '%s\n' "$2"; fails=$((fails + 1)); }
lines() { wc -l <"$1" | tr -d ' '; }
# Every row of a CSV has as many cells as its header (no half-written row).
complete_rows() { awk -F, 'NR == 1 { n = NF } NF != n { bad = 1 } END { exit bad }' "$1"; }

# --- sph --csv on a full device: fails at the header, before any step; the device stays one.
if mknod "$work/full" c 1 7 2>/dev/null && mknod "$work/null" c 1 3 2>/dev/null; then
  out=$("$m" sph --backend cpu --particles 500 --steps 20 --csv "$work/full" -q 2>&1)
  rc=$?
  [[ $rc -ne 0 && $rc -lt 128 ]] || fail "sph --csv FULL: exit $rc" "$out"
  grep -q "writing '$work/full' failed after 0 rows: No space left on device" <<<"$out" ||
    fail "sph --csv FULL: message" "$out"
  grep -q "steps/s" <<<"$out" && fail "sph --csv FULL: stepped before failing" "$out"
  out=$("$m" verify --backend cpu --set particles.count=500 --json "$work/full" 2>&1)
  rc=$?
  [[ $rc -ne 0 && $rc -lt 128 ]] || fail "verify --json FULL: exit $rc" "$out"
  grep -q "wrote $work/full" <<<"$out" && fail "verify --json FULL: said it wrote" "$out"
  out=$("$m" sph --backend cpu --particles 500 --steps 3 --csv "$work/null" -q 2>&1) ||
    fail "sph --csv NULL" "$out"
  "$m" verify --backend cpu --set particles.count=500 --json "$work/null" >/dev/null 2>&1 ||
    fail "verify --json NULL"
  [[ -c "$work/full" && -c "$work/null" ]] || fail "a device was replaced" "$(ls -la "$work")"
else
  echo "SKIPPED: the private device cases (mknod not permitted here); pipes and links below"
fi
# --- an output through a link replaces the file it names; the link stays a link.
echo old >"$work/real.json"
ln -s real.json "$work/link.json"
"$m" verify --backend cpu --set particles.count=500 --json "$work/link.json" >/dev/null 2>&1 ||
  fail "verify --json LINK"
[[ -L "$work/link.json" ]] || fail "verify --json LINK replaced the link"
grep -q '"kernel"' "$work/real.json" || fail "verify --json LINK: the file it names was not written"
# --- a refused run leaves an existing CSV whole.
"$m" sph --backend cpu --particles 500 --steps 3 --csv "$work/good.csv" -q >/dev/null 2>&1 ||
  fail "sph --csv good.csv"
good=$(md5sum <"$work/good.csv")
out=$("$m" sph --backend cpu --particles 500 --steps 3 --csv "$work/good.csv" --dt nan -q 2>&1) &&
  fail "sph --dt nan accepted" "$out"
[[ $(md5sum <"$work/good.csv") == "$good" ]] || fail "a refused run changed good.csv" "$out"
[[ -z "$(ls -A "$work" | grep masav-partial)" ]] || fail "a partial CSV left" "$(ls -A "$work")"

# --- sph --csv when the file cannot grow past 4 KiB: fails at that row; the rows before stay.
out=$(trap '' XFSZ; ulimit -f 4; "$m" sph --backend cpu --particles 500 --steps 200 --csv "$work/limit.csv" -q 2>&1)
rc=$?
[[ $rc -ne 0 && $rc -lt 128 ]] || fail "sph --csv past the size limit: exit $rc" "$out"
grep -Eq "writing '.*limit.csv' failed after [0-9]+ rows: File too large" <<<"$out" ||
  fail "sph --csv past the size limit: message" "$out"
[[ -f "$work/limit.csv" && $(lines "$work/limit.csv") -gt 2 ]] || fail "sph --csv: rows lost" "$out"

# --- sph --csv interrupted: every completed row is in the file, and the exit says so.
"$m" sph --backend cpu --particles 500 --steps 1000000 --csv "$work/int.csv" -q >"$work/int.log" 2>&1 &
pid=$!
for _ in $(seq 200); do  # the rows go to the partial file until the run ends
  [[ -f "$work/.int.csv.masav-partial" && $(lines "$work/.int.csv.masav-partial") -ge 5 ]] && break
  sleep 0.05
done
kill -INT $pid
wait $pid
rc=$?
[[ $rc -eq 130 ]] || fail "sph interrupted: exit $rc, want 130" "$(cat "$work/int.log")"
grep -q "interrupted after step" "$work/int.log" || fail "sph interrupted: message" "$(cat "$work/int.log")"
[[ $(lines "$work/int.csv") -ge 5 ]] || fail "sph interrupted: rows lost"
complete_rows "$work/int.csv" || fail "sph interrupted: a partial row" "$(tail -3 "$work/int.csv")"
grep -Eq "wrote .*int.csv \(([0-9]+) rows\)" "$work/int.log" || fail "sph interrupted: no summary"

# --- an output directory held by another process is refused, naming it.
small=(--backend cpu --set particles.count=500)
mkdir -p "$work/locked"
(exec 9>"$work/locked/.masav.lock" && flock 9 && exec sleep 30) &
holder=$!
for _ in $(seq 100); do flock -n "$work/locked/.masav.lock" true || break; sleep 0.05; done
out=$("$m" export "${small[@]}" --out "$work/locked" 2>&1)
rc=$?
[[ $rc -ne 0 && $rc -lt 128 ]] || fail "export into a locked directory: exit $rc" "$out"
grep -q "the output directory '$work/locked' is in use by another masav process" <<<"$out" ||
  fail "export into a locked directory: message" "$out"
[[ -z "$(ls "$work/locked")" ]] || fail "export into a locked directory wrote files" "$(ls "$work/locked")"
if "$m" run --help >/dev/null 2>&1; then
  out=$("$m" run --backend cpu --frames 1 --out "$work/locked" 2>&1)
  grep -q "is in use by another masav process" <<<"$out" || fail "run into a locked directory" "$out"
fi
kill $holder
wait $holder 2>/dev/null
# The holder is gone; its lock file (with a dead pid in it) stays and is taken over.
echo 999999999 >"$work/locked/.masav.lock"
out=$("$m" export "${small[@]}" --out "$work/locked" 2>&1) || fail "stale lock not taken over" "$out"
[[ -e "$work/locked/.masav.lock" ]] && fail "lock file left after exit"

# --- export: a write failure (file size limit) leaves the previous set whole.
"$m" export "${small[@]}" --set particles.seed=1 --out "$work/set" >/dev/null 2>&1 ||
  fail "export: first set"
before=$(cd "$work/set" && md5sum -- * | sort)
out=$(trap '' XFSZ; ulimit -f 8; "$m" export --overwrite --backend cpu --set particles.count=20000 \
  --set particles.seed=2 --out "$work/set" 2>&1)
rc=$?
[[ $rc -ne 0 && $rc -lt 128 ]] || fail "export past the size limit: exit $rc" "$out"
grep -q "failed" <<<"$out" || fail "export past the size limit: message" "$out"
after=$(cd "$work/set" && md5sum -- * | sort)
[[ "$before" == "$after" ]] || fail "export: the old set changed" "$before
--- now ---
$after"
[[ -z "$(ls -A "$work/set" | grep -v -E '^(scene.toml|stages.csv|particles_frame00000.vtp|manifest.json)$')" ]] ||
  fail "export: temporary files left" "$(ls -A "$work/set")"

# --- atom: --out naming a file is refused before any computing; a failed write leaves nothing.
touch "$work/afile"
out=$("$m" atom --state state1 --backend cpu --out "$work/afile" 2>&1)
rc=$?
[[ $rc -ne 0 && $rc -lt 128 ]] || fail "atom --out FILE: exit $rc" "$out"
grep -q "'$work/afile' exists and is not a directory" <<<"$out" || fail "atom --out FILE: message" "$out"
grep -q "^atom:" <<<"$out" && fail "atom --out FILE: computed before failing" "$out"
atom_small=(--state state3 --particles 3000 --backend cpu --photons 16 --dims 16 --density-dims 16
  --width 32 --height 32 --no-cache)
out=$(trap '' XFSZ; ulimit -f 8; "$m" atom "${atom_small[@]}" --out "$work/atom" 2>&1)
rc=$?
[[ $rc -ne 0 && $rc -lt 128 ]] || fail "atom past the size limit: exit $rc" "$out"
[[ -z "$(ls -A "$work/atom")" ]] || fail "atom: a partial set" "$(ls -A "$work/atom")"

[[ $fails -eq 0 ]] && echo "outputs safe: all checks passed"
exit $((fails > 0))
