#pragma once
// Target 3D element size over a face: h away from the boundary, graded down towards boundary
// segments shorter than h. A face next to a narrow one gets edge nodes at the narrow face's size;
// meshing its inside at h would stand elements of size h on segments of h/4 (Lo's lambda ~0.3).
// The field is min(h, l_s + g |x - c_s|) over the segments s (length l_s, midpoint c_s), with
// distances in 3D, so the grading does not depend on the domain's UV scale.
#include <vector>

#include "wefm/core/meshing/boundary.hpp"

namespace wefm::meshing {

// The growth rate free meshing uses, for the field and for the boundary pieces
// (discretise_loops). Measured on the CAD sample: 0.2 drops Ball's min lambda to 0.48, 0.4 lowers
// its lambda_mesh.
constexpr double kSizeGradation = 0.3;

class SizeField {
 public:
  // `gradation` g: size growth per unit distance from a short segment (> 0).
  SizeField(const std::vector<LoopNodes>& loops, double h, double gradation);
  double at(const Vec3& x) const;
  double h() const { return h_; }

 private:
  struct Source {
    Vec3 c;
    double l;
  };
  // A box of the k-d tree over the sources' midpoints: the sources' bounding box and their shortest
  // length; children `left` and `right`, or -1 for a leaf, whose sources are src_[first, last).
  struct Node {
    Vec3 lo, hi;
    double lmin;
    Index first, last, left, right;
  };
  static constexpr Index kLeaf = 8;
  Index build(Index first, Index last);
  // Smallest l + g |x - c| any source in the box can give (a lower bound).
  double bound(const Node& n, const Vec3& x) const;
  void visit(Index node, const Vec3& x, double& best) const;

  double h_, g_;
  std::vector<Source> src_;
  std::vector<Node> nodes_;
};

}  // namespace wefm::meshing
