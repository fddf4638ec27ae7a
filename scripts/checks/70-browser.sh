#!/usr/bin/env bash
# phongcl serve in a real browser: Debian's headless Chromium driven over WebDriver (chromedriver)
# by scripts/checks/browser_relight.py. Edits a light through the page, checks the images against the
# scalar reference of the edited scene, saves the scene, takes a screenshot, and reports the
# input-event-to-image-displayed frame rates while dragging at 640x480 and 1920x1080, and at 1080p
# over a render (serve --over), one light group's light dragged.
# PHONGCL_SCREENSHOT=FILE keeps the screenshot (docs/serve.png, shown in docs/serve.md, was made so).
set -euo pipefail
cd "$(dirname "$0")/../.."
scripts/setup.sh serve
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export POCL_CACHE_DIR="${POCL_CACHE_DIR:-$work/pocl-cache}"
fail() { echo "70-browser: FAILED: $*" >&2; exit 1; }

cmake --build build --target phongcl phongcl-lab phongcl_python >"$work/build.log" 2>&1 || { cat "$work/build.log"; fail "build"; }
build/phongcl gbuffer --scene scenes/large/scene.json --out "$work/large.exr" >"$work/gbuffer.log" ||
  { cat "$work/gbuffer.log"; fail "the 1080p G-buffer"; }
echo "70-browser: load before: $(cat /proc/loadavg)"
/usr/bin/python3 scripts/checks/browser_relight.py --phongcl build/phongcl --work "$work" \
  --large-gbuffer "$work/large.exr" --python-module build/python --screenshot "${PHONGCL_SCREENSHOT:-$work/screenshot.png}"
echo "70-browser: load after: $(cat /proc/loadavg)"
