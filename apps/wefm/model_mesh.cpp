#include "model_mesh.hpp"
#include "wefm/common/lo_lambda.hpp"
#include "wefm/common/scaled_jacobian.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <unordered_set>

namespace wefm_cli {

namespace {

uint64_t cell_key(int64_t i, int64_t j, int64_t k) {
  // Mixes three cell coordinates into one key; collisions only cost a distance test.
  return static_cast<uint64_t>(i) * 73856093ULL ^ static_cast<uint64_t>(j) * 19349663ULL ^
         static_cast<uint64_t>(k) * 83492791ULL;
}

// Spreads a cell key over PointGrid's slots (the keys of neighbouring cells differ in few bits).
size_t spread(uint64_t key) {
  key ^= key >> 33;
  key *= 0xff51afd7ed558ccdULL;
  key ^= key >> 33;
  return static_cast<size_t>(key);
}

uint64_t pair_key(int32_t a, int32_t b) {
  if (a > b) std::swap(a, b);
  return (static_cast<uint64_t>(static_cast<uint32_t>(a)) << 32) | static_cast<uint32_t>(b);
}

// Every edge of a triangle list with the triangles that use it: per edge (a, b), a < b, its uses in
// triangle order, the edges grouped by their smaller node. The model-wide checks walk this once
// instead of hashing every edge of every triangle.
class EdgeTable {
 public:
  EdgeTable(size_t nodes, const std::vector<int32_t>& tris) : start_(nodes + 1, 0) {
    for (size_t t = 0; t + 2 < tris.size(); t += 3)
      for (size_t c = 0; c < 3; ++c) ++start_[static_cast<size_t>(std::min(tris[t + c], tris[t + (c + 1) % 3])) + 1];
    for (size_t v = 0; v < nodes; ++v) start_[v + 1] += start_[v];
    uses_.resize(start_[nodes]);
    std::vector<size_t> fill(start_.begin(), start_.end() - 1);
    for (size_t t = 0; t + 2 < tris.size(); t += 3)
      for (size_t c = 0; c < 3; ++c) {
        const int32_t a = tris[t + c], b = tris[t + (c + 1) % 3];
        uses_[fill[static_cast<size_t>(std::min(a, b))]++] = {std::max(a, b), static_cast<int32_t>(t / 3)};
      }
    // Within a node's group by the other node; the triangles of one edge stay in order.
    for (size_t v = 0; v < nodes; ++v)
      std::sort(uses_.begin() + static_cast<std::ptrdiff_t>(start_[v]), uses_.begin() + static_cast<std::ptrdiff_t>(start_[v + 1]));
  }

  // Calls f(a, b, first, last) once per edge, [first, last) its uses (.second: the triangle).
  template <class F>
  void for_each(F f) const {
    for (size_t a = 0; a + 1 < start_.size(); ++a)
      for (size_t k = start_[a]; k < start_[a + 1];) {
        size_t e = k + 1;
        while (e < start_[a + 1] && uses_[e].first == uses_[k].first) ++e;
        f(static_cast<int32_t>(a), uses_[k].first, uses_.data() + k, uses_.data() + e);
        k = e;
      }
  }

  // How many triangles use the edge (a, b).
  int uses(int32_t a, int32_t b) const {
    if (a > b) std::swap(a, b);
    const auto first = uses_.begin() + static_cast<std::ptrdiff_t>(start_[static_cast<size_t>(a)]);
    const auto last = uses_.begin() + static_cast<std::ptrdiff_t>(start_[static_cast<size_t>(a) + 1]);
    const auto lo = std::lower_bound(first, last, std::make_pair(b, std::numeric_limits<int32_t>::min()));
    const auto hi = std::lower_bound(lo, last, std::make_pair(b, std::numeric_limits<int32_t>::max()));
    return static_cast<int>(hi - lo);
  }

 private:
  std::vector<size_t> start_;
  std::vector<std::pair<int32_t, int32_t>> uses_;  // (larger node, triangle)
};

// Lo's lambda below this is a triangle with no area to speak of: a solver divides by it.
constexpr double kZeroAreaLambda = 1e-6;
// How many unexplained edges conformity() lists by position.
constexpr size_t kListedDefects = 20;

}  // namespace

size_t PointGrid::slot(uint64_t key) const {
  const size_t mask = keys_.size() - 1;
  size_t s = spread(key) & mask;
  while (first_[s] >= 0 && keys_[s] != key) s = (s + 1) & mask;
  return s;
}

void PointGrid::grow() {
  const std::vector<uint64_t> keys = std::move(keys_);
  const std::vector<int32_t> first = std::move(first_), last = std::move(last_);
  const size_t n = std::max<size_t>(64, 2 * keys.size());
  keys_.assign(n, 0);
  first_.assign(n, -1);
  last_.assign(n, -1);
  for (size_t k = 0; k < keys.size(); ++k)
    if (first[k] >= 0) {
      const size_t s = slot(keys[k]);
      keys_[s] = keys[k];
      first_[s] = first[k];
      last_[s] = last[k];
    }
}

void PointGrid::add(const double* p, int32_t id) {
  if (2 * (cells_ + 1) > keys_.size()) grow();
  const uint64_t key = cell_key(static_cast<int64_t>(std::floor(p[0] / cell_)), static_cast<int64_t>(std::floor(p[1] / cell_)),
                                static_cast<int64_t>(std::floor(p[2] / cell_)));
  const size_t s = slot(key);
  const auto entry = static_cast<int32_t>(ids_.size());
  ids_.push_back(id);
  next_.push_back(-1);
  if (first_[s] < 0) {
    keys_[s] = key;
    first_[s] = entry;
    ++cells_;
  } else {
    next_[static_cast<size_t>(last_[s])] = entry;
  }
  last_[s] = entry;
}

int32_t PointGrid::find(const double* p, const std::vector<double>& xyz) const {
  if (keys_.empty()) return -1;
  int64_t lo[3], hi[3];
  for (int c = 0; c < 3; ++c) {
    lo[c] = static_cast<int64_t>(std::floor((p[c] - 2 * tol_) / cell_));
    hi[c] = static_cast<int64_t>(std::floor((p[c] + 2 * tol_) / cell_));
  }
  for (int64_t i = lo[0]; i <= hi[0]; ++i)
    for (int64_t j = lo[1]; j <= hi[1]; ++j)
      for (int64_t k = lo[2]; k <= hi[2]; ++k) {
        const size_t s = slot(cell_key(i, j, k));
        for (int32_t e = first_[s]; e >= 0; e = next_[static_cast<size_t>(e)]) {
          const int32_t id = ids_[static_cast<size_t>(e)];
          const double* q = &xyz[3 * static_cast<size_t>(id)];
          if (std::fabs(p[0] - q[0]) <= tol_ && std::fabs(p[1] - q[1]) <= tol_ && std::fabs(p[2] - q[2]) <= tol_) return id;
        }
      }
  return -1;
}

int32_t ModelMesh::find(const double* p) const { return grid_.find(p, xyz_); }

int32_t ModelMesh::weld(const double* p, int face_tag) {
  if (const int32_t found = find(p); found >= 0) return found;
  const int32_t id = static_cast<int32_t>(xyz_.size() / 3);
  xyz_.insert(xyz_.end(), p, p + 3);
  node_face_.push_back(face_tag);
  welded_.push_back(1);
  grid_.add(p, id);
  return id;
}

void ModelMesh::note_defect(ConformityCounts& out, uint64_t key, int uses, int expected) const {
  if (out.defect_edges.size() >= kListedDefects) return;
  const size_t a = key >> 32, b = key & 0xffffffffULL;
  ConformityCounts::DefectEdge d{{}, uses, expected};
  for (size_t c = 0; c < 3; ++c) d.midpoint[c] = 0.5 * (xyz_[3 * a + c] + xyz_[3 * b + c]);
  out.defect_edges.push_back(d);
}

void ModelMesh::expect_model_edge(const std::vector<double>& nodes, int face_uses) {
  // A node no face mesh holds (its faces failed) leaves its segments undeclared: their absence is
  // then counted where the faces' other edges are, not here.
  // A kink node drop_fins took off the mesh is passed over: the edge runs along the chord there.
  // So is a model vertex it took off (a narrow face merged across a sharp edge folds around the
  // corner of the face beyond, and both close the corner with the same triangle): no gap is hidden,
  // since the chord left is an edge like any other, counted open if fewer than two triangles use it.
  const size_t n = nodes.size() / 3;
  int32_t prev = -1;
  for (size_t k = 0; k < n; ++k) {
    const int32_t b = find(&nodes[3 * k]);
    if (b >= 0 && fin_nodes_.count(b)) continue;
    if (prev >= 0 && b >= 0 && prev != b) expected_uses_[pair_key(prev, b)] += face_uses;
    prev = b;
  }
}

int64_t ModelMesh::drop_fins(const std::set<std::pair<int, int>>& alike) {
  const EdgeTable edges(xyz_.size() / 3, tris_);
  std::vector<int> node_tris(xyz_.size() / 3, 0);
  std::vector<std::pair<std::array<int32_t, 3>, size_t>> on_boundary;  // welded corners, triangle
  for (size_t t = 0; t + 2 < tris_.size(); t += 3) {
    for (size_t c = 0; c < 3; ++c) ++node_tris[static_cast<size_t>(tris_[t + c])];
    if (welded_[static_cast<size_t>(tris_[t])] && welded_[static_cast<size_t>(tris_[t + 1])] && welded_[static_cast<size_t>(tris_[t + 2])]) {
      std::array<int32_t, 3> key{tris_[t], tris_[t + 1], tris_[t + 2]};
      std::sort(key.begin(), key.end());
      on_boundary.push_back({key, t / 3});
    }
  }
  std::sort(on_boundary.begin(), on_boundary.end());
  std::vector<char> drop(tri_face_.size(), 0);
  int64_t dropped = 0;
  for (size_t g = 0; g < on_boundary.size();) {
    size_t e = g + 1;
    while (e < on_boundary.size() && on_boundary[e].first == on_boundary[g].first) ++e;
    const size_t first = g, count = e - g;
    g = e;
    if (count != 2) continue;
    const std::array<int32_t, 3>& key = on_boundary[first].first;
    const size_t t0i = on_boundary[first].second, t1i = on_boundary[first + 1].second;
    const int f = tri_face_[t0i], h = tri_face_[t1i];
    if (f == h || alike.count({f, h}) || alike.count({h, f})) continue;
    // Once each way: the second triangle's corners run backwards through the first's.
    const int32_t* t0 = &tris_[3 * t0i];
    const int32_t* t1 = &tris_[3 * t1i];
    const int at = static_cast<int>(std::find(t1, t1 + 3, t0[0]) - t1);
    if (t1[(at + 2) % 3] != t0[1]) continue;
    // The kink: a corner on these two triangles only, its two edges on nothing else.
    for (size_t c = 0; c < 3; ++c) {
      const int32_t b = key[c], x = key[(c + 1) % 3], y = key[(c + 2) % 3];
      if (node_tris[static_cast<size_t>(b)] != 2 || edges.uses(b, x) != 2 || edges.uses(b, y) != 2) continue;
      drop[t0i] = drop[t1i] = 1;
      fin_nodes_.insert(b);
      dropped += 2;
      break;
    }
  }
  if (!dropped) return 0;
  std::vector<int32_t> tris;
  std::vector<int> faces, tags;
  std::vector<int64_t> quads;
  for (size_t t = 0; t < tri_face_.size(); ++t)
    if (!drop[t]) {
      tris.insert(tris.end(), &tris_[3 * t], &tris_[3 * t] + 3);
      faces.push_back(tri_face_[t]);
      tags.push_back(tri_tag_[t]);
      quads.push_back(tri_quad_[t]);
    }
  tris_ = std::move(tris);
  tri_face_ = std::move(faces);
  tri_tag_ = std::move(tags);
  tri_quad_ = std::move(quads);
  return dropped;
}

std::vector<char> ModelMesh::boundary_nodes(size_t nodes, const std::vector<int32_t>& triangles) {
  std::vector<char> boundary(nodes, 0);
  EdgeTable(nodes, triangles).for_each([&](int32_t a, int32_t b, const auto* first, const auto* last) {
    if (last - first == 1) boundary[static_cast<size_t>(a)] = boundary[static_cast<size_t>(b)] = 1;
  });
  return boundary;
}

void ModelMesh::resplit_quad(std::array<int32_t, 3>& t1, std::array<int32_t, 3>& t2, bool always) const {
  auto has = [](const std::array<int32_t, 3>& t, int32_t v) { return t[0] == v || t[1] == v || t[2] == v; };
  int k1 = 0, k2 = 0;
  while (k1 < 3 && has(t2, t1[static_cast<size_t>(k1)])) ++k1;
  while (k2 < 3 && has(t1, t2[static_cast<size_t>(k2)])) ++k2;
  if (k1 == 3 || k2 == 3) return;  // not two halves of one quad
  // The quad u, s1, w, s2 counter-clockwise: t1 = (u, s1, s2), t2 = (w, s2, s1).
  const int32_t u = t1[static_cast<size_t>(k1)], s1 = t1[static_cast<size_t>((k1 + 1) % 3)], s2 = t1[static_cast<size_t>((k1 + 2) % 3)];
  const int32_t w = t2[static_cast<size_t>(k2)];
  auto lambda = [&](int32_t a, int32_t b, int32_t c) {
    return wefm_common::lo_lambda(&xyz_[3 * static_cast<size_t>(a)], &xyz_[3 * static_cast<size_t>(b)], &xyz_[3 * static_cast<size_t>(c)]);
  };
  if (always || std::min(lambda(u, s1, w), lambda(u, w, s2)) > std::min(lambda(u, s1, s2), lambda(w, s2, s1))) t1 = {u, s1, w}, t2 = {u, w, s2};
}

std::vector<char> ModelMesh::folds_of(const std::vector<std::array<int32_t, 3>>& tris) {
  std::vector<std::pair<std::array<int32_t, 3>, size_t>> by_corners;
  for (size_t i = 0; i < tris.size(); ++i) {
    std::array<int32_t, 3> key = tris[i];
    std::sort(key.begin(), key.end());
    by_corners.push_back({key, i});
  }
  std::sort(by_corners.begin(), by_corners.end());
  std::vector<char> fold(tris.size(), 0);
  for (size_t k = 0; k + 1 < by_corners.size(); ++k)
    if (by_corners[k].first == by_corners[k + 1].first) fold[by_corners[k].second] = fold[by_corners[k + 1].second] = 1;
  return fold;
}

bool ModelMesh::resplit_bad_diagonals(std::vector<std::array<int32_t, 3>>& tris, const std::vector<int64_t>& quads,
                                      const std::vector<char>& fold) const {
  std::unordered_map<uint64_t, int> uses;
  uses.reserve(3 * tris.size());
  for (const auto& t : tris)
    for (size_t c = 0; c < 3; ++c) ++uses[pair_key(t[c], t[(c + 1) % 3])];
  bool resplit = false;
  for (size_t i = 0; i + 1 < tris.size(); ++i) {
    if (quads[i] < 0 || quads[i + 1] != quads[i]) continue;
    int diagonal_uses = 0;  // of the edge the two halves share
    for (size_t c = 0; c < 3; ++c)
      for (size_t d = 0; d < 3; ++d) {
        const uint64_t key = pair_key(tris[i][c], tris[i][(c + 1) % 3]);
        if (pair_key(tris[i + 1][d], tris[i + 1][(d + 1) % 3]) == key) diagonal_uses = uses[key];
      }
    if (fold[i] || fold[i + 1] || diagonal_uses > 2) resplit_quad(tris[i], tris[i + 1], true), resplit = true;
    ++i;
  }
  return resplit;
}

int64_t ModelMesh::add_face(int face_tag, const std::vector<double>& xyz, const std::vector<int32_t>& triangles,
                            const std::vector<int>& triangle_tags, const std::vector<int32_t>& quad_of) {
  face_tags_.push_back(face_tag);
  for (int tag : std::set<int>(triangle_tags.begin(), triangle_tags.end()))
    if (tag != face_tag) face_tags_.push_back(tag);
  const std::vector<char> boundary = boundary_nodes(xyz.size() / 3, triangles);
  std::vector<int32_t> global(xyz.size() / 3);
  for (size_t v = 0; v < global.size(); ++v) {
    if (boundary[v]) {
      global[v] = weld(&xyz[3 * v], face_tag);
    } else {
      global[v] = static_cast<int32_t>(xyz_.size() / 3);
      xyz_.insert(xyz_.end(), &xyz[3 * v], &xyz[3 * v] + 3);
      node_face_.push_back(face_tag);
      welded_.push_back(0);
    }
  }
  // Welding can also turn two triangles that touch both sides of a seam near its degenerate end into
  // one triangle twice, once each way: a zero-volume fold. Both copies are dropped.
  std::vector<std::array<int32_t, 3>> kept;
  std::vector<int> kept_tags;
  std::vector<int64_t> kept_quads;
  int32_t face_quads = 0;
  int64_t dropped = 0;
  for (size_t t = 0; t + 2 < triangles.size(); t += 3) {
    const int32_t a = global[static_cast<size_t>(triangles[t])], b = global[static_cast<size_t>(triangles[t + 1])],
                  c = global[static_cast<size_t>(triangles[t + 2])];
    if (a == b || b == c || a == c) {
      ++dropped;
      continue;
    }
    kept.push_back({a, b, c});
    kept_tags.push_back(triangle_tags.empty() ? face_tag : triangle_tags[t / 3]);
    const int32_t q = quad_of.empty() ? -1 : quad_of[t / 3];
    kept_quads.push_back(q < 0 ? -1 : next_quad_ + q);
    face_quads = std::max(face_quads, q + 1);
  }
  next_quad_ += face_quads;
  for (size_t i = 0; i + 1 < kept.size(); ++i)
    if (kept_quads[i] >= 0 && kept_quads[i + 1] == kept_quads[i]) resplit_quad(kept[i], kept[i + 1]), ++i;
  std::vector<char> fold = folds_of(kept);
  if (face_quads > 0 && resplit_bad_diagonals(kept, kept_quads, fold)) fold = folds_of(kept);
  for (size_t i = 0; i < kept.size(); ++i) {
    if (fold[i]) {
      ++dropped;
      continue;
    }
    tris_.insert(tris_.end(), kept[i].begin(), kept[i].end());
    tri_face_.push_back(face_tag);
    tri_tag_.push_back(kept_tags[i]);
    tri_quad_.push_back(kept_quads[i]);
  }
  return dropped;
}

ConformityCounts ModelMesh::conformity() const {
  const EdgeTable edges(xyz_.size() / 3, tris_);
  // Faces that lie on each other are meshed alike: their triangles at the edge are the same two
  // triples of points. Triangles that differ are faces folded onto each other, a defect. Points, not
  // nodes: the faces' interior nodes are not welded (see add_face), so two coincident faces meshed
  // alike (the touching faces of an assembly's volumes, or a body the file holds twice) have the
  // same triangles on nodes of their own.
  PointGrid points(grid_.tolerance());
  std::vector<double> point_xyz;                  // the distinct points seen, 3 doubles each
  std::unordered_map<int32_t, int32_t> point_of;  // node -> index of its point
  auto point = [&](int32_t v) {
    const auto [it, fresh] = point_of.emplace(v, 0);
    if (fresh) {
      const double* p = &xyz_[3 * static_cast<size_t>(v)];
      it->second = points.find(p, point_xyz);
      if (it->second < 0) {
        it->second = static_cast<int32_t>(point_xyz.size() / 3);
        points.add(p, it->second);
        point_xyz.insert(point_xyz.end(), p, p + 3);
      }
    }
    return it->second;
  };
  auto meshed_alike = [&](const std::pair<int32_t, int32_t>* first, const std::pair<int32_t, int32_t>* last) {
    std::vector<std::array<int32_t, 3>> triples;
    for (auto u = first; u < last; ++u) {
      const size_t t = 3 * static_cast<size_t>(u->second);
      std::array<int32_t, 3> corners{point(tris_[t]), point(tris_[t + 1]), point(tris_[t + 2])};
      std::sort(corners.begin(), corners.end());
      triples.push_back(corners);
    }
    std::sort(triples.begin(), triples.end());
    return std::unique(triples.begin(), triples.end()) - triples.begin() == 2;
  };
  ConformityCounts out;
  std::unordered_set<uint64_t> defect_edges;
  edges.for_each([&](int32_t a, int32_t b, const std::pair<int32_t, int32_t>* first, const std::pair<int32_t, int32_t>* last) {
    const int n = static_cast<int>(last - first);
    // Whether some face uses the edge other than twice (a face's triangles are stored together).
    bool odd_in_a_face = false;
    for (auto u = first; u < last;) {
      auto e = u + 1;
      while (e < last && tri_face_[static_cast<size_t>(e->second)] == tri_face_[static_cast<size_t>(u->second)]) ++e;
      odd_in_a_face |= e - u != 2;
      u = e;
    }
    const uint64_t key = pair_key(a, b);
    const auto it = expected_uses_.find(key);
    if (n > 2 && !odd_in_a_face && it == expected_uses_.end()) odd_in_a_face = !meshed_alike(first, last);
    ++out.edges;
    out.open_edges += n == 1;
    out.non_manifold_edges += n > 2;
    // Off the model edges: twice, or twice by each of several faces lying on each other (touching
    // volumes of an assembly whose faces coincide, meshed alike).
    const int want = it != expected_uses_.end() ? it->second : (odd_in_a_face ? 2 : n);
    out.brep_edge_segments += it != expected_uses_.end();
    if (n != want) {
      defect_edges.insert(key);
      note_defect(out, key, n, want);
    }
    out.unexplained_open_edges += n < want;
    out.unexplained_non_manifold_edges += n > want;
  });
  // A model-edge segment no triangle uses at all is a gap as well (both faces left it out). Its faces
  // are those of the triangles at its ends (a lost cone apex has none; the seam node beside it does).
  std::unordered_set<int32_t> gap_ends;
  for (const auto& [key, want] : expected_uses_)
    if (!edges.uses(static_cast<int32_t>(key >> 32), static_cast<int32_t>(key & 0xffffffffULL))) {
      out.unexplained_open_edges += 1;
      note_defect(out, key, 0, want);
      gap_ends.insert(static_cast<int32_t>(key >> 32)), gap_ends.insert(static_cast<int32_t>(key & 0xffffffffULL));
    }
  std::vector<int> faces;
  for (size_t t = 0; t + 2 < tris_.size(); t += 3) {
    bool bad = wefm_common::lo_lambda(&xyz_[3 * static_cast<size_t>(tris_[t])], &xyz_[3 * static_cast<size_t>(tris_[t + 1])],
                         &xyz_[3 * static_cast<size_t>(tris_[t + 2])]) < kZeroAreaLambda;
    out.zero_area_triangles += bad;
    for (size_t c = 0; c < 3 && !bad && !defect_edges.empty(); ++c)
      bad = defect_edges.count(pair_key(tris_[t + c], tris_[t + (c + 1) % 3])) > 0;
    for (size_t c = 0; c < 3 && !bad && !gap_ends.empty(); ++c) bad = gap_ends.count(tris_[t + c]) > 0;
    if (bad) faces.push_back(tri_face_[t / 3]);
  }
  std::sort(faces.begin(), faces.end());
  faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
  out.defect_faces = std::move(faces);
  return out;
}

LambdaStats ModelMesh::lambda_of(const std::vector<double>& xyz, const std::vector<int32_t>& triangles) {
  LambdaStats s;
  double log_sum = 0;
  int64_t below = 0;
  s.lambda_min = 1;
  for (size_t t = 0; t + 2 < triangles.size(); t += 3) {
    const double l = wefm_common::lo_lambda(&xyz[3 * static_cast<size_t>(triangles[t])], &xyz[3 * static_cast<size_t>(triangles[t + 1])],
                               &xyz[3 * static_cast<size_t>(triangles[t + 2])]);
    log_sum += std::log(std::max(l, 1e-300));
    s.lambda_min = std::min(s.lambda_min, l);
    below += l < 0.6;
    ++s.triangles;
  }
  if (s.triangles) {
    s.lambda_mesh = std::exp(log_sum / static_cast<double>(s.triangles));
    s.fraction_below_0_6 = static_cast<double>(below) / static_cast<double>(s.triangles);
  } else {
    s.lambda_min = 0;
  }
  return s;
}

LambdaStats ModelMesh::lambda() const { return lambda_of(xyz_, tris_); }

namespace {

// The quad of two triangles that share an edge, once each way: t1 = (u, v, w) holds u -> v, t2 holds
// v -> u and s: the quad u, s, v, w, in the triangles' turning sense. False when they share no edge so.
bool quad_of_pair(const int32_t* t1, const int32_t* t2, int32_t* quad) {
  for (int k = 0; k < 3; ++k) {
    const int32_t u = t1[k], v = t1[(k + 1) % 3], w = t1[(k + 2) % 3];
    for (int j = 0; j < 3; ++j)
      if (t2[j] == v && t2[(j + 1) % 3] == u) {
        const int32_t q[4] = {u, t2[(j + 2) % 3], v, w};
        std::copy(q, q + 4, quad);
        return true;
      }
  }
  return false;
}

}  // namespace

void ModelMesh::quad_elements(std::vector<int32_t>& elements, std::vector<int>& tags) const {
  std::unordered_map<int64_t, std::vector<size_t>> halves;
  for (size_t t = 0; t < tri_quad_.size(); ++t)
    if (tri_quad_[t] >= 0) halves[tri_quad_[t]].push_back(t);
  elements.clear(), tags.clear();
  for (size_t t = 0; t < tri_quad_.size(); ++t) {
    const int32_t* T = &tris_[3 * t];
    if (tri_quad_[t] >= 0) {
      const std::vector<size_t>& h = halves.at(tri_quad_[t]);
      int32_t quad[4];
      if (h.size() == 2 && quad_of_pair(&tris_[3 * h[0]], &tris_[3 * h[1]], quad)) {
        if (t != h[0]) continue;  // written with its first half
        elements.insert(elements.end(), quad, quad + 4);
        tags.push_back(tri_tag_[t]);
        continue;
      }
    }
    elements.insert(elements.end(), {T[0], T[1], T[2], -1});
    tags.push_back(tri_tag_[t]);
  }
}

ModelMesh::QuadStats ModelMesh::quads() const {
  QuadStats s;
  if (next_quad_ == 0) return s;
  std::vector<int32_t> el;
  std::vector<int> tags;
  quad_elements(el, tags);
  auto X = [&](int32_t i) { return &xyz_[3 * static_cast<size_t>(i)]; };
  auto area = [&](int32_t a, int32_t b, int32_t c) {
    const double* p = X(a);
    const double u[3] = {X(b)[0] - p[0], X(b)[1] - p[1], X(b)[2] - p[2]}, v[3] = {X(c)[0] - p[0], X(c)[1] - p[1], X(c)[2] - p[2]};
    const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    return 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  };
  double quad_area = 0, all = 0, sum = 0;
  s.scaled_jacobian_min = 1;
  for (size_t e = 0; e < el.size(); e += 4) {
    const int32_t* q = &el[e];
    if (q[3] < 0) {
      all += area(q[0], q[1], q[2]);
      continue;
    }
    const double a = area(q[0], q[1], q[2]) + area(q[0], q[2], q[3]);
    quad_area += a, all += a;
    const double sj = wefm_common::scaled_jacobian(X(q[0]), X(q[1]), X(q[2]), X(q[3]));
    s.scaled_jacobian_min = std::min(s.scaled_jacobian_min, sj);
    sum += sj;
    ++s.quads;
    if (!(sj > 0)) {
      ++s.folded;
      s.folded_faces.push_back(tags[e / 4]);
    }
  }
  std::sort(s.folded_faces.begin(), s.folded_faces.end());
  s.folded_faces.erase(std::unique(s.folded_faces.begin(), s.folded_faces.end()), s.folded_faces.end());
  if (s.quads) s.scaled_jacobian_mean = sum / static_cast<double>(s.quads);
  else s.scaled_jacobian_min = 0;
  s.area_fraction = all > 0 ? quad_area / all : 0;
  return s;
}

MeshDescription ModelMesh::description() const {
  MeshDescription d;
  d.xyz = xyz_;
  d.elements = tris_;
  d.element_group = tri_tag_;  // a merged face's triangles go back to the B-rep faces under them
  if (next_quad_ > 0) {
    quad_elements(elements_, element_tags_);
    d.elements = elements_;
    d.element_group = element_tags_;
    d.nodes_per_element = 4;
  }
  d.point_group = node_face_;
  for (int f : face_tags_) d.groups.push_back({f, "face_" + std::to_string(f)});
  d.obj_groups = true;
  d.digits17 = true;
  return d;
}

}  // namespace wefm_cli
