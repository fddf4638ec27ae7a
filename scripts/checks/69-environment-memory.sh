#!/usr/bin/env bash
# The environment light's memory with a 16384 x 8192 float map (docs/environment.md "Memory"): the
# map is written (uncompressed, 1.5 GB) into a temporary directory, row by row, and `phongcl shade`
# lights a small ray-cast G-buffer with it; its peak resident memory, less that of the same shade
# with a 1024 x 512 map, must stay under PHONGCL_MAP_MEMORY_BOUND_MIB (default 100 MiB; measured 45
# MiB, where reading a whole channel cost 509): the map is read a block of rows at a time, never
# whole. Needs build/phongcl and GNU time (/usr/bin/time).
set -euo pipefail
cd "$(dirname "$0")/../.."
check=69-environment-memory
phongcl="${PHONGCL_BUILD_DIR:-build}/phongcl"
[ -x "$phongcl" ] || { echo "$check: no $phongcl (build first)" >&2; exit 1; }
[ -x /usr/bin/time ] || { echo "$check: GNU time (/usr/bin/time) is not installed" >&2; exit 1; }
bound_mib="${PHONGCL_MAP_MEMORY_BOUND_MIB:-100}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
export POCL_CACHE_DIR="${POCL_CACHE_DIR:-$work/pocl-cache}"

# A sky gradient over a dark ground, every row constant: the reading and folding cost the same.
for size in "1024 512" "16384 8192"; do
  python3 - "$work/sky-${size% *}.exr" $size <<'PY'
import struct, sys
sys.path.insert(0, "scripts/blender")
import exr_file
path, width, height = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
def line(y):
    sky = 0.2 + 0.8 * (1.0 - y / height) if y < height // 2 else 0.05
    return b"".join(struct.pack("<f", value) * width for value in (sky, 0.9 * sky, 0.8 * sky))  # B, G, R
exr_file.write_lines(path, width, height, line)
PY
done

peak_kib() {  # map width: prints the shade's peak resident set in KiB
  cat >"$work/scene-$1.json" <<JSON
{ "camera": { "eye": [0, 2, 6], "look_at": [0, 0.5, 0], "up": [0, 1, 0], "fov_y_deg": 40, "width": 64, "height": 48 },
  "materials": [ { "kd": [0.8, 0.8, 0.8] } ],
  "objects": [ { "type": "plane", "normal": [0, 1, 0], "offset": 0, "material": 0 },
               { "type": "sphere", "center": [0, 0.8, 0], "radius": 0.8, "material": 0 } ],
  "lights": [ { "type": "environment", "file": "sky-$1.exr" } ],
  "gbuffer": "gbuffer.exr" }
JSON
  "$phongcl" gbuffer --scene "$work/scene-$1.json" --out "$work/gbuffer.exr" >/dev/null
  /usr/bin/time -f %M -o "$work/peak-$1.txt" "$phongcl" shade --scene "$work/scene-$1.json" --shadows off \
    --out "$work/shaded-$1.exr" >"$work/shade-$1.log" 2>&1 || { cat "$work/shade-$1.log"; echo "$check: shading with the $1-wide map failed" >&2; exit 1; }
  tail -1 "$work/peak-$1.txt"
}
peak_kib 1024 >/dev/null  # builds the kernel into the PoCL cache: the compiler's memory is not the map's
small=$(peak_kib 1024)
large=$(peak_kib 16384)
extra_mib=$(( (large - small) / 1024 ))
echo "$check: peak resident memory $((large / 1024)) MiB with a 16384x8192 map, $((small / 1024)) MiB with 1024x512: the large map costs $extra_mib MiB (bound $bound_mib)"
[ "$extra_mib" -le "$bound_mib" ] || { echo "$check: the 16384x8192 map costs $extra_mib MiB, over $bound_mib" >&2; exit 1; }
