# Sourced by 65-blender-shadows.sh and 65-blender-soft-shadows.sh (in lib/ so that test.sh does not
# run it as a check), after `check=<name>`: blender_check.sh's tools and work directory
# (PHONGCL_SHADOW_CHECK_KEEP=DIR keeps it) and the size (PHONGCL_SHADOW_CHECK_SIZE="320 240"; default
# 160x120); then shadow_scene.py's render, each light shaded alone, and `phongcl agreement` over them.
keep="${PHONGCL_SHADOW_CHECK_KEEP:-}"
source scripts/checks/lib/blender_check.sh
read -r width height <<<"${PHONGCL_SHADOW_CHECK_SIZE:-160 120}"

# shadow_scene.py at width x height into $work; arguments go to it (--soft --samples N --unshadowed).
render_shadow_scene() {
  "$blender" -b --factory-startup --python-exit-code 1 --python scripts/blender/shadow_scene.py -- --out "$work" \
    --width "$width" --height "$height" "$@" >"$work/blender.log" 2>&1 ||
    { tail -20 "$work/blender.log"; echo "$check: shadow_scene.py failed" >&2; exit 1; }
}

# One scene per light, the other lights removed (Cycles rendered each alone), each shaded with every
# --shadows mode given (and `off`, the unshadowed light the agreement's tolerance is taken from).
# Sets `lights` to their count.
shade_each_light() {
  lights=$(python3 -c "import json,sys; print(len(json.load(open(sys.argv[1]))['lights']))" "$work/scene.json")
  local k mode
  for ((k = 0; k < lights; ++k)); do
    python3 - "$work/scene.json" "$k" "$work/light$k.json" <<'PY'
import json, sys
scene = json.load(open(sys.argv[1]))
scene["lights"] = [scene["lights"][int(sys.argv[2])]]
json.dump(scene, open(sys.argv[3], "w"), indent=1)
PY
    for mode in "$@" off; do
      "$phongcl" shade --scene "$work/light$k.json" --shadows "$mode" --out "$work/$mode$k.exr" \
        --aov "$work/$mode$k.aov.exr" >"$work/shade-$mode$k.log" ||
        { cat "$work/shade-$mode$k.log"; echo "$check: shading light $k ($mode) failed" >&2; exit 1; }
    done
  done
}

# `phongcl agreement` of a mode's images with Cycles', held to --at-least $2 percent: every light's
# together, or with $3 the one light of that index alone. Its report goes to agreement-$1[-$3].txt.
# The tolerance's base is phongcl's `off` image, or with tolerance_base=cycles Cycles' render of the
# light with its shadows off (render_shadow_scene --unshadowed).
shadow_agreement() {
  local args=() k first=0 last=$((lights - 1)) report="$work/agreement-$1.txt"
  [ $# -ge 3 ] && first=$3 last=$3 report="$work/agreement-$1-$3.txt"
  for ((k = first; k <= last; ++k)); do
    args+=(--cycles "$work/light$k.exr" --shaded "$work/$1$k.aov.exr")
    if [ "${tolerance_base:-phongcl}" = cycles ]; then
      args+=(--cycles-unshadowed "$work/light$k-unshadowed.exr")
    else
      args+=(--unshadowed "$work/off$k.aov.exr")
    fi
  done
  "$phongcl" agreement "${args[@]}" --at-least "$2" | tee "$report"
}

# The percentage a report of shadow_agreement gives for every light it counted.
agreeing_share() { grep -o 'every light [0-9.]*%' "$1" | cut -d' ' -f3; }
