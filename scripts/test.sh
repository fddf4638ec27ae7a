#!/usr/bin/env bash
# README quick start 2: set up, build everything, and run every test (ctest).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
scripts/build.sh -DPHONGCL_BUILD_TESTS=ON
# A private PoCL kernel cache: CI machines may have no writable HOME.
export POCL_CACHE_DIR="${POCL_CACHE_DIR:-$PWD/build/pocl-cache}"
ctest --test-dir build --output-on-failure -j 2
