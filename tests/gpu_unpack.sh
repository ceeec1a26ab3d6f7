#!/bin/bash
# gpu_unpack.sh TOOL OUT: tools/gpu-unpack extracts an archive of tools/gpu-pack's shape where its
# CMakeCache.txt says it was built, links the missing source path to the checkout, and runs a
# command with the packed libraries first on LD_LIBRARY_PATH (or prints them as exports); bad
# arguments are refused with exit status 2 and a message.
set -eu
tool=$1 out=$2
rm -rf "$out" && mkdir -p "$out/pack/packed-lib" "$out/pack/packed-layers"
checkout=$(cd "$(dirname "$tool")/.." && pwd -P)
fail() { echo "FAILED: $*"; exit 1; }
printf 'CMAKE_CACHEFILE_DIR:INTERNAL=%s\nCMAKE_HOME_DIRECTORY:INTERNAL=%s\n' \
  "$out/built/ci" "$out/elsewhere/src" >"$out/pack/CMakeCache.txt"
printf '#!/bin/sh\necho "packed masav $*"\n' >"$out/pack/masav" && chmod +x "$out/pack/masav"
tar -C "$out/pack" -cJf "$out/fake.tar.xz" .

# shellcheck disable=SC2016  # expanded by the command the tool runs, in its environment
got=$("$tool" "$out/fake.tar.xz" -- sh -c 'echo "$LD_LIBRARY_PATH|$VK_ADD_LAYER_PATH"; "$0"/masav info' "$out/built/ci" 2>"$out/err.txt") ||
  fail "the command did not run: $(cat "$out/err.txt")"
[ -x "$out/built/ci/masav" ] || fail "nothing extracted at the build directory the cache names"
[ "$(cd "$out/elsewhere/src" && pwd -P)" = "$checkout" ] || fail "$out/elsewhere/src does not lead to $checkout"
case "$got" in
  "$out/built/ci/packed-lib"*"|$out/built/ci/packed-layers"*"packed masav info"*) ;;
  *) fail "unexpected environment or output: $got" ;;
esac
"$tool" "$out/fake.tar.xz" --build-dir "$out/other" >"$out/exports.txt" 2>"$out/err.txt" ||
  fail "printing the exports failed: $(cat "$out/err.txt")"
grep -q "^export LD_LIBRARY_PATH=$out/other/packed-lib" "$out/exports.txt" ||
  fail "no LD_LIBRARY_PATH export: $(cat "$out/exports.txt")"
[ -x "$out/other/masav" ] || fail "--build-dir was not used"

refused() {  # refused MESSAGE ARGS...: exit status 2 and the message
  local want=$1 rc=0
  shift
  "$tool" "$@" >"$out/refused.txt" 2>&1 || rc=$?
  [ "$rc" = 2 ] || fail "'$*' exited $rc, not 2"
  grep -q "$want" "$out/refused.txt" || fail "'$*' did not say '$want': $(cat "$out/refused.txt")"
}
refused "no archive given"
refused "no file" "$out/missing.tar.xz"
refused "not a .tar.xz" "$out/pack/CMakeCache.txt"
refused "unknown option '--jobs'" "$out/fake.tar.xz" --jobs 4
tar -C "$out/pack" -cJf "$out/nocache.tar.xz" ./masav
refused "holds no ./CMakeCache.txt" "$out/nocache.tar.xz"
echo "gpu-unpack: extracted where built, source path linked, environment set, bad input refused"
