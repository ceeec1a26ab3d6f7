#!/usr/bin/env bash
# readme_build_dirs.sh SOURCE_DIR
# The commands of the README and docs/*.md name a binary: it must be one that tools/run or
# tools/test builds. Reads the preset each script configures, that preset's binaryDir in
# CMakePresets.json, and checks that the README names `<binaryDir>/masav` for both, and that
# neither the README nor a docs page names another build directory's masav.
set -u
src=$1
fail() { printf 'readme_build_dirs: %s\n' "$1"; exit 1; }
dirs=()
for script in run test; do
  preset=$(grep -Eo 'cmake --preset [a-z]+' "$src/tools/$script" | head -1 | awk '{print $3}')
  [[ -n "$preset" ]] || fail "tools/$script configures no preset"
  dir=$(python3 -c '
import json, sys
presets = {p["name"]: p for p in json.load(open(sys.argv[1]))["configurePresets"]}
p = presets[sys.argv[2]]
while "binaryDir" not in p:
    p = presets[p["inherits"]]
print(p["binaryDir"].replace("${sourceDir}/", ""))' "$src/CMakePresets.json" "$preset") ||
    fail "preset '$preset' of tools/$script is not in CMakePresets.json"
  grep -q "$dir/masav" "$src/README.md" || fail "tools/$script builds $dir/masav; the README never names it"
  dirs+=("$dir")
done
while read -r used; do
  ok=0
  for d in "${dirs[@]}"; do [[ "$used" == "$d/masav" ]] && ok=1; done
  [[ $ok -eq 1 ]] || fail "the README or docs/ run $used, which neither tools/run nor tools/test builds"
done < <(cat "$src/README.md" "$src"/docs/*.md | grep -Eo 'build/[a-z-]+/masav' | sort -u)
echo "README binaries: ${dirs[*]/%//masav} (tools/run, tools/test)"
