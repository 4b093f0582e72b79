#pragma once
// The WEFM energy (METHOD §5) as a Hermitian matrix K = A^H A + sum_d mu B_d^H W_d B_d over uses.
// `threads` (Options::threads; <= 1 runs in the caller's thread) splits the work; every result is
// bit-identical for any thread count (see parallel.hpp).
#include <vector>

#include "wefm/core/method/coefficients.hpp"
#include "wefm/core/method/options.hpp"

namespace wefm {

// sigma_h = alpha_h + i beta_h rho_h^s for every half-edge (rho = 1 when rho is empty or s == 0).
std::vector<Complex> compute_sigma(const Coefficients& c, const std::vector<double>& rho, double s, int threads = 1);

// w_h of eq. 9: (1/beta_h) (sum of 1/beta over the half-edges opposite the same use)^(-k).
std::vector<double> compute_weights(const Topology& topo, const Coefficients& c, double k, int threads = 1);

// Surface term operator A with the weights of eq. 9. PerUse: one row per use, the weighted sum of
// its predictions' errors (eq. 7 as printed). PerHalfEdge: one row per half-edge, each prediction's
// error weighted by sqrt(w_h), so errors cannot cancel inside a sum (see Options::residual).
SpMatC assemble_surface_operator(const Topology& topo, const Coefficients& c, const std::vector<Complex>& sigma, double k,
                                 Residual form, int threads = 1);

// Boundary term operator (eq. 10) with rows already scaled by sqrt(mu / l_bar). `unwind` < 1 scales
// the goal turning angles of gentle turns (under 30 degrees) toward straight, corners unchanged.
SpMatC assemble_boundary_operator(const TriMesh& mesh, const Topology& topo, const Coefficients& c, double mu,
                                  double unwind = 1.0);
// Its pattern (every value 1) without the coefficients: from the mesh and the loops alone.
SpMatC boundary_operator_pattern(const TriMesh& mesh, const Topology& topo, double mu);
// B^H B, compressed: the boundary term's part of K (empty for a null or empty B).
SpMatC boundary_gram(const SpMatC* B);

// K = A^H A (+ B^H B). Full Hermitian matrix, compressed, rows sorted in each column.
SpMatC assemble_energy(const SpMatC& A, const SpMatC* B, int threads = 1);

// The same K without building A: for the per-half-edge residual straight into its pattern
// (energy_assembler.hpp), in one pass and without A's nine entries per triangle in memory;
// equal to assemble_energy(assemble_surface_operator(...), B) up to rounding.
SpMatC assemble_energy(const Topology& topo, const Coefficients& c, const std::vector<Complex>& sigma, double k, Residual form,
                       const SpMatC* B, int threads = 1);

// Energy value |A z|^2 + |B z|^2.
double energy_value(const SpMatC& A, const SpMatC* B, const VectorXc& z);

}  // namespace wefm
