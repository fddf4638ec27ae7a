# Sourced by 67-blender-environment.sh and 67-blender-environment-specular.sh after `check=<name>` (in
# lib/ so that test.sh does not run it as a check): blender_check.sh's tools and work directory
# (PHONGCL_ENVIRONMENT_CHECK_KEEP=DIR keeps it), the render's size and samples
# (PHONGCL_ENVIRONMENT_CHECK_SIZE="320 240", PHONGCL_ENVIRONMENT_CHECK_SAMPLES=N), and render_environment.
keep="${PHONGCL_ENVIRONMENT_CHECK_KEEP:-}"
source scripts/checks/lib/blender_check.sh
read -r width height <<<"${PHONGCL_ENVIRONMENT_CHECK_SIZE:-160 120}"
samples="${PHONGCL_ENVIRONMENT_CHECK_SAMPLES:-256}"

# environment_scene.py under one world (uniform or hdri) into $work/<world>, with its further options.
render_environment() {
  local world=$1; shift
  "$blender" -b --factory-startup --python-exit-code 1 --python scripts/blender/environment_scene.py -- --out "$work/$world" \
    --world "$world" --width "$width" --height "$height" --samples "$samples" "$@" >"$work/blender-$world.log" 2>&1 ||
    { tail -20 "$work/blender-$world.log"; echo "$check: environment_scene.py --world $world failed" >&2; exit 1; }
}
