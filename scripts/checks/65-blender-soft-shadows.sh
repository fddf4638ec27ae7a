#!/usr/bin/env bash
# Soft shadows against Cycles: renders scripts/blender/shadow_scene.py --soft (the spheres and box
# under a 2 m area light, a point and a spot light of radius 0.25 m and a 10-degree sun, each alone,
# 256 samples, and each again with its shadows off) at 160x120, shades each light alone with
# --shadows geometry (the default rays) and screen, and holds each light's `phongcl agreement`
# (within 5% of Cycles' own unshadowed light, away from silhouettes) to the level docs/shadows.md
# measured (Blender 3.4 and 5.2), less a margin of about 1 point for Cycles' noise and the versions:
# the area, point and sun lights reach the issue's 99% with geometry, the spot not yet (97.9%), nor
# screen space's 95% for the spot (the docs say why).
# PHONGCL_SHADOW_CHECK_SIZE and PHONGCL_SHADOW_CHECK_KEEP as in 65-blender-shadows.sh.
set -euo pipefail
cd "$(dirname "$0")/../.."
check=65-blender-soft-shadows
source scripts/checks/lib/shadow_lights.sh
render_shadow_scene --soft --samples 256 --unshadowed
shade_each_light geometry screen
tolerance_base=cycles
# Per light, in shadow_scene.py's order: area, point, spot, sun.
geometry_targets=(98.2 98.7 96.8 98.5)
screen_targets=(96.2 98.2 90.4 98.1)
summary=""
for ((k = 0; k < lights; ++k)); do
  shadow_agreement off 0 "$k" >/dev/null
  shadow_agreement geometry "${geometry_targets[k]}" "$k"
  shadow_agreement screen "${screen_targets[k]}" "$k"
  summary+="; light $k $(agreeing_share "$work/agreement-off-$k.txt") off, $(agreeing_share "$work/agreement-geometry-$k.txt")"
  summary+=" geometry, $(agreeing_share "$work/agreement-screen-$k.txt") screen"
done
echo "$check: Cycles ${width}x${height}$summary"
