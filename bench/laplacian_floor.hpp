#pragma once
// The floor every wefm figure is divided by: one CHOLMOD factorisation and one solve of the face's
// cotangent Laplacian (n x n with one vertex pinned), the system LSCM- and BFF-class methods pay
// for. A wefm solve cannot beat it by much, so "x floor" compares machines and solvers fairly.
#include <cstdint>
#include <string>

#include "face_generator.hpp"

namespace wefm_bench {

struct FloorResult {
  bool ok = false;
  std::string error;
  int64_t n = 0;             // unknowns (vertices - 1)
  int64_t matrix_nnz = 0;    // stored lower triangle
  double factor_nnz = 0;     // CHOLMOD's lnz
  double flops = 0;          // CHOLMOD's fl
  std::string ordering;      // the ordering CHOLMOD's default strategy picked
  double assembly = 0, analysis = 0, factorization = 0, solve = 0;
  double cpu = 0;  // CPU seconds (all threads) of analysis + factorisation + solve
  double total() const { return analysis + factorization + solve; }  // the floor (assembly excluded)
};

// complex_arithmetic: factorise the same matrix stored as complex (imaginary parts zero), which is
// what a Hermitian n x n formulation of the WEFM system would cost, for comparison.
FloorResult measure_floor(const Face& face, bool complex_arithmetic);

// Whether this build has CHOLMOD for the floor.
bool floor_available();

}  // namespace wefm_bench
