#!/usr/bin/env bash
# README quick start 2: set up, build everything, run every test (ctest), then every check in
# scripts/checks/ in name order (builds and runs of their own: sanitizers, fuzzing, a second OpenCL
# implementation, services). Any failure fails the whole run.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh all
# A unity build (CMake compiles up to 8 of a room's files as one, the heavy headers parsed once per
# batch): 314 s against 551 s here. The sanitizer build is one too. A warning fails this build.
scripts/build.sh -DPHONGCL_BUILD_TESTS=ON -DCMAKE_UNITY_BUILD=ON -DPHONGCL_WERROR=ON
# A private PoCL kernel cache: CI machines may have no writable HOME.
export POCL_CACHE_DIR="${POCL_CACHE_DIR:-$PWD/build/pocl-cache}"
ctest --test-dir build --output-on-failure -j 2

shopt -s nullglob
for check in scripts/checks/*.sh; do
  echo "== ${check#scripts/checks/}"
  start=$SECONDS
  bash "$check"
  echo "== ${check#scripts/checks/}: passed in $((SECONDS - start)) s"
done
