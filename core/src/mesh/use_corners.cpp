#include "wefm/core/mesh/use_corners.hpp"
#include "wefm/core/sys/huge_pages.hpp"

namespace wefm {

UseCorners use_corners(const Topology& tp) {
  UseCorners uc;
  uc.start.assign(static_cast<size_t>(tp.use_count) + 1, 0);
  for (Index u : tp.corner_use) ++uc.start[static_cast<size_t>(u) + 1];
  for (size_t i = 1; i < uc.start.size(); ++i) uc.start[i] += uc.start[i - 1];
  assign_huge(uc.corner, tp.corner_use.size());
  std::vector<Index> fill(uc.start.begin(), uc.start.end() - 1);
  for (size_t c = 0; c < tp.corner_use.size(); ++c)
    uc.corner[static_cast<size_t>(fill[static_cast<size_t>(tp.corner_use[c])]++)] = static_cast<Index>(c);
  return uc;
}

}  // namespace wefm
