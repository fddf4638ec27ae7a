# Sourced by the Blender checks (in lib/ so that test.sh does not run it as a check), after
# `check=<name>` and, where a check keeps its files on request, `keep=<the directory asked for, or
# empty>`: the built phongcl, an installed Blender, a work directory (keep's, else one removed on
# exit), and PoCL's cache inside it unless one is set.
phongcl="${PHONGCL_BUILD_DIR:-build}/phongcl"
[ -x "$phongcl" ] || { echo "$check: no $phongcl (build first)" >&2; exit 1; }
blender="${BLENDER:-blender}"  # BLENDER=/var/cache/phongcl/bin/blender5 checks another version (scripts/setup.sh blender5)
command -v "$blender" >/dev/null || { echo "$check: $blender is not installed (scripts/setup.sh blender)" >&2; exit 1; }
work="${keep:-}"
if [ -z "$work" ]; then
  work="$(mktemp -d)"
  trap 'rm -rf "$work"' EXIT
fi
mkdir -p "$work"
export POCL_CACHE_DIR="${POCL_CACHE_DIR:-$work/pocl-cache}"
