#pragma once
// The Fortran BLAS and LAPACK routines the own supernodal kernels call (OpenBLAS provides them,
// CHOLMOD links them), declared as CHOLMOD calls them. CHOLMOD builds only.
#ifdef WEFM_HAVE_CHOLMOD
extern "C" {
void zherk_(const char* uplo, const char* trans, const int* n, const int* k, const double* alpha, const void* a, const int* lda,
            const double* beta, void* c, const int* ldc);
void zgemm_(const char* ta, const char* tb, const int* m, const int* n, const int* k, const void* alpha, const void* a, const int* lda,
            const void* b, const int* ldb, const void* beta, void* c, const int* ldc);
void ztrsm_(const char* side, const char* uplo, const char* ta, const char* diag, const int* m, const int* n, const void* alpha,
            const void* a, const int* lda, void* b, const int* ldb);
void zpotrf_(const char* uplo, const int* n, void* a, const int* lda, int* info);
}
#endif
