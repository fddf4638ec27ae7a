#pragma once
// The peers' requests to vectorise a loop (`omp simd`), where the build can honour them. A sanitizer
// build's per-access checks make these loops unvectorisable, and clang then says it could not
// (-Wpass-failed); that build (PHONGCL_PEERS_VECTORISED=OFF) runs them as plain loops, which is all a
// correctness check of the peers needs. The benchmarks' builds keep every request.
#define PHONGCL_PRAGMA(text) _Pragma(#text)
#ifdef PHONGCL_PEERS_SCALAR
#define PHONGCL_SIMD(clauses)
#define PHONGCL_PARALLEL_FOR_SIMD(clauses) PHONGCL_PRAGMA(omp parallel for clauses)
#else
#define PHONGCL_SIMD(clauses) PHONGCL_PRAGMA(omp simd clauses)
#define PHONGCL_PARALLEL_FOR_SIMD(clauses) PHONGCL_PRAGMA(omp parallel for simd clauses)
#endif
