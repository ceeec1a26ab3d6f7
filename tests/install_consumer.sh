#!/usr/bin/env bash
# install_consumer.sh BUILD_DIR SOURCE_DIR WORK_DIR: the installed package as a user meets it.
#  1. `cmake --install BUILD_DIR --prefix WORK_DIR/prefix` into a fresh prefix;
#  2. examples/consumer, a separate ten-line CMake project, configured with find_package(masav
#     0.2) against the prefix, built and run: it must list cpu (and vulkan where it was built)
#     as available; a request for a version the package is not (9.9) must be refused;
#  3. examples/ as its own project against the prefix, built and two examples run;
#  4. the consumer built with pkg-config alone (`pkg-config --cflags --libs masav`);
#  5. every ```cpp block of docs/library.md with a main() compiled the same way and run.
set -euo pipefail
[[ $# -eq 3 ]] || { echo "usage: install_consumer.sh BUILD_DIR SOURCE_DIR WORK_DIR"; exit 2; }
build=$1 src=$2 work=$3
rm -rf "$work"
mkdir -p "$work"
prefix=$work/prefix
fail() { echo "FAILED: $*"; exit 1; }

cmake --install "$build" --prefix "$prefix" >"$work/install.log" 2>&1 ||
  { cat "$work/install.log"; fail "cmake --install"; }
for f in include/masav/masav.h include/masav/version.h lib/libmasav.a \
         lib/cmake/masav/masavConfig.cmake lib/cmake/masav/masavConfigVersion.cmake \
         lib/cmake/masav/masavTargets.cmake lib/pkgconfig/masav.pc; do
  [[ -f "$prefix/$f" ]] || fail "the install has no $f"
done
echo "installed into $prefix ($(find "$prefix" -type f | wc -l) files)"

gen=()
command -v ninja >/dev/null && gen=(-G Ninja)
configure() {  # configure SRC BIN
  cmake -S "$1" -B "$2" "${gen[@]}" -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release \
        >"$2.log" 2>&1 || { cat "$2.log"; fail "configuring $1 against the prefix"; }
}
built_vulkan=$(grep -c 'MASAV_WITH_VULKAN:BOOL=ON' "$build/CMakeCache.txt" || true)

# 2. The ten-line consumer.
configure "$src/examples/consumer" "$work/consumer"
cmake --build "$work/consumer" >"$work/consumer-build.log" 2>&1 ||
  { cat "$work/consumer-build.log"; fail "building examples/consumer"; }
out=$("$work/consumer/consumer") || fail "examples/consumer exited non-zero: $out"
echo "$out"
grep -q "^masav [0-9.]* (headers [0-9.]*)" <<<"$out" || fail "no version line"
grep -q "^cpu .*built=1 available=1" <<<"$out" || fail "cpu is not available"
if [[ $built_vulkan -gt 0 ]]; then
  grep -q "^vulkan .*built=1" <<<"$out" || fail "vulkan was built but the package lacks it"
  if [[ ",${MASAV_REQUIRE_BACKENDS:-}," == *,vulkan,* ]]; then
    grep -q "^vulkan .*built=1 available=1" <<<"$out" || fail "vulkan is required but not available"
  fi
fi
mkdir -p "$work/too_new"
sed 's/find_package(masav 0.2 /find_package(masav 9.9 /' "$src/examples/consumer/CMakeLists.txt" \
  >"$work/too_new/CMakeLists.txt"
cp "$src/examples/consumer/main.cpp" "$work/too_new/"
if cmake -S "$work/too_new" -B "$work/too_new/build" -DCMAKE_PREFIX_PATH="$prefix" \
     >"$work/too_new.log" 2>&1; then
  fail "find_package(masav 9.9) accepted the installed $(grep -o 'PACKAGE_VERSION "[^"]*"' \
       "$prefix/lib/cmake/masav/masavConfigVersion.cmake")"
fi
echo "find_package(masav 9.9) refused, as it must be"

# 3. The examples as their own project.
configure "$src/examples" "$work/examples"
cmake --build "$work/examples" -j2 >"$work/examples-build.log" 2>&1 ||
  { cat "$work/examples-build.log"; fail "building examples/ against the prefix"; }
(cd "$work" && "$work/examples/example_sort_backends" 5000) || fail "example_sort_backends"
"$work/examples/example_compare_backends_test" || fail "example_compare_backends_test"

# 4. pkg-config alone.
export PKG_CONFIG_PATH=$prefix/lib/pkgconfig
read -r -a pc < <(pkg-config --cflags --libs masav) || fail "pkg-config --cflags --libs masav"
g++ -O1 -o "$work/consumer_pc" "$src/examples/consumer/main.cpp" "${pc[@]}" ||
  fail "g++ with pkg-config's flags: ${pc[*]}"
"$work/consumer_pc" | grep -q "^cpu .*available=1" || fail "the pkg-config build does not run"
echo "pkg-config build runs"

# 5. docs/library.md's snippets.
python3 - "$src/docs/library.md" "$work/snippets" <<'PY'
import os, re, sys
text = open(sys.argv[1]).read()
os.makedirs(sys.argv[2], exist_ok=True)
blocks = [b for b in re.findall(r"```cpp\n(.*?)```", text, re.S) if "int main" in b]
if not blocks:
    sys.exit("FAILED: docs/library.md has no ```cpp block with a main()")
for i, b in enumerate(blocks):
    open(os.path.join(sys.argv[2], f"snippet_{i}.cpp"), "w").write(b)
print(f"{len(blocks)} snippets of docs/library.md")
PY
for f in "$work"/snippets/snippet_*.cpp; do
  exe=${f%.cpp}
  g++ -O1 -o "$exe" "$f" "${pc[@]}" || fail "compiling $(basename "$f") of docs/library.md"
  (cd "$work/snippets" && "$exe") >"$exe.out" 2>&1 || { cat "$exe.out"; fail "running $(basename "$f")"; }
  echo "$(basename "$f"): $(head -c 300 "$exe.out" | tr '\n' ' ')"
done
echo "install_consumer: all passed"
