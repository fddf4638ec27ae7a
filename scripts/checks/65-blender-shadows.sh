#!/usr/bin/env bash
# Shadows against Cycles: renders scripts/blender/shadow_scene.py (spheres and a box on a ground
# under two point lights that cast hard shadows; pure diffuse, no bounces) at 160x120, exports its
# meshes (export_scene.py --geometry), shades each light alone with --shadows geometry, screen and
# off, and holds `phongcl agreement` (Cycles' direct diffuse light, within 5% of each light's
# unshadowed value, away from silhouettes) to the targets of docs/shadows.md: geometry >= 99.5%,
# screen >= 96%. Needs build/phongcl and build/phongcl-lab (scripts/test.sh builds them first).
# PHONGCL_SHADOW_CHECK_SIZE="320 240" renders the docs' size; PHONGCL_SHADOW_CHECK_KEEP=DIR keeps the files.
set -euo pipefail
cd "$(dirname "$0")/../.."
check=65-blender-shadows
source scripts/checks/lib/shadow_lights.sh
render_shadow_scene
shade_each_light geometry screen
shadow_agreement off 0
shadow_agreement geometry 99.5
shadow_agreement screen 96
echo "65-blender-shadows: Cycles ${width}x${height}; every light agrees on $(agreeing_share "$work/agreement-off.txt")" \
  "without shadows, $(agreeing_share "$work/agreement-geometry.txt") geometry, $(agreeing_share "$work/agreement-screen.txt") screen"
