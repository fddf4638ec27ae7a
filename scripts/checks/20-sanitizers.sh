#!/usr/bin/env bash
# The test suite built with clang's AddressSanitizer and UndefinedBehaviorSanitizer, in its
# own build directory. Leak detection is off here: PoCL and LLVM keep allocations alive until exit
# (compiled programs, LLVM's static registries) that LeakSanitizer reports from their own frames;
# leaks in phongcl's readers are caught by 30-fuzz.sh, whose harnesses load no OpenCL and run with
# leak detection on.
set -euo pipefail
cd "$(dirname "$0")/../.."
source scripts/checks/lib/sanitizer_build.sh
start=$SECONDS
configure_sanitizer_build
cmake --build "$sanitizer_dir" -j2 > "$sanitizer_dir/build.log" 2>&1 || { tail -40 "$sanitizer_dir/build.log"; exit 1; }
built=$((SECONDS - start))
# use_sigaltstack=0: LLVM (inside PoCL) replaces a thread's alternate signal stack with one of its
# own when it compiles a kernel on that thread (shade starts OpenCL on a thread while the G-buffer
# is read), and ASan then aborts at that thread's exit, failing to unmap a stack it did not map.
export ASAN_OPTIONS=detect_leaks=0:abort_on_error=1:strict_string_checks=1:use_sigaltstack=0
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
# PoCL's kernel cache is the main suite's where scripts/test.sh set it: the same kernels, compiled
# once (five times faster here); what the sanitizers check is phongcl's host code, not PoCL's compiler.
export POCL_CACHE_DIR="${POCL_CACHE_DIR:-$PWD/$sanitizer_dir/pocl-cache}"
# The kernel-accuracy sweeps are the main suite's alone: each shades every kernel variant, lane
# count, exponent or roughness against the double reference, repeating dozens of times the host
# path (pack, build, launch, read back) that its suite's other tests run here once, and together
# they were half of this stage's time.
sweeps='^(AreaLights\.SpecularMatchesTheReference|AreaLtc\.Principled(V2)?HighlightMatchesTheReference'
sweeps+='|Specular\.EachModelMatchesTheReferenceInEveryVariantAndLaneCount|Shading\.EveryLaneCountMatchesReference'
sweeps+='|Lights\.EveryFeatureMatchesReferenceInEveryVariantAndLaneCount|Lights\.GroupsAddUpToTheImageInEveryVariant'
sweeps+='|KernelVariants\.EveryVariantBuilds)$'
log="$sanitizer_dir/ctest.log"
if ! ctest --test-dir "$sanitizer_dir" -j2 --output-on-failure -E "$sweeps" > "$log" 2>&1; then
  grep -E -m 40 "ERROR: AddressSanitizer|runtime error|Failed|\*\*\*" "$log" || true
  echo "sanitizers: FAILED (full log: $log)"
  exit 1
fi
echo "sanitizers: $(grep -Eo '[0-9]+ tests passed|100% tests passed, 0 tests failed out of [0-9]+' "$log" | tail -1)" \
     "under ASan+UBSan, the main suite's $(ctest --test-dir "$sanitizer_dir" -N -R "$sweeps" | grep -c 'Test *#') sweeps left out (build ${built} s, tests $((SECONDS - start - built)) s)"
