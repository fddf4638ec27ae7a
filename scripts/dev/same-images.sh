#!/usr/bin/env bash
# Checks that a kernel or host change leaves every image bit-identical: shades every bundled scene
# (scenes/*, scenes/large's G-buffer generated first) in every precision variant, specialised and
# general, at every lane width, with tiled culling on and off, with and without the term outputs
# (--aov), with a baseline phongcl and with build/phongcl, and `cmp`s the EXRs.
#
#   git worktree add /tmp/base main && (cd /tmp/base && scripts/build.sh)   # or copy a build/ aside
#   scripts/dev/same-images.sh /tmp/base/build/phongcl [--quick] [--jobs N] [--scene NAME]... [--lanes "2 4"]
#
# The baseline's images are kept (keyed by its binary and library) in $SAME_IMAGES_DIR (default
# /tmp/phongcl-same-images), so later runs shade with build/phongcl only. --quick keeps lanes 1 and
# 16 and the smaller scenes (a few minutes); the full matrix is 7 scenes x 160 variants, which
# compiles 1,120 kernels per binary (hours on a busy 2-core machine, less with --jobs).
# Exits non-zero listing each combination whose images differ or that fails with build/phongcl only.
# (double16 with every light shape overflows PoCL's work-group stack: both fail there.)
set -euo pipefail
cd "$(dirname "$0")/../.."
repo=$PWD

base=""
quick=0
jobs=2
scenes=()
lanes_asked=""
while [ $# -gt 0 ]; do
  case $1 in
    --quick) quick=1 ;;
    --lanes) lanes_asked=$2; shift ;;
    --jobs) jobs=$2; shift ;;
    --scene) scenes+=("$2"); shift ;;
    -*) echo "same-images: unknown option $1" >&2; exit 2 ;;
    *) base=$1 ;;
  esac
  shift
done
[ -x "$base" ] || { echo "usage: $0 BASELINE_PHONGCL [--quick] [--jobs N] [--scene NAME]... [--lanes LIST]" >&2; exit 2; }
new="$repo/build/phongcl"
[ -x "$new" ] || { echo "same-images: $new is missing (run scripts/build.sh first)" >&2; exit 2; }
base=$(cd "$(dirname "$base")" && pwd)/$(basename "$base")

# Each binary loads the libphongcl.so beside it (LD_LIBRARY_PATH overrides a RUNPATH).
base_key=$(cat "$base" "$(dirname "$base")"/libphongcl.so.*.*.* 2> /dev/null | sha256sum | cut -c1-16)
work=${SAME_IMAGES_DIR:-/tmp/phongcl-same-images}
mkdir -p "$work/base-$base_key" "$work/new" "$work/scenes" "$work/pocl"
rm -rf "$work/new"/*
export POCL_CACHE_DIR="$work/pocl"

if [ ${#scenes[@]} -eq 0 ]; then
  for dir in scenes/*/; do scenes+=("$(basename "$dir")"); done
  [ "$quick" = 1 ] && scenes=(default directional_diffuse many_lights shininess spotlights)
fi
lanes_list=(1 2 4 8 16)
[ "$quick" = 1 ] && lanes_list=(1 16)
[ -n "$lanes_asked" ] && read -r -a lanes_list <<< "$lanes_asked"

# A scene whose G-buffer is not in the repository (scenes/large) is ray-cast once, by build/phongcl.
gbuffer_of() {
  local scene=$1
  if [ -f "scenes/$scene/gbuffer.exr" ]; then echo "$repo/scenes/$scene/gbuffer.exr"; return; fi
  local made="$work/scenes/$scene.exr"
  [ -f "$made" ] || "$new" gbuffer --scene "scenes/$scene/scene.json" --out "$made" > /dev/null
  echo "$made"
}

jobs_file="$work/jobs.txt"
: > "$jobs_file"
for scene in "${scenes[@]}"; do
  gbuffer=$(gbuffer_of "$scene")
  for precision in double precise fast half-storage; do
    for specialise in specialised general; do
      for lanes in "${lanes_list[@]}"; do
        for culling in tiled none; do
          for terms in rgba aov; do
            echo "$scene $gbuffer $precision $specialise $lanes $culling $terms" >> "$jobs_file"
          done
        done
      done
    done
  done
done

# shade BINARY OUT_PREFIX SCENE GBUFFER PRECISION SPECIALISE LANES CULLING TERMS: writes
# OUT_PREFIX.exr (and .aov.exr), or OUT_PREFIX.failed with the error.
shade() {
  local binary=$1 out=$2 scene=$3 gbuffer=$4 precision=$5 specialise=$6 lanes=$7 culling=$8 terms=$9
  local flags=(--scene "scenes/$scene/scene.json" --gbuffer "$gbuffer" --precision "$precision" --lanes "$lanes"
               --culling "$culling" --compression none --out "$out.exr")
  [ "$specialise" = general ] && flags+=(--no-specialise)
  [ "$terms" = aov ] && flags+=(--aov "$out.aov.exr")
  PHONGCL_CACHE_DIR="$(dirname "$out")/cache" LD_LIBRARY_PATH="$(dirname "$binary")" \
    "$binary" shade "${flags[@]}" > /dev/null 2> "$out.err" || { mv "$out.err" "$out.failed"; return 0; }
  rm -f "$out.err"
}

# compare_one LINE: shades with the baseline (unless kept) and build/phongcl, and prints one line.
compare_one() {
  read -r scene gbuffer precision specialise lanes culling terms <<< "$1"
  local name="$scene-$precision-$specialise-$lanes-$culling-$terms"
  local kept="$work/base-$base_key/$name" fresh="$work/new/$name"
  [ -f "$kept.exr" ] || [ -f "$kept.failed" ] || shade "$base" "$kept" $1
  shade "$new" "$fresh" $1
  if [ -f "$kept.failed" ] && [ -f "$fresh.failed" ]; then echo "both-failed $name"; return; fi
  if [ -f "$kept.failed" ]; then echo "baseline-failed $name (build/phongcl shades it)"; return; fi
  if [ -f "$fresh.failed" ]; then echo "DIFFERENT $name (build/phongcl failed: $(head -c 200 "$fresh.failed"))"; return; fi
  local same=1
  cmp -s "$kept.exr" "$fresh.exr" || same=0
  [ "$terms" = aov ] && { cmp -s "$kept.aov.exr" "$fresh.aov.exr" || same=0; }
  [ $same = 1 ] && echo "same $name" || echo "DIFFERENT $name"
  rm -f "$fresh.exr" "$fresh.aov.exr"
}
export -f shade compare_one
export base new work base_key

total=$(wc -l < "$jobs_file")
echo "same-images: $total combinations, baseline $base (images kept in $work/base-$base_key), $jobs at a time"
results="$work/results.txt"
tr '\n' '\0' < "$jobs_file" | xargs -0 -P "$jobs" -I{} bash -c 'compare_one "$1"' _ {} | tee "$results" |
  grep -v '^same ' || true
same=$(grep -c '^same ' "$results" || true)
both_failed=$(grep -c '^both-failed ' "$results" || true)
fixed=$(grep -c '^baseline-failed ' "$results" || true)
different=$(grep -c '^DIFFERENT ' "$results" || true)
echo "same-images: $same identical, $both_failed failing in both, $fixed failing only in the baseline," \
  "$different different (of $total)"
[ "$different" = 0 ] && [ "$((same + both_failed + fixed))" = "$total" ]
