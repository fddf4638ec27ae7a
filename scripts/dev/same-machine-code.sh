#!/usr/bin/env bash
# Compares the machine code PoCL generates for a scene's kernel with a baseline phongcl's and
# build/phongcl's: each shades the scene once with a fresh PoCL cache, the work-group function's
# shared object is disassembled, and the instructions are compared with addresses taken out.
#
#   scripts/dev/same-machine-code.sh BASELINE_PHONGCL [SCENE_JSON [SHADE_OPTION...]]
#
# Default scene: scenes/large (its G-buffer ray-cast first). Prints both instruction counts and the
# differing lines; exits non-zero when they differ.
set -euo pipefail
cd "$(dirname "$0")/../.."
base=${1:?usage: $0 BASELINE_PHONGCL [SCENE_JSON [SHADE_OPTION...]]}
scene=${2:-scenes/large/scene.json}
shift $(($# < 2 ? $# : 2))
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
gbuffer=$(dirname "$scene")/gbuffer.exr
if [ ! -f "$gbuffer" ]; then
  gbuffer="$work/gbuffer.exr"
  build/phongcl gbuffer --scene "$scene" --out "$gbuffer" > /dev/null
fi

# instructions BINARY NAME: NAME.s, the work-group function's instructions without addresses.
instructions() {
  local binary=$1 name=$2 so
  shift 2
  POCL_CACHE_DIR="$work/pocl-$name" PHONGCL_CACHE_DIR="$work/cache-$name" LD_LIBRARY_PATH="$(dirname "$binary")" \
    "$binary" shade --scene "$scene" --gbuffer "$gbuffer" --out "$work/$name.exr" --compression none "$@" > /dev/null
  so=$(find "$work/pocl-$name" -path '*goffs0*' -name 'phong_shade.so' | head -1)
  objdump -d --no-show-raw-insn "$so" | grep -E '^\s+[0-9a-f]+:\s' |
    sed -E 's/^\s+[0-9a-f]+:\s+//; s/#.*//; s/[0-9a-f]+ <[^>]*>/TARGET/' > "$work/$name.s"
}
instructions "$(cd "$(dirname "$base")" && pwd)/$(basename "$base")" baseline "$@"
instructions "$PWD/build/phongcl" new "$@"
echo "same-machine-code: $scene: $(wc -l < "$work/baseline.s") instructions in the baseline, $(wc -l < "$work/new.s") now"
if diff "$work/baseline.s" "$work/new.s"; then
  echo "same-machine-code: identical but for addresses"
else
  echo "same-machine-code: the lines above differ"
  exit 1
fi
