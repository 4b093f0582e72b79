#pragma once
// Quality of a 3D mesh (METHOD §9.4, eq. 11 and 12).
#include <cmath>
#include <vector>

#include "wefm/common/lo_lambda.hpp"
#include "wefm/core/meshing/domain_mesh.hpp"

namespace wefm::meshing {

// Lo's lambda (common/lo_lambda): 1 for an equilateral triangle, 0 when flat.
inline double lo_lambda(const Vec3& a, const Vec3& b, const Vec3& c) { return wefm_common::lo_lambda(a, b, c); }

// Minimum over the four corners of the corner Jacobian (e1 x e2 . n) / (|e1| |e2|), n the quad's
// mean normal: 1 for a rectangle, <= 0 for a folded or inverted quad.
double scaled_jacobian(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

// Wiggle factor (eq. 12) of one rail line: (1/n) sum_j |L_j+1 - L_j|^2 / Lbar^2 over its segment
// vectors L_j, with the component along the surface normal at the node removed: the bending a
// curved surface imposes on every line is not waviness of the mesh, and without this a rail round a
// cylinder would never score 0. Lbar is the mean segment length.
double wiggle(const std::vector<Vec3>& nodes, const std::vector<Vec3>& normals);

// Fills the quality fields of m.report from m's 3D nodes, elements and rails.
void measure_quality(DomainMesh& m);

}  // namespace wefm::meshing
