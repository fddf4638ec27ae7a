#!/usr/bin/env bash
# A second OpenCL implementation: Oclgrind (Debian) compiles the recipe's kernel variants with its
# own front end, and simulates the kernel, checking every memory access. Registered for this run
# only (an ICD file in a temp dir via OCL_ICD_VENDORS, nothing in /etc), it shades a small G-buffer
# at lanes 1 (the GPU path) in every precision variant, both specialised and general, with
# --check-api --uninitialized --data-races, and the spot-light scene through tiled culling (cull.cl
# and the tile lists), and a shadowed frame both ways (the BVH traversal and the screen-space march).
# Passes when Oclgrind reports nothing and each image is within that variant's bound of the C++
# reference (shadowed frames: of PoCL's image of the same kernel, as `phongcl reference` has no
# shadows).
# The tiled runs leave out --uninitialized: Oclgrind 21.10's checker stops on the `freeze` LLVM puts
# between a / and a % (tile_bounds), and then takes the tile lists keep_box_lights wrote for
# uninitialized (its own memory checker finds every read in bounds, and the image matches).
# Lanes > 1 are not run: Oclgrind 21.10 crashes under --uninitialized on the shuffle with an
# undefined mask that all_lanes() compiles to (at lanes 1 it is `return mask`).
set -euo pipefail
cd "$(dirname "$0")/../.."
phongcl="$PWD/build/phongcl"
icd=/usr/lib/oclgrind/liboclgrind-rt-icd.so
[ -x "$phongcl" ] || { echo "oclgrind: build/phongcl is missing (run scripts/build.sh first)"; exit 1; }
[ -f "$icd" ] || { echo "oclgrind: $icd is missing (scripts/setup.sh reliability installs oclgrind)"; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
echo "$icd" > "$work/oclgrind.icd"

# The default scene at 48x32 pixels: every light type, a material table, background pixels; and
# the spot-light scene (spots, falloff, ranges, linking) at 40x30 in tiles of 8 (the last ones partial);
# the default scene at 32x24 with every light casting shadows.
# small_scene SOURCE DEST WIDTH HEIGHT [shadows]: with `shadows`, every light casts them.
small_scene() {
  python3 - "$@" << 'PY'
import json, sys
scene = json.load(open(sys.argv[1]))
scene["camera"].update(width=int(sys.argv[3]), height=int(sys.argv[4]))
scene["gbuffer"] = "gbuffer.exr"
for light in scene["lights"]:
    light["shadows"] = sys.argv[5:] == ["shadows"]
json.dump(scene, open(sys.argv[2], "w"))
PY
  "$phongcl" gbuffer --scene "$2" > /dev/null
  "$phongcl" reference --scene "$2" --out "$(dirname "$2")/reference.exr" > /dev/null
}
mkdir "$work/spots" "$work/shadows"
small_scene scenes/default/scene.json "$work/scene.json" 48 32
small_scene scenes/spotlights/scene.json "$work/spots/scene.json" 40 30
small_scene scenes/default/scene.json "$work/shadows/scene.json" 32 24 shadows
# PoCL's shadowed images, before only Oclgrind is registered.
for mode in geometry screen; do
  "$phongcl" shade --scene "$work/shadows/scene.json" --shadows "$mode" --precision precise --lanes 1 \
    --out "$work/shadows/$mode.exr" --png "$work/shadows/$mode.png" > /dev/null
done

export OCL_ICD_VENDORS="$work" PHONGCL_CACHE_DIR="$work/cache"
export OCLGRIND_CHECK_API=1 OCLGRIND_UNINITIALIZED=1 OCLGRIND_DATA_RACES=1
# Bounds: the product's relative bound (tests/accuracy_bound.h, as the tests hold it); half storage
# rounds its inputs to 11 bits, which the specular power multiplies (measured bound 0.5).
product_bound=$(sed -n 's/^constexpr double kRelativeBound = \(.*\);$/\1/p' tests/accuracy_bound.h)
[ -n "$product_bound" ] || { echo "40-oclgrind: no kRelativeBound in tests/accuracy_bound.h" >&2; exit 1; }
declare -A bound=([double]=$product_bound [precise]=$product_bound [fast]=$product_bound [half-storage]=0.5)
runs=0
# on_oclgrind WHAT SCENE_DIR PRECISION [FLAGS...]: shades $work/lit.exr and lit.png on Oclgrind.
on_oclgrind() {
  local what=$1 dir=$2 precision=$3
  shift 3
  local flags=(--precision "$precision" --lanes 1 --device oclgrind "$@")
  if ! "$phongcl" shade --scene "$dir/scene.json" "${flags[@]}" --out "$work/lit.exr" --png "$work/lit.png" \
    > "$work/out.txt" 2> "$work/err.txt"; then
    head -20 "$work/err.txt"; echo "oclgrind: $what: phongcl failed"; exit 1
  fi
  if [ -s "$work/err.txt" ]; then
    head -40 "$work/err.txt"; echo "oclgrind: $what: Oclgrind reported errors (above)"; exit 1
  fi
  grep -q "Oclgrind" "$work/out.txt" || { cat "$work/out.txt"; echo "oclgrind: $what did not run on Oclgrind"; exit 1; }
  runs=$((runs + 1))
}
# shade_on_oclgrind WHAT SCENE_DIR PRECISION [FLAGS...]: on Oclgrind, within bounds of the reference.
shade_on_oclgrind() {
  on_oclgrind "$@"
  local what=$1 dir=$2 precision=$3
  if ! "$phongcl" compare "$work/lit.exr" "$dir/reference.exr" --tolerance "${bound[$precision]}" > "$work/compare.txt" 2>&1; then
    cat "$work/compare.txt"; echo "oclgrind: $what: outside ${bound[$precision]} of the reference"; exit 1
  fi
}
for precision in double precise fast half-storage; do
  shade_on_oclgrind "$precision specialised" "$work" "$precision"
  shade_on_oclgrind "$precision general" "$work" "$precision" --no-specialise
done
for precision in precise half-storage; do
  OCLGRIND_UNINITIALIZED=0 shade_on_oclgrind "$precision tiled" "$work/spots" "$precision" --culling tiled --tile 8
  grep -q "tiled culling 8x8" "$work/out.txt" || { cat "$work/out.txt"; echo "oclgrind: $precision tiled: not culled"; exit 1; }
done
# Shadows: every light's ray traced through the BVH, or marched across the depth plane. A light's
# decision within rounding of a silhouette may go either way in another compiler, so the PNGs must
# agree (each channel within one step) on 99% of the pixels rather than everywhere. Built with
# -cl-opt-disable: optimised, Oclgrind 21.10's inliner leaves llvm.experimental.noalias.scope.decl
# (from the functions returning a ShadowRay) that its interpreter does not know; the memory
# accesses checked are the same. A cache of their own: the tiled runs' optimised culling programs
# (cached under the same options) hold `freeze`, which the Uninitialized plugin cannot run.
for mode in geometry screen; do
  PHONGCL_CACHE_DIR="$work/cache-opt-disable" OCLGRIND_BUILD_OPTIONS=-cl-opt-disable on_oclgrind "$mode shadows" "$work/shadows" precise --shadows "$mode"
  grep -q "shadows    $mode" "$work/out.txt" || { cat "$work/out.txt"; echo "oclgrind: $mode shadows: not shadowed"; exit 1; }
  if ! "$phongcl" compare "$work/lit.png" "$work/shadows/$mode.png" --bytes 1 --min-fraction 0.99 > "$work/compare.txt" 2>&1; then
    cat "$work/compare.txt"; echo "oclgrind: $mode shadows: Oclgrind's image differs from PoCL's"; exit 1
  fi
done
# The kernels through Oclgrind's own compiler front end, in the variants the recipe makes and once
# with -cl-opt-disable, built and that one launched (tests/test_shading_interface.cpp).
variants="$PWD/build/tests/test_shading_interface"
[ -x "$variants" ] || { echo "oclgrind: $variants is missing (build with -DPHONGCL_BUILD_TESTS=ON)"; exit 1; }
if ! PHONGCL_TEST_DEVICE=oclgrind "$variants" --gtest_filter='KernelVariants.*' > "$work/variants.txt" 2> "$work/err.txt" ||
   [ -s "$work/err.txt" ]; then
  cat "$work/variants.txt" "$work/err.txt" | tail -40; echo "oclgrind: kernel variants: build failed or Oclgrind reported errors"; exit 1
fi
grep -q "building on Oclgrind" "$work/variants.txt" || { cat "$work/variants.txt"; echo "oclgrind: variants did not build on Oclgrind"; exit 1; }
built=$(grep -o "[0-9]* phong.cl and [0-9]* cull.cl variants" "$work/variants.txt")

echo "oclgrind: $built built by Oclgrind's front end (one with -cl-opt-disable, launched)"
echo "oclgrind: $runs runs (4 precisions x specialised/general, tiled culling in precise and half-storage without --uninitialized, geometry and screen shadows in precise; lanes 1) clean under --check-api --uninitialized --data-races, within bounds of the reference (shadows: of PoCL's image)"
