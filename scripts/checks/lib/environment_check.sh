# Sourced by 67-blender-environment.sh and 67-blender-environment-specular.sh after `check=<name>` (in
# lib/ so that test.sh does not run it as a check): the built phongcl, an installed Blender (BLENDER=PATH
# for another), the render's size and samples (PHONGCL_ENVIRONMENT_CHECK_SIZE="320 240",
# PHONGCL_ENVIRONMENT_CHECK_SAMPLES=N), a work directory (PHONGCL_ENVIRONMENT_CHECK_KEEP=DIR keeps it, else
# one removed on exit) with PoCL's cache in it unless one is set, and render_environment.
phongcl="${PHONGCL_BUILD_DIR:-build}/phongcl"
[ -x "$phongcl" ] || { echo "$check: no $phongcl (build first)" >&2; exit 1; }
blender="${BLENDER:-blender}"
command -v "$blender" >/dev/null || { echo "$check: $blender is not installed (scripts/setup.sh blender)" >&2; exit 1; }
read -r width height <<<"${PHONGCL_ENVIRONMENT_CHECK_SIZE:-160 120}"
samples="${PHONGCL_ENVIRONMENT_CHECK_SAMPLES:-256}"

work="${PHONGCL_ENVIRONMENT_CHECK_KEEP:-}"
if [ -z "$work" ]; then
  work="$(mktemp -d)"
  trap 'rm -rf "$work"' EXIT
fi
mkdir -p "$work"
export POCL_CACHE_DIR="${POCL_CACHE_DIR:-$work/pocl-cache}"

# environment_scene.py under one world (uniform or hdri) into $work/<world>, with its further options.
render_environment() {
  local world=$1; shift
  "$blender" -b --factory-startup --python-exit-code 1 --python scripts/blender/environment_scene.py -- --out "$work/$world" \
    --world "$world" --width "$width" --height "$height" --samples "$samples" "$@" >"$work/blender-$world.log" 2>&1 ||
    { tail -20 "$work/blender-$world.log"; echo "$check: environment_scene.py --world $world failed" >&2; exit 1; }
}
