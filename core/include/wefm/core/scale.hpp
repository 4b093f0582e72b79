#pragma once
// For s > 0 the energy is not scale-free: sigma depends on rho = L / |z2 - z1|. With the vector
// gauge fixing the size, the size must follow the energy's own preference or the fixed point
// converges to a stretched layout. This computes the uniform scale a minimising the surface
// energy of a * (z - center) with rho recomputed from the scaled layout.
#include "wefm/core/coefficients.hpp"

namespace wefm {

double optimal_scale(const Topology& topo, const Coefficients& c, const VectorXc& z, double s, double k, Complex center);

}  // namespace wefm
