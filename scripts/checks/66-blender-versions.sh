#!/usr/bin/env bash
# The Blender checks (60 to 65, 67 and 68) again on the newer Blenders artists run, each from its own Debian root:
# 5.2 (Debian unstable) and 4.3 (Debian 13). `scripts/setup.sh blenderN` makes a root once per machine
# (about 2 minutes and 1.3 GB each; seconds when it exists), then every check runs with
# BLENDER=/var/cache/phongcl/bin/blenderN, so each renders its scenes with that version and holds
# phongcl to that version's Cycles and colour management with the same targets as on 3.4 (the exporter
# writes 4.0+'s Principled BSDF as its version 2, so 67-specular and 68 hold version 2 there).
# PHONGCL_BLENDER_VERSIONS="blender5" narrows the list (default "blender5 blender4").
set -euo pipefail
cd "$(dirname "$0")/../.."
check=66-blender-versions
versions=${PHONGCL_BLENDER_VERSIONS:-blender5 blender4}
cache=${PHONGCL_CACHE:-/var/cache/phongcl}
checks=(60-blender 61-blender-notes 62-blender-area 62-blender-lights 63-blender-colour 64-blender-over 65-blender-shadows
        65-blender-soft-shadows 67-blender-environment 67-blender-environment-specular 68-blender-principled)

summary=()
for version in $versions; do
  start=$(date +%s)
  scripts/setup.sh "$version"
  made=$(($(date +%s) - start))
  blender="$cache/bin/$version"
  release=$("$blender" --version 2>/dev/null | sed -n 's/^Blender \([0-9.]*\).*/\1/p' | head -1)
  [ -n "$release" ] || { echo "$check: $blender does not run" >&2; exit 1; }
  for name in "${checks[@]}"; do
    echo "== $check: $name on Blender $release"
    BLENDER="$blender" bash "scripts/checks/$name.sh" || { echo "$check: $name failed on Blender $release" >&2; exit 1; }
  done
  summary+=("Blender $release: root in ${made} s, checks in $(($(date +%s) - start - made)) s")
done
echo "$check: every Blender check passed on $(IFS=';'; echo "${summary[*]}" | sed 's/;/; /g')"
