#!/usr/bin/env bash
# Installs the Debian 12 packages phongcl needs, only those missing (README "Dependencies" says why
# each one is there). Safe to run again; uses sudo when not root.
set -euo pipefail

packages=(
  g++ cmake ninja-build pkg-config                         # toolchain
  pocl-opencl-icd ocl-icd-opencl-dev opencl-headers opencl-clhpp-headers  # OpenCL: PoCL device, loader, C/C++ headers
  libglm-dev libopenexr-dev libpng-dev                     # math, EXR and PNG files
  nlohmann-json3-dev libcli11-dev                          # scene JSON, command line
  libgtest-dev libbenchmark-dev                            # tests and benchmarks
)

missing=()
for package in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" || missing+=("$package")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "phongcl setup: installing ${missing[*]}"
sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
