#pragma once
// How many corners an element of a mesh with `nodes_per_element` nodes each has: in a quad-dominant
// mesh (four nodes per element) a triangle is marked by -1 as its fourth node. One rule for the
// library's meshes and the tool's writers, which read the same arrays across the C API.
#include <cstddef>

namespace wefm_common {

template <class I>
inline std::size_t element_corners(const I* element, int nodes_per_element) {
  return nodes_per_element == 4 && element[3] < 0 ? 3 : static_cast<std::size_t>(nodes_per_element);
}

}  // namespace wefm_common
