#!/usr/bin/env bash
# Makes a minimal Debian root holding Debian's own Blender, and a wrapper that runs it, so a newer
# Blender than the host's can render on this machine without changing the host: only the cache
# directory is written. Usage: make_root.sh SUITE NAME, e.g. `make_root.sh trixie blender4`.
#   root:    $PHONGCL_CACHE/roots/SUITE   (PHONGCL_CACHE defaults to /var/cache/phongcl)
#   wrapper: $PHONGCL_CACHE/bin/NAME      (`NAME -b scene.blend --python ...`, arguments passed through),
#            a link to $PHONGCL_CACHE/blenders/NAME/bin/blender, laid out as an installed Blender is:
#            its ../share/blender is the root's, so `phongcl --ocio blender --blender NAME` finds the
#            root's OCIO config, and so does `--ocio blender` with that bin directory on PATH.
# Safe to run again: a root is complete once its marker file exists; a root without one (an interrupted
# run) is removed and made again. docs/formats.md "From a Blender scene" says how to add a version.
set -euo pipefail
suite=${1:?usage: make_root.sh SUITE NAME}
name=${2:?usage: make_root.sh SUITE NAME}
cache=${PHONGCL_CACHE:-/var/cache/phongcl}
mirror=${PHONGCL_DEBIAN_MIRROR:-http://deb.debian.org/debian}
root="$cache/roots/$suite"
# Blender, and the OpenGL/EGL libraries with Mesa's software drivers that 5.x's compositor and EEVEE load
# even in the background (without them: "Couldn't open libGL.so.1", an abort).
packages=(blender libegl1 libegl-mesa0 libgl1 libopengl0 libglx-mesa0 libgl1-mesa-dri)
marker="$root/.phongcl-complete"
install="$cache/blenders/$name"
wrapper="$install/bin/blender"

if [ "$(id -u)" -ne 0 ]; then
  echo "phongcl setup: making a Debian root needs root (debootstrap, chroot); run as root or with sudo" >&2
  exit 2
fi

install_packages() {  # into the root, without recommends
  # Package scripts want /proc; mounted for the install only.
  mount -t proc proc "$root/proc"
  trap 'umount "$root/proc" 2>/dev/null || true' EXIT
  chroot "$root" env DEBIAN_FRONTEND=noninteractive apt-get update -qq
  chroot "$root" env DEBIAN_FRONTEND=noninteractive \
    apt-get install -y -qq --no-install-recommends "$@" >>"$cache/roots/$suite.apt.log" 2>&1 \
    || { echo "phongcl setup: installing $* in $root failed; see $cache/roots/$suite.apt.log" >&2; exit 1; }
  chroot "$root" apt-get clean
  umount "$root/proc"
  trap - EXIT
}

if [ ! -f "$marker" ]; then
  start=$(date +%s)
  if [ -e "$root" ]; then
    echo "phongcl setup: $root is incomplete (no $(basename "$marker")); making it again"
    rm -rf --one-file-system "$root"
  fi
  mkdir -p "$cache/roots"
  echo "phongcl setup: making a Debian $suite root in $root (minutes, once per machine)"
  debootstrap --variant=minbase "$suite" "$root" "$mirror" >"$cache/roots/$suite.debootstrap.log" 2>&1 \
    || { echo "phongcl setup: debootstrap $suite failed; see $cache/roots/$suite.debootstrap.log" >&2; exit 1; }
  # unstable's Release file is re-signed daily and can be past its Valid-Until date on a mirror snapshot.
  echo 'Acquire::Check-Valid-Until "false";' >"$root/etc/apt/apt.conf.d/99phongcl-valid-until"
  install_packages "${packages[@]}"
  chroot "$root" dpkg-query -W -f='${Version}' blender >"$marker"
  echo "phongcl setup: $suite root ready in $(( $(date +%s) - start )) s, $(du -sh --one-file-system "$root" | cut -f1)," \
    "blender $(cat "$marker")"
fi

# A root made before a package joined the list gets it now.
missing=()
for package in "${packages[@]}"; do
  chroot "$root" dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" || missing+=("$package")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "phongcl setup: adding ${missing[*]} to $root"
  install_packages "${missing[@]}"
fi

mkdir -p "$cache/bin" "$install/bin"
ln -sfn "$root/usr/share" "$install/share"
repository=$(cd "$(dirname "$0")/../.." && pwd)
cat >"$wrapper.tmp" <<WRAPPER
#!/usr/bin/env bash
# Runs Debian $suite's Blender ($(cat "$marker")) from $root; written by scripts/blender/make_root.sh.
# Mapped at the same paths, so that paths in arguments work: phongcl's repository ($repository), the
# current directory's git work tree (or the directory), /tmp, \$TMPDIR, the work tree (or directory) of
# each argument that names an existing file or directory or a file in one, and the directories in
# PHONGCL_BLENDER_BINDS (colon-separated); never / or a system directory, which would hide the root's.
# Blender's user settings go to a scratch /root, not the host's home; the root itself is read-only.
set -euo pipefail
root=$root
dirs=($(printf %q "$repository") "\$(git rev-parse --show-toplevel 2>/dev/null || pwd)" "\$PWD" /tmp "\${TMPDIR:-/tmp}")
IFS=: read -r -a extra <<<"\${PHONGCL_BLENDER_BINDS:-}"
dirs+=("\${extra[@]}")
for arg in "\$@"; do
  case "\$arg" in -*|"") continue ;; esac
  if [ -d "\$arg" ]; then dir=\$arg; elif [ -d "\$(dirname -- "\$arg")" ]; then dir=\$(dirname -- "\$arg"); else continue; fi
  dir=\$(cd "\$dir" && pwd)
  dirs+=("\$(git -C "\$dir" rev-parse --show-toplevel 2>/dev/null || echo "\$dir")")
done
binds=()
declare -A seen=()
for dir in "\${dirs[@]}"; do
  case "\$dir" in
    ""|/|/usr|/usr/*|/lib*|/bin|/bin/*|/sbin|/sbin/*|/etc|/etc/*|/var|/var/*|/proc*|/dev*|/sys*|/boot*|/run*) continue ;;
  esac
  if [ -d "\$dir" ] && [ -z "\${seen[\$dir]:-}" ]; then
    seen[\$dir]=1
    binds+=(--bind "\$dir" "\$dir")
  fi
done
# The root's directories, read-only, on an empty / of its own: the mount points of the directories
# mapped above are made there, which a user other than root could not do in the root itself. Empty ones
# (home, opt, ...) are left to be made, and /root, HOME, is a scratch one.
layout=(--tmpfs /)
for entry in "\$root"/*; do
  name=\${entry##*/}
  case "\$name" in proc|dev|sys|tmp|root) continue ;; esac
  if [ -L "\$entry" ]; then
    layout+=(--symlink "\$(readlink "\$entry")" "/\$name")
  elif [ -d "\$entry" ] && [ -n "\$(ls -A "\$entry")" ]; then
    layout+=(--ro-bind "\$entry" "/\$name")
  fi
done
if command -v bwrap >/dev/null; then
  exec bwrap "\${layout[@]}" --tmpfs /root --proc /proc --dev /dev --ro-bind /sys /sys "\${binds[@]}" \\
    --setenv HOME /root --chdir "\$PWD" --die-with-parent /usr/bin/blender "\$@"
fi
echo "\$(basename "\$0"): bwrap (package bubblewrap) is needed to run \$root's Blender" >&2
exit 2
WRAPPER
chmod +x "$wrapper.tmp"
mv "$wrapper.tmp" "$wrapper"
ln -sfn "../blenders/$name/bin/blender" "$cache/bin/$name"
echo "phongcl setup: $cache/bin/$name runs Blender $(cat "$marker") (Debian $suite)"
