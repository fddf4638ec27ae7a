# Sourced by 20-sanitizers.sh and 30-fuzz.sh (in lib/ so that test.sh does not run it as a check): one clang ASan+UBSan build in build/sanitizers/,
# with libFuzzer coverage hooks, shared by the test suite and the fuzzers (one build, not two).
# -O1 and line tables only: quicker to build than -O2 -g, and reports still name file and line. The
# test programs too: at -O0 their brute-force references (GLM in double, not inlined) ran 3 to 4
# times slower, and the suite took 757 s against 446 s, for a test file compiled in 3.7 s against 5.1. A
# unity build (CMake compiles up to 8 of a room's files as one), so the heavy headers (CLI11, JSON,
# OpenEXR, the standard library) are parsed once per batch: 358 s against 646 s here. It also
# refuses a helper written twice in one room. Warnings are errors here too; the C++ peers' loops go
# without their vectorisation requests, which UBSan's checks make impossible (lab/peers/simd_request.h).
# The lab's references and fits are built without sanitizers at -O2 (cmake/Lab.cmake,
# PHONGCL_LAB_UNSANITIZED): what is checked is the product; their quadratures are what the tests wait on.
sanitizer_dir=build/sanitizers
configure_sanitizer_build() {
  local launcher=()
  command -v ccache > /dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  cmake -S . -B "$sanitizer_dir" -G Ninja -DCMAKE_BUILD_TYPE=None -DCMAKE_CXX_COMPILER=clang++-14 \
    -DCMAKE_CXX_FLAGS="-O1 -gline-tables-only -fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer -fsanitize=fuzzer-no-link" \
    -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" \
    -DPHONGCL_BUILD_TESTS=ON -DPHONGCL_BUILD_BENCH=OFF -DPHONGCL_BUILD_PYTHON=OFF -DPHONGCL_BUILD_FUZZERS=ON -DCMAKE_UNITY_BUILD=ON \
    -DPHONGCL_WERROR=ON -DPHONGCL_PEERS_VECTORISED=OFF -DPHONGCL_LAB_UNSANITIZED=ON "${launcher[@]}" > /dev/null
}
