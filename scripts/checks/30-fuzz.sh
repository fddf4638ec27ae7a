#!/usr/bin/env bash
# Each libFuzzer harness (tests/fuzz/) for a bounded time from the seed corpus in
# tests/fuzz/corpus/ (the bundled scenes, small G-buffers, mesh files, HTTP requests and the
# regression inputs). Fails on a crash, a sanitizer report, a leak, an allocation over
# -malloc_limit_mb or an input slower than -timeout (a reader that spins); fuzz_http also on a 500
# or an error without a JSON body. The scene, G-buffer and mesh harnesses load no OpenCL and run
# with LeakSanitizer on; fuzz_http shades with PoCL behind the server and runs with it off, as the
# sanitizer suite does (PoCL keeps allocations until exit). FUZZ_SECONDS (default 60) sets the time
# per harness; CONTRIBUTING.md "Reliability" says how to run them longer.
set -euo pipefail
cd "$(dirname "$0")/../.."
source scripts/checks/lib/sanitizer_build.sh
seconds="${FUZZ_SECONDS:-60}"
configure_sanitizer_build
cmake --build "$sanitizer_dir" -j2 --target fuzz_scene fuzz_gbuffer fuzz_mesh fuzz_http > "$sanitizer_dir/fuzz-build.log" 2>&1 ||
  { tail -40 "$sanitizer_dir/fuzz-build.log"; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
# PoCL's kernel cache is the main suite's where scripts/test.sh set it: the same kernels, compiled
# once (five times faster here); what the sanitizers check is phongcl's host code, not PoCL's compiler.
export POCL_CACHE_DIR="${POCL_CACHE_DIR:-$PWD/$sanitizer_dir/pocl-cache}"
# fuzz TARGET: one harness for $seconds; on a finding prints it, keeps the reproducer and fails.
fuzz() {
  local target=$1 log="$work/$1.log" options=()
  mkdir -p "$work/$target"  # new inputs go here, so the committed seeds stay as they are
  if [ "$target" = http ]; then
    # use_sigaltstack=0: as in 20-sanitizers.sh (LLVM inside PoCL replaces the alternate stack).
    export ASAN_OPTIONS=detect_leaks=0:abort_on_error=1:use_sigaltstack=0
    # A new light count or precision builds a kernel: seconds on a busy machine, not a hang.
    options=(-dict="$PWD/tests/fuzz/http.dict" -rss_limit_mb=4096 -timeout=60)
  else
    export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1
    options=(-rss_limit_mb=2048 -timeout=10)
  fi
  if ! (cd "$work" && "$OLDPWD/$sanitizer_dir/tests/fuzz/fuzz_$target" -max_total_time="$seconds" \
          -malloc_limit_mb=1024 -max_len=65536 -print_final_stats=1 "${options[@]}" \
          "$target" "$OLDPWD/tests/fuzz/corpus/$target") > "$log" 2>&1; then
    grep -E -m 30 "ERROR|SUMMARY|runtime error|out-of-memory|malloc\(|#[0-9]+ 0x" "$log" || true
    # fuzz_http's own finding: its reason and the response it refused.
    sed -n '/^fuzz_http: /,/^--- end ---$/p' "$log" | head -40
    mkdir -p "$sanitizer_dir/fuzz-findings"
    cp "$work"/crash-* "$work"/leak-* "$work"/oom-* "$work"/timeout-* "$sanitizer_dir/fuzz-findings/" 2> /dev/null || true
    cp "$log" "$sanitizer_dir/fuzz-findings/"
    echo "fuzz_$target: FAILED (reproducer in $sanitizer_dir/fuzz-findings/, log above)"
    return 1
  fi
}
# The three readers' harnesses are single-threaded: they share the machine's two cores. fuzz_http
# shades with PoCL's threads, so it runs alone after them.
fuzz scene & scene=$!
fuzz gbuffer & gbuffer=$!
fuzz mesh & mesh=$!
failed=0
wait "$scene" || failed=1
wait "$gbuffer" || failed=1
wait "$mesh" || failed=1
[ "$failed" = 0 ] || exit 1
fuzz http
summary=()
for target in scene gbuffer mesh http; do
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$work/$target.log")
  summary+=("fuzz_$target ${runs} runs in ${seconds} s")
done
echo "fuzz: no crash, leak, oversize allocation or escaped exception: ${summary[*]}"
