// Chords two faces make alike (shared_chords.hpp).
#include "shared_chords.hpp"

#include <algorithm>
#include <set>
#include <unordered_map>

#include "model_mesh.hpp"

namespace wefm_cli {

std::vector<size_t> faces_with_shared_chords(const std::vector<FaceMeshView>& faces, const std::vector<size_t>& lies_on, double tol) {
  PointGrid grid(tol);
  std::vector<double> points;  // one per matched boundary node
  auto id_of = [&](const double* p) {
    int32_t id = grid.find(p, points);
    if (id < 0) {
      id = static_cast<int32_t>(points.size() / 3);
      points.insert(points.end(), p, p + 3);
      grid.add(p, id);
    }
    return id;
  };
  struct Use {
    size_t face;
    bool chord;
  };
  std::unordered_map<uint64_t, std::vector<Use>> uses;  // by pair of matched nodes
  for (size_t i = 0; i < faces.size(); ++i) {
    const std::vector<double>& xyz = *faces[i].xyz;
    const std::vector<int32_t>& tris = *faces[i].tris;
    if (tris.empty()) continue;
    std::vector<int32_t> id(xyz.size() / 3, -1);
    for_each_boundary_pair(xyz.size() / 3, tris, [&](int32_t a, int32_t b, int n) {
      for (int32_t v : {a, b})
        if (id[static_cast<size_t>(v)] < 0) id[static_cast<size_t>(v)] = id_of(&xyz[3 * static_cast<size_t>(v)]);
      const uint32_t p = static_cast<uint32_t>(id[static_cast<size_t>(a)]), q = static_cast<uint32_t>(id[static_cast<size_t>(b)]);
      if (p == q) return;  // a seam's two sides, or a collapsed edge: welding's business
      uses[(static_cast<uint64_t>(std::min(p, q)) << 32) | std::max(p, q)].push_back({i, n >= 2});
    });
  }
  auto alike = [&](size_t i, size_t j) { return lies_on[i] == j + 1 || lies_on[j] == i + 1 || (lies_on[i] && lies_on[i] == lies_on[j]); };
  std::set<size_t> out;
  for (const auto& [key, list] : uses)
    for (const Use& u : list)
      if (u.chord)
        for (const Use& w : list)
          if (w.face != u.face && !alike(u.face, w.face)) out.insert(u.face);
  return {out.begin(), out.end()};
}

}  // namespace wefm_cli
