# The lab: what checks and measures the product. It links the product; nothing in the product links
# it, and none of it is installed. The C++ peers' native-ISA code stays here.
phongcl_lab_room(reference)
phongcl_lab_room(report)
# The C++ peers are OpenMP programs, as strong CPU code of this kind is written; the product's host
# passes use their own threads (common/host_threads.h).
phongcl_lab_room(peers DEPS OpenMP::OpenMP_CXX)
# The C++ peers must be strong: every vector unit, contraction to FMA, and no errno/trap semantics
# (which stop GCC from vectorising floor and if-converting selects; results are unchanged: we never
# read errno or unmask FP exceptions). 512-bit vectors: GCC's Sapphire Rapids tuning prefers 256.
target_compile_options(phongcl_peers PRIVATE -O3 -march=native -mprefer-vector-width=512 -fno-math-errno
                       -fno-trapping-math -ffp-contract=fast)
# Their loops' vectorisation requests (lab/peers/simd_request.h): off in the sanitizer build, whose
# checks make those loops unvectorisable.
option(PHONGCL_PEERS_VECTORISED "The C++ peers' omp simd requests (OFF where they cannot be honoured)" ON)
if(NOT PHONGCL_PEERS_VECTORISED)
  target_compile_definitions(phongcl_peers PRIVATE PHONGCL_PEERS_SCALAR)
endif()
phongcl_lab_room(stability DEPS phongcl_reference phongcl_report)
# The fits and integrals whose tables the kernels read: the LTC table of kernels/ltc_table.h and the
# Principled BSDF v2's GGX tables of kernels/principled_tables.h.
phongcl_lab_room(fit DEPS phongcl_reference OpenMP::OpenMP_CXX)

# The sanitizer build's references and fits go uninstrumented, at -O2: the sanitizers are there for the
# product's code (and the tests', the peers', the stability runner's), while the double quadratures the
# tests hold the kernels to ran many times slower under ASan, one test (88 s) past ctest's 600 s.
option(PHONGCL_LAB_UNSANITIZED "Build the lab's reference and fit rooms without sanitizers (the sanitizer build)" OFF)
if(PHONGCL_LAB_UNSANITIZED)
  foreach(room reference fit)
    target_compile_options(phongcl_${room} PRIVATE -fno-sanitize=all -O2)
  endforeach()
endif()

add_library(phongcl_lab INTERFACE)
target_link_libraries(phongcl_lab INTERFACE phongcl_reference phongcl_report phongcl_peers phongcl_stability phongcl_fit)

# The Embree peer of the shadow rays (optional, as the Halide peer is: without libembree-dev its rows
# say SKIP). PHONGCL_HAVE_EMBREE tells the lab's commands and tests it is there.
find_package(embree 3 CONFIG QUIET)
if(embree_FOUND)
  phongcl_lab_room(embree DEPS phongcl_peers embree OpenMP::OpenMP_CXX)
  target_compile_definitions(phongcl_embree PUBLIC PHONGCL_HAVE_EMBREE)
  target_link_libraries(phongcl_lab INTERFACE phongcl_embree)
endif()

# phongcl-lab: reference, compare, bench, stability. `phongcl` hands those commands to it.
file(GLOB PHONGCL_LAB_CLI_SOURCES CONFIGURE_DEPENDS lab/cli/*.cpp)
add_executable(phongcl-lab ${PHONGCL_LAB_CLI_SOURCES})
target_link_libraries(phongcl-lab PRIVATE phongcl_lab phongcl_cli_support)

# The Halide peer of `phongcl bench --throughput`, a benchmark program (PHONGCL_BUILD_BENCH), when
# Halide 14 is installed (scripts/packages/halide.txt); without it the benchmark's halide rows say
# SKIP and its tests skip. Found by hand: Debian's HalideConfig.cmake pulls in LLVM's CMake package
# (which needs a C compiler enabled) although the shared library needs nothing of it.
if(PHONGCL_BUILD_BENCH)
  find_path(HALIDE_INCLUDE_DIR Halide.h PATH_SUFFIXES halide14)
  find_library(HALIDE_LIBRARY NAMES Halide14 Halide)
  if(HALIDE_INCLUDE_DIR AND HALIDE_LIBRARY)
    add_subdirectory(lab/peers/halide_peer)
  else()
    message(STATUS "Halide not found: no Halide peer (phongcl bench --throughput reports its rows as SKIP)")
  endif()
endif()
