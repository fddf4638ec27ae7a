#!/usr/bin/env bash
# Each libFuzzer harness (tests/fuzz/) for a bounded time from the seed corpus in
# tests/fuzz/corpus/ (the bundled scenes, small G-buffers and the regression inputs). Fails on a
# crash, a sanitizer report, a leak (LeakSanitizer on: the harnesses load no OpenCL), an allocation
# over -malloc_limit_mb or an input slower than -timeout. FUZZ_SECONDS (default 60) sets the time
# per harness; CONTRIBUTING.md "Reliability" says how to run them longer.
set -euo pipefail
cd "$(dirname "$0")/../.."
source scripts/checks/lib/sanitizer_build.sh
seconds="${FUZZ_SECONDS:-60}"
configure_sanitizer_build
cmake --build "$sanitizer_dir" -j2 --target fuzz_scene fuzz_gbuffer > "$sanitizer_dir/fuzz-build.log" 2>&1 ||
  { tail -40 "$sanitizer_dir/fuzz-build.log"; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
summary=()
for target in scene gbuffer; do
  mkdir -p "$work/$target"  # new inputs go here, so the committed seeds stay as they are
  log="$work/$target.log"
  if ! (cd "$work" && "$OLDPWD/$sanitizer_dir/tests/fuzz/fuzz_$target" -max_total_time="$seconds" -timeout=10 \
          -malloc_limit_mb=1024 -rss_limit_mb=2048 -max_len=65536 -print_final_stats=1 \
          "$target" "$OLDPWD/tests/fuzz/corpus/$target") > "$log" 2>&1; then
    grep -E -m 30 "ERROR|SUMMARY|runtime error|out-of-memory|malloc\(|#[0-9]+ 0x" "$log" || true
    mkdir -p "$sanitizer_dir/fuzz-findings"
    cp "$work"/crash-* "$work"/leak-* "$work"/oom-* "$work"/timeout-* "$sanitizer_dir/fuzz-findings/" 2> /dev/null || true
    echo "fuzz_$target: FAILED (reproducer in $sanitizer_dir/fuzz-findings/, log above)"
    exit 1
  fi
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
  summary+=("fuzz_$target ${runs} runs in ${seconds} s")
done
echo "fuzz: no crash, leak or oversize allocation: ${summary[*]}"
