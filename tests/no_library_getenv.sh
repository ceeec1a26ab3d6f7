#!/bin/sh
# The libraries never read the process environment: only programs (app/, the test mains) do, and
# pass typed options down (app/host_environment.h). Fails listing every library line that calls
# getenv or secure_getenv or reads environ.
# Usage: no_library_getenv.sh SOURCE_DIR
src=${1:?usage: no_library_getenv.sh SOURCE_DIR}
cd "$src" || exit 2
dirs=""
for d in engine compute cuda* registry render api python/src include; do
  [ -d "$d" ] && dirs="$dirs $d"
done
hits=$(grep -rnE '\b(secure_)?getenv\b|\benviron\b' $dirs \
         --include='*.c' --include='*.cc' --include='*.cpp' --include='*.cu' --include='*.cuh' \
         --include='*.h' --include='*.hpp' --include='*.inc')
if [ -n "$hits" ]; then
  echo "FAILED: a library reads the environment (pass the value as an option from app/ instead):"
  echo "$hits"
  exit 1
fi
echo "no library source reads the environment ($dirs )"
