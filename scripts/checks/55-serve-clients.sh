#!/usr/bin/env bash
# phongcl serve on loopback against clients that do not play along (scripts/checks/serve_clients.py):
# hostile requests, slow, idle and waiting clients while the page and API are timed, SIGTERM while
# they are connected, RSS over repeated 5 MB scene PUTs and over new light mixes (a kernel each).
# Prints the figures docs/reliability.md quotes; fails above its bounds (answers within 1 s, stop
# within 2 s, RSS that stops growing under the PUTs).
set -euo pipefail
cd "$(dirname "$0")/../.."
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export POCL_CACHE_DIR="${POCL_CACHE_DIR:-$work/pocl-cache}"
cmake --build build --target phongcl >"$work/build.log" 2>&1 || { cat "$work/build.log"; echo "55-serve-clients: FAILED: build" >&2; exit 1; }
echo "55-serve-clients: load before: $(cat /proc/loadavg)"
/usr/bin/python3 scripts/checks/serve_clients.py --phongcl build/phongcl --scene scenes/default/scene.json \
  --work "$work" --puts "${SERVE_PUTS:-12}" --mixes "${SERVE_MIXES:-40}"
echo "55-serve-clients: load after: $(cat /proc/loadavg)"
