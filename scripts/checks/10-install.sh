#!/usr/bin/env bash
# The installed package: `cmake --install` of build/ into a temporary prefix, then a consumer built
# out of tree against it (tests/consumer, find_package(phongcl)) and run; the installed `phongcl`
# runs from the prefix and has no lab; the installed binaries are baseline x86-64 (no AVX or
# AVX-512 instruction: the C++ peers' -march=native code stays in the lab) and hold no lab code.
set -euo pipefail
cd "$(dirname "$0")/../.."
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export POCL_CACHE_DIR="${POCL_CACHE_DIR:-$work/pocl-cache}"
fail() { echo "10-install: FAILED: $*" >&2; exit 1; }

cmake --build build >/dev/null
cmake --install build --prefix "$work/prefix" >/dev/null
prefix="$work/prefix"
library=$(find "$prefix" -name 'libphongcl.so.*.*' | head -n1)
[ -n "$library" ] || fail "no libphongcl.so installed"

lab_files=$(find "$prefix" \( -name '*peer*' -o -name '*reference*' -o -name '*stability*' -o -name '*report*' \
  -o -name 'phongcl-lab' \) -print)
[ -z "$lab_files" ] || fail "lab files installed: $lab_files"
lab_symbols=$(nm -DC "$library" | grep -E 'reference_image|run_catalogue|simd_peer|scalar_peer|markdown_table' || true)
[ -z "$lab_symbols" ] || fail "lab symbols in $library: $lab_symbols"

python_module=$(find "$prefix" -name 'phongcl.cpython-*.so' | head -n1)

# AVX and later use VEX/EVEX encodings: v-prefixed mnemonics, ymm/zmm registers, mask registers.
# Functions in phongcl::avx2 are exempt: they run only where the CPU reports AVX2 and FMA
# (host/color/pixel_kernels_avx2.cpp), so the binaries still run on baseline x86-64.
for binary in "$library" "$prefix/bin/phongcl" $python_module; do
  beyond=$(objdump -d -C --no-show-raw-insn "$binary" |
    awk '/^[0-9a-f]+ <.*>:$/ { dispatched = index($0, "<phongcl::avx2::") > 0 } !dispatched' |
    grep -cE $'\t''v[a-z0-9]+ |%[yz]mm[0-9]|%k[0-7]' || true)
  [ "$beyond" -eq 0 ] || fail "$binary has $beyond instructions beyond baseline x86-64 (AVX or later)"
done

# With the warnings of the project's own build, as errors: the installed headers compile cleanly in a
# strict user's build.
cmake -S tests/consumer -B "$work/consumer" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$prefix" \
  -DCMAKE_CXX_FLAGS="-Wall -Wextra -Wpedantic" -DCMAKE_COMPILE_WARNING_AS_ERROR=ON >"$work/configure.log" 2>&1 ||
  { cat "$work/configure.log"; fail "consumer does not configure"; }
cmake --build "$work/consumer" >"$work/build.log" 2>&1 || { cat "$work/build.log"; fail "consumer does not build"; }
mkdir "$work/out"
"$work/consumer/phongcl_consumer" scenes/default/scene.json scenes/default/gbuffer.exr "$work/out" ||
  fail "consumer run"
[ -s "$work/out/out.exr" ] || fail "consumer wrote no image"

"$prefix/bin/phongcl" shade --scene scenes/default/scene.json --out "$work/cli.exr" >"$work/shade.log" ||
  { cat "$work/shade.log"; fail "installed phongcl shade"; }
if "$prefix/bin/phongcl" bench --scene scenes/default/scene.json --report "$work/r" 2>"$work/lab.log"; then
  fail "installed phongcl ran a lab command"
fi
grep -q "lab command" "$work/lab.log" || { cat "$work/lab.log"; fail "no clear message for a lab command"; }

if [ -n "$python_module" ]; then
  (cd "$work" && PYTHONPATH="$(dirname "$python_module")" /usr/bin/python3 -c "
import phongcl, sys
scene = phongcl.load_scene(sys.argv[1])
image = phongcl.Relighter(scene, phongcl.read_gbuffer(sys.argv[2])).shade()
assert image.shape == (480, 640, 4) and image[..., 3].max() == 1, image.shape
" "$OLDPWD/scenes/default/scene.json" "$OLDPWD/scenes/default/gbuffer.exr") || fail "the installed Python module"
fi

echo "10-install: installed $(find "$prefix" -type f | wc -l) files; consumer built against find_package(phongcl)" \
  "and ran; installed phongcl shades and refuses lab commands${python_module:+, the installed Python module shades};" \
  "libphongcl, phongcl${python_module:+ and the module} are baseline x86-64"
