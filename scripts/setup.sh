#!/usr/bin/env bash
# Installs the Debian 12 packages phongcl needs, only those missing. Each scripts/packages/NAME.txt
# is one group (a package per word, `#` starts a comment; CONTRIBUTING.md "Dependencies" says why each one is
# there). `setup.sh` installs the core group, `setup.sh NAME...` those groups, `setup.sh all` every
# group. Safe to run again; uses sudo when not root.
# A group with a NAME.root file beside its list is a Blender run from a minimal Debian root rather than the
# host's: the file names the Debian suite, and after its host packages are in, scripts/blender/make_root.sh
# makes that root and the wrapper /var/cache/phongcl/bin/NAME (once per machine; docs/formats.md "From a
# Blender scene"). `all` leaves these groups out: each takes minutes and over a gigabyte.
set -euo pipefail
cd "$(dirname "$0")/packages"

groups=("$@")
[ ${#groups[@]} -gt 0 ] || groups=(core)
if [ "${groups[0]}" = all ]; then
  groups=()
  for list in *.txt; do [ -f "${list%.txt}.root" ] || groups+=("${list%.txt}"); done
fi

packages=()
roots=()
for group in "${groups[@]}"; do
  [ -f "$group.txt" ] || { echo "phongcl setup: no package group '$group' (scripts/packages/$group.txt)" >&2; exit 2; }
  read -r -a words <<<"$(sed 's/#.*//' "$group.txt" | tr '\n' ' ')"
  packages+=("${words[@]}")
  if [ -f "$group.root" ]; then roots+=("$(sed 's/#.*//' "$group.root" | tr -d '[:space:]') $group"); fi
done

make_roots() {
  local root
  for root in ${roots[@]+"${roots[@]}"}; do
    # shellcheck disable=SC2086  # "SUITE NAME"
    $sudo ../blender/make_root.sh $root
  done
}
sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi

missing=()
for package in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" || missing+=("$package")
done
if [ ${#missing[@]} -eq 0 ]; then
  make_roots
  exit 0
fi

echo "phongcl setup: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
make_roots
