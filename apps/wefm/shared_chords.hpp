#pragma once
// `wefm mesh-model`: chords two faces make alike. Where two faces share two boundary nodes across a
// narrow or coarse part (the halves of a thin tube, a half tube and its symmetry plane), each face's
// mesher may join them by the same straight edge inside the face: welded, that edge has four
// triangles. Such faces are meshed again with every chord off the surface split
// (wefm_mesh_options.split_chords), which puts a node of each face's own between the two.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace wefm_cli {

struct FaceMeshView {
  const std::vector<double>* xyz;      // 3 per node
  const std::vector<int32_t>* tris;    // 3 per triangle; empty for a face with no mesh
};

// The faces (indices into `faces`) with an edge inside them between two of their boundary nodes that
// another face's mesh also has, as a chord or on its boundary. Boundary nodes are matched within
// `tol`, as welding matches them. `lies_on[i]`: 1 + the face that face i lies on (coincident faces of
// touching volumes, meshed alike on purpose), else 0; such pairs do not count.
std::vector<size_t> faces_with_shared_chords(const std::vector<FaceMeshView>& faces, const std::vector<size_t>& lies_on, double tol);

}  // namespace wefm_cli
