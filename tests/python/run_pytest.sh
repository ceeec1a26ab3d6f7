#!/usr/bin/env bash
# run_pytest.sh PYTHON MODULE_DIR [MASAV [PYTEST ARGS...]]
# The pytest suite of the Python module (tests/python/): MODULE_DIR holds the package masav as
# the build makes it (build/<preset>/python), MASAV is the command line the suite compares with.
# Exits 77 (ctest: skipped) with the reason when the interpreter, pytest, numpy or the module is
# missing, so a build without Python reports the suite as skipped, never as passed.
set -u
[[ $# -ge 2 ]] || { echo "usage: run_pytest.sh PYTHON MODULE_DIR [MASAV [PYTEST ARGS...]]"; exit 2; }
py=$1 moddir=$2 masav=${3:-}
shift $(( $# < 3 ? $# : 3 ))
here=$(cd "$(dirname "$0")" && pwd)
if ! command -v "$py" >/dev/null 2>&1; then
  echo "skipped: no Python interpreter '$py' (tools/setup installs python3-dev)"
  exit 77
fi
for mod in pytest numpy; do
  if ! "$py" -c "import $mod" 2>/dev/null; then
    echo "skipped: $py cannot import $mod (tools/setup installs python3-$mod)"
    exit 77
  fi
done
if ! compgen -G "$moddir/masav/_masav*.so" >/dev/null; then
  echo "skipped: the module masav is not built in $moddir (MASAV_WITH_PYTHON=OFF, or CMake" \
       "found no pybind11-dev, python3-dev and python3-numpy; tools/setup installs them)"
  exit 77
fi
export PYTHONPATH="$moddir${PYTHONPATH:+:$PYTHONPATH}"
export MASAV_PYTHON_DIR="$moddir" MASAV_CLI="$masav"
# Nothing written into the source tree: no bytecode, no pytest cache.
export PYTHONDONTWRITEBYTECODE=1
exec "$py" -m pytest -q -rs -p no:cacheprovider "$here" "$@"
