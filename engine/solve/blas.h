#pragma once
// The BLAS routines the supernodal factorisations use (Fortran interface; the system's
// libblas.so.3 is OpenBLAS, as for CHOLMOD), column-major throughout.
#include <cstddef>

extern "C" void dgemm_(const char* transa, const char* transb, const int* m, const int* n, const int* k,
                       const double* alpha, const double* a, const int* lda, const double* b, const int* ldb,
                       const double* beta, double* c, const int* ldc, std::size_t transa_len,
                       std::size_t transb_len);
extern "C" void dtrsm_(const char* side, const char* uplo, const char* transa, const char* diag, const int* m,
                       const int* n, const double* alpha, const double* a, const int* lda, double* b, const int* ldb,
                       std::size_t side_len, std::size_t uplo_len, std::size_t transa_len, std::size_t diag_len);

namespace pfem::blas {

// c (m x n, leading dimension ldc) = beta c + alpha op(a) op(b), op(a) m x k, op(b) k x n; 'N' or
// 'T' for op.
inline void gemm(char ta, char tb, int m, int n, int k, double alpha, const double* a, int lda, const double* b,
                 int ldb, double beta, double* c, int ldc) {
  dgemm_(&ta, &tb, &m, &n, &k, &alpha, a, &lda, b, &ldb, &beta, c, &ldc, 1, 1);
}

// Solves op(a) x = b (side 'L') or x op(a) = b (side 'R') in place of b (m x n), a triangular
// ('L' lower or 'U' upper; diag 'U' unit, 'N' not).
inline void trsm(char side, char uplo, char ta, char diag, int m, int n, const double* a, int lda, double* b,
                 int ldb) {
  const double one = 1.0;
  dtrsm_(&side, &uplo, &ta, &diag, &m, &n, &one, a, &lda, b, &ldb, 1, 1, 1, 1);
}

}  // namespace pfem::blas
