#!/usr/bin/env bash
# The Python module: builds it in build/ (python/, pybind11), runs its pytest suite against an
# independent NumPy reference, the README's Python relight as written, and the turntable example for a
# few steps.
set -euo pipefail
cd "$(dirname "$0")/../.."
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export POCL_CACHE_DIR="${POCL_CACHE_DIR:-$work/pocl-cache}"
python=/usr/bin/python3  # the Debian interpreter python/CMakeLists.txt builds for, with python3-numpy
fail() { echo "15-python: FAILED: $*" >&2; exit 1; }

cmake --build build --target phongcl_python >"$work/build.log" 2>&1 || { cat "$work/build.log"; fail "build"; }
module=$(find build/python -maxdepth 1 -name 'phongcl*.so' | head -n1)
[ -n "$module" ] || fail "build/python has no phongcl module (are python3-dev and pybind11-dev installed?)"
export PYTHONPATH="$PWD/build/python:$PWD/python/tests"

status=0
(cd "$work" && "$python" -m pytest -q -p no:cacheprovider "$OLDPWD/python/tests") || status=$?
# Exit 5: pytest collected nothing, which here means the suite went missing, not that it passed.
[ "$status" -ne 5 ] || fail "pytest collected no tests in python/tests"
[ "$status" -eq 0 ] || fail "pytest (exit $status)"

# The README's Python relight, as written, run from a directory that sees the repository's scenes.
sed -n '/^```python$/,/^```$/p' README.md | sed '1d;$d' >"$work/readme_relight.py"
[ -s "$work/readme_relight.py" ] || fail "README.md has no python block"
ln -s "$PWD/scenes" "$work/scenes"
(cd "$work" && "$python" readme_relight.py) || fail "the README's Python relight"
[ -s "$work/relit.exr" ] || fail "the README's Python relight wrote no relit.exr"

"$python" examples/relight_turntable.py --scene scenes/default/scene.json --out "$work/turntable" --steps 4 \
  >"$work/turntable.log" || { cat "$work/turntable.log"; fail "examples/relight_turntable.py"; }
[ "$(find "$work/turntable" -name 'frame_*.png' | wc -l)" -eq 4 ] || fail "the turntable wrote no 4 frames"
echo "15-python: pytest and the README's relight passed; examples/relight_turntable.py: $(grep 'relight + shade' "$work/turntable.log" | xargs)"
