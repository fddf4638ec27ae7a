#!/usr/bin/env bash
# Installs the Debian 12 packages phongcl needs, only those missing. Each scripts/packages/NAME.txt
# is one group (a package per word, `#` starts a comment; CONTRIBUTING.md "Dependencies" says why each one is
# there). `setup.sh` installs the core group, `setup.sh NAME...` those groups, `setup.sh all` every
# group. Safe to run again; uses sudo when not root.
set -euo pipefail
cd "$(dirname "$0")/packages"

groups=("$@")
[ ${#groups[@]} -gt 0 ] || groups=(core)
if [ "${groups[0]}" = all ]; then
  groups=()
  for list in *.txt; do groups+=("${list%.txt}"); done
fi

packages=()
for group in "${groups[@]}"; do
  [ -f "$group.txt" ] || { echo "phongcl setup: no package group '$group' (scripts/packages/$group.txt)" >&2; exit 2; }
  read -r -a words <<<"$(sed 's/#.*//' "$group.txt" | tr '\n' ' ')"
  packages+=("${words[@]}")
done

missing=()
for package in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" || missing+=("$package")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "phongcl setup: installing ${missing[*]}"
sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
