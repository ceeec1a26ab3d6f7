#!/bin/sh
# version_is_head.sh MASAV SOURCE_DIR: `masav --version` names the commit the binary was built
# from (git describe, at build time), not the one its build directory was configured at.
m=$1 src=$2
want=$(git -C "$src" describe --always --tags 2>/dev/null) || {
  echo "SKIPPED: $src is not a git checkout"
  exit 77
}
got=$("$m" --version) || { echo "FAILED: masav --version exited non-zero"; exit 1; }
case $got in
  *"($want)"* | *"($want-dirty)"*) echo "$got" ;;
  *) echo "FAILED: masav --version says '$got'; the checkout is at $want (rebuild?)"; exit 1 ;;
esac
