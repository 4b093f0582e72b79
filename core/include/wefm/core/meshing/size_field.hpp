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
  // True when a source at squared distance d2 cannot reach below its length + gap.
  bool beyond(double d2, double gap) const;

  struct Source {
    Vec3 c;
    double l;
  };
  double h_, g_;
  double reach_ = 0;  // farthest distance at which a source still lowers the size below h
  std::vector<Source> src_;
  // Uniform grid of the sources, cells at least `reach_` wide: a query reads a 3x3x3 block.
  Vec3 lo_ = Vec3::Zero();
  double cell_ = 1;
  int n_[3] = {1, 1, 1};
  std::vector<Index> start_, items_;
};

}  // namespace wefm::meshing
