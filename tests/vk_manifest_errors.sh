#!/usr/bin/env bash
# vk_manifest_errors.sh MASAV WORK_DIR: a Vulkan driver manifest named wrongly by the loader's
# variables (VK_ICD_FILENAMES, VK_DRIVER_FILES) is named in masav's message, with the fix,
# instead of the loader's misleading error (a malformed manifest reads as ErrorOutOfHostMemory).
set -u
[[ $# -eq 2 ]] || { echo "usage: vk_manifest_errors.sh MASAV WORK_DIR"; exit 2; }
m=$1 work=$2
rm -rf "$work"
mkdir -p "$work"
fail() { echo "FAILED: $*"; exit 1; }
printf '{not json' >"$work/malformed.json"
printf '{"file_format_version": "1.0.0", "ICD": {"library_path": "/nonexistent/libvulkan_x.so", "api_version": "1.3.0"}}' \
  >"$work/missing_lib.json"
check() {  # check VAR VALUE REGEX
  local out
  out=$(env -u VK_ICD_FILENAMES -u VK_DRIVER_FILES "$1=$2" "$m" check --backend vulkan 2>&1)
  [[ $? -ne 0 ]] || fail "$1=$2: masav check --backend vulkan succeeded"
  grep -qE "$3" <<<"$out" || fail "$1=$2: expected /$3/ in: $out"
  grep -q "ErrorOutOfHostMemory" <<<"$out" && fail "$1=$2: the loader's misleading error is shown"
  echo "$1=$(basename "$2"): $(grep -oE "$3" <<<"$out" | head -1)"
}
check VK_ICD_FILENAMES "$work/malformed.json" "names '.*malformed.json', which is not a Vulkan driver manifest"
check VK_DRIVER_FILES "$work/malformed.json" "VK_DRIVER_FILES names '.*malformed.json', which is not"
check VK_ICD_FILENAMES "$work/missing_lib.json" "whose driver library '/nonexistent/libvulkan_x.so' does not exist"
check VK_ICD_FILENAMES "$work/absent.json" "names '.*absent.json', which does not exist"
echo "vk_manifest_errors: all passed"
