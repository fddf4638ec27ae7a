#!/usr/bin/env bash
# SIGKILL during `phongcl shade` of a 1080p frame with --out and --png: after every kill the
# output directory holds the two files of one complete run (both old or both new, never a mix)
# and nothing else. Kill times spread over a whole run, so some land in the writes.
set -euo pipefail
cd "$(dirname "$0")/../.."
phongcl="$PWD/build/phongcl"
kills="${KILLS:-12}"
work=$(mktemp -d)
shader=""
trap '[ -n "$shader" ] && kill -9 "$shader" 2> /dev/null; rm -rf "$work"' EXIT
export PHONGCL_CACHE_DIR="$work/cache" POCL_CACHE_DIR="${POCL_CACHE_DIR:-$work/pocl-cache}"
mkdir -p "$work/out"
"$phongcl" gbuffer --scene scenes/large/scene.json --out "$work/g.exr" > /dev/null
# Two runs that differ in both files: A (float EXR, exposure 0) and B (half EXR, exposure 1).
shade() {  # shade A|B: arguments for that run
  local extra=(); [ "$1" = B ] && extra=(--half --exposure 1)
  echo shade --scene scenes/large/scene.json --gbuffer "$work/g.exr" --out "$work/out/lit.exr" --png "$work/out/lit.png" "${extra[@]}"
}
state() { cat "$work/out/lit.exr" "$work/out/lit.png" | md5sum | cut -d' ' -f1; }
"$phongcl" $(shade A) > /dev/null  # also compiles the kernel into the program cache
state_a=$(state)
start=$(date +%s%N)
"$phongcl" $(shade B) > /dev/null
run_ms=$(( ($(date +%s%N) - start) / 1000000 ))
state_b=$(state)
current=B survived=0 replaced=0
for i in $(seq 1 "$kills"); do
  next=$([ "$current" = A ] && echo B || echo A)
  delay_ms=$(( run_ms * i / kills ))  # from just after the start to the end of a whole run
  "$phongcl" $(shade "$next") > /dev/null 2>&1 &
  shader=$!
  sleep "$(printf '%d.%03d' $((delay_ms / 1000)) $((delay_ms % 1000)))"
  kill -9 "$shader" 2> /dev/null || true
  wait "$shader" 2> /dev/null || true
  shader=""
  left=$(ls -A "$work/out" | grep -v -x -e lit.exr -e lit.png || true)
  [ -z "$left" ] || { echo "kills: kill $i after $delay_ms ms left: $left"; exit 1; }
  now=$(state)
  if [ "$now" = "$state_a" ]; then current=A; elif [ "$now" = "$state_b" ]; then current=B; else
    echo "kills: kill $i after $delay_ms ms left an EXR and a PNG of different runs (or a damaged file)"; exit 1
  fi
  [ "$current" = "$next" ] && replaced=$((replaced + 1))
  survived=$((survived + 1))
done
echo "kills: $survived SIGKILLs over a ${run_ms} ms 1080p run ($replaced after the renames): no temporary left, no file lost or mixed"
