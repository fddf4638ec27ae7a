#!/usr/bin/env bash
# Times a baseline phongcl-lab against build/phongcl-lab with a control: the baseline runs twice per
# round (A and A'), so the spread between two runs of one binary shows what a B/A ratio can mean on
# this machine. Each run is `phongcl-lab bench` on scenes/large (every variant, --runs 15), with its
# own PoCL and phongcl caches; the three runs rotate their order from round to round, so a drift of
# the machine's speed within a round lands on each of them alike.
#
#   scripts/dev/same-speed.sh /tmp/base/build/phongcl-lab [ROUNDS]   (default 6 rounds, ~20 s a run)
#
# Prints every run's median kernel times, then per variant: the median of all runs of each binary,
# and the median and range over the rounds of B / mean(A, A') and of A' / A.
set -euo pipefail
cd "$(dirname "$0")/../.."
base=${1:?usage: $0 BASELINE_PHONGCL_LAB [ROUNDS]}
rounds=${2:-6}
scene=$PWD/scenes/large/scene.json
[ -f scenes/large/gbuffer.exr ] || build/phongcl gbuffer --scene "$scene" > /dev/null
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
variants='precise \(S\)|fast \(S\)|precise \(G\)|fast \(G\)'

# run NAME BINARY: one bench run, printed as "NAME ms ms ms ms" in the order of $variants.
run() {
  local name=$1 binary=$2
  mkdir -p "$work/$name"
  POCL_CACHE_DIR="$work/$name/pocl" PHONGCL_CACHE_DIR="$work/$name/cache" LD_LIBRARY_PATH="$(dirname "$binary")" \
    "$binary" bench --scene "$scene" --runs 15 --report "$work/$name/report" |
    awk -F'|' -v name="$name" -v pattern="$variants" \
      '$2 ~ pattern { gsub(/ ms| /, "", $3); line = line " " $3 } END { print name line }'
}

runs=$work/runs.txt
for round in $(seq 1 "$rounds"); do
  case $((round % 3)) in
    1) order="B A A'" ;;
    2) order="A' B A" ;;
    0) order="A A' B" ;;
  esac
  for name in $order; do
    if [ "$name" = B ]; then run B build/phongcl-lab; else run "$name" "$base"; fi
  done | tee -a "$runs"
done

python3 - "$runs" <<'EOF'
import statistics, sys
runs = [line.split() for line in open(sys.argv[1])]
rounds = [runs[i:i + 3] for i in range(0, len(runs), 3)]
for column, variant in enumerate(["precise (S)", "fast (S)", "precise (G)", "fast (G)"], start=1):
    median = {name: statistics.median(float(r[column]) for r in runs if r[0] == name) for name in ("A", "A'", "B")}
    by_name = [{r[0]: float(r[column]) for r in one} for one in rounds]
    b_over_a = [t["B"] / ((t["A"] + t["A'"]) / 2) for t in by_name]
    a_over_a = [t["A'"] / t["A"] for t in by_name]
    a, a2, b = median["A"], median["A'"], median["B"]
    print(f"{variant:12} median ms A {a:.2f}, A' {a2:.2f}, B {b:.2f};"
          f" B/A {statistics.median(b_over_a):.3f} ({min(b_over_a):.3f}-{max(b_over_a):.3f}),"
          f" A'/A {statistics.median(a_over_a):.3f} ({min(a_over_a):.3f}-{max(a_over_a):.3f})")
EOF
