#!/usr/bin/env bash
# README quick start 1: set up, build, and shade the bundled default scene with the OpenCL kernel.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh core
scripts/build.sh -DPHONGCL_BUILD_TESTS=OFF -DPHONGCL_BUILD_BENCH=OFF
mkdir -p out
build/phongcl shade --scene scenes/default/scene.json --out out/default.exr --png out/default.png
