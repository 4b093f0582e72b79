#pragma once
// Boundary discretisation (METHOD §9.1): every loop cut into nodes at a 3D arc length near h.
// Breaks (always nodes) are the ends of the loop's edges and the vertices whose UV turning angle
// exceeds the corner threshold on any loop through them; each piece between breaks gets
// round(L / h) uniform intervals of its 3D arc length. The two sides of a repeated edge run along
// the same 3D chain with the same breaks, so their nodes are the same 3D points: counts match.
#include <map>
#include <vector>

#include "wefm/core/meshing/predicates.hpp"
#include "wefm/core/mesh/topology.hpp"

namespace wefm::meshing {

struct LoopNodes {
  std::vector<P2> uv;    // cyclic, in loop order (face on the left)
  std::vector<Vec3> xyz;
  std::vector<Index> use;  // the loop use at a node placed on a mesh vertex, else -1
};

// Caller-given 3D nodes per edge, in the edge's direction, including both ends.
using EdgeNodes = std::map<Index, std::vector<Vec3>>;

// UV turning angle (radians, left turn positive) at position j of loop l.
double turning_angle(const Topology& topo, const VectorXc& uv, Index loop, size_t j);

// With `gradation` g > 0 the pieces not given by the caller shrink towards a break where another
// piece has shorter segments and grow back by g per unit length (graded_spacing.hpp).
std::vector<LoopNodes> discretise_loops(const TriMesh& mesh, const Topology& topo, const VectorXc& uv, double h,
                                        double corner_angle_rad, const EdgeNodes& given, double gradation = 0);

// Nodes along positions [from, to] (cyclic, to after from) of loop l at n uniform 3D intervals.
LoopNodes discretise_run(const TriMesh& mesh, const Topology& topo, const VectorXc& uv, Index loop, size_t from,
                         size_t to, Index n);

// 3D length of the loop run from position `from` to `to` (cyclic).
double run_length(const TriMesh& mesh, const Topology& topo, Index loop, size_t from, size_t to);

}  // namespace wefm::meshing
