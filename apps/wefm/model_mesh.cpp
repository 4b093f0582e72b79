#include "model_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <map>

namespace wefm_cli {

namespace {

uint64_t cell_key(int64_t i, int64_t j, int64_t k) {
  // Mixes three cell coordinates into one key; collisions only cost a distance test.
  return static_cast<uint64_t>(i) * 73856093ULL ^ static_cast<uint64_t>(j) * 19349663ULL ^
         static_cast<uint64_t>(k) * 83492791ULL;
}

uint64_t pair_key(int32_t a, int32_t b) {
  if (a > b) std::swap(a, b);
  return (static_cast<uint64_t>(static_cast<uint32_t>(a)) << 32) | static_cast<uint32_t>(b);
}

// Lo's quality: 4 sqrt(3) area / sum of squared edge lengths (1 for an equilateral triangle).
double lo_lambda(const double* a, const double* b, const double* c) {
  double e1[3], e2[3], e3[3];
  for (int i = 0; i < 3; ++i) {
    e1[i] = b[i] - a[i];
    e2[i] = c[i] - a[i];
    e3[i] = c[i] - b[i];
  }
  const double cx = e1[1] * e2[2] - e1[2] * e2[1], cy = e1[2] * e2[0] - e1[0] * e2[2], cz = e1[0] * e2[1] - e1[1] * e2[0];
  const double area = 0.5 * std::sqrt(cx * cx + cy * cy + cz * cz);
  double sq = 0;
  for (int i = 0; i < 3; ++i) sq += e1[i] * e1[i] + e2[i] * e2[i] + e3[i] * e3[i];
  return sq > 0 ? 4.0 * std::sqrt(3.0) * area / sq : 0.0;
}

// Lo's lambda below this is a triangle with no area to speak of: a solver divides by it.
constexpr double kZeroAreaLambda = 1e-6;
// How many unexplained edges conformity() lists by position.
constexpr size_t kListedDefects = 20;

}  // namespace

uint64_t PointGrid::key(const double* p, int di, int dj, int dk) const {
  return cell_key(static_cast<int64_t>(std::floor(p[0] / tol_)) + di, static_cast<int64_t>(std::floor(p[1] / tol_)) + dj,
                  static_cast<int64_t>(std::floor(p[2] / tol_)) + dk);
}

void PointGrid::add(const double* p, int32_t id) { cells_.emplace(key(p, 0, 0, 0), id); }

int32_t PointGrid::find(const double* p, const std::vector<double>& xyz) const {
  for (int di = -1; di <= 1; ++di)
    for (int dj = -1; dj <= 1; ++dj)
      for (int dk = -1; dk <= 1; ++dk) {
        auto range = cells_.equal_range(key(p, di, dj, dk));
        for (auto it = range.first; it != range.second; ++it) {
          const double* q = &xyz[3 * static_cast<size_t>(it->second)];
          if (std::fabs(p[0] - q[0]) <= tol_ && std::fabs(p[1] - q[1]) <= tol_ && std::fabs(p[2] - q[2]) <= tol_)
            return it->second;
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
  // Never an end node: a model vertex left out of the mesh is a gap.
  const size_t n = nodes.size() / 3;
  int32_t prev = -1;
  for (size_t k = 0; k < n; ++k) {
    const int32_t b = find(&nodes[3 * k]);
    if (b >= 0 && k > 0 && k + 1 < n && fin_nodes_.count(b)) continue;
    if (prev >= 0 && b >= 0 && prev != b) expected_uses_[pair_key(prev, b)] += face_uses;
    prev = b;
  }
}

int64_t ModelMesh::drop_fins(const std::set<std::pair<int, int>>& alike) {
  std::unordered_map<uint64_t, int> uses;
  std::vector<int> node_tris(xyz_.size() / 3, 0);
  std::map<std::array<int32_t, 3>, std::vector<size_t>> on_boundary;  // welded corners -> triangles
  for (size_t t = 0; t + 2 < tris_.size(); t += 3) {
    for (int c = 0; c < 3; ++c) {
      ++uses[pair_key(tris_[t + static_cast<size_t>(c)], tris_[t + static_cast<size_t>((c + 1) % 3)])];
      ++node_tris[static_cast<size_t>(tris_[t + static_cast<size_t>(c)])];
    }
    if (welded_[static_cast<size_t>(tris_[t])] && welded_[static_cast<size_t>(tris_[t + 1])] && welded_[static_cast<size_t>(tris_[t + 2])]) {
      std::array<int32_t, 3> key{tris_[t], tris_[t + 1], tris_[t + 2]};
      std::sort(key.begin(), key.end());
      on_boundary[key].push_back(t / 3);
    }
  }
  std::vector<char> drop(tri_face_.size(), 0);
  int64_t dropped = 0;
  for (const auto& [key, list] : on_boundary) {
    if (list.size() != 2) continue;
    const int f = tri_face_[list[0]], g = tri_face_[list[1]];
    if (f == g || alike.count({f, g}) || alike.count({g, f})) continue;
    // Once each way: the second triangle's corners run backwards through the first's.
    const int32_t* t0 = &tris_[3 * list[0]];
    const int32_t* t1 = &tris_[3 * list[1]];
    const int at = static_cast<int>(std::find(t1, t1 + 3, t0[0]) - t1);
    if (t1[(at + 2) % 3] != t0[1]) continue;
    // The kink: a corner on these two triangles only, its two edges on nothing else.
    for (int c = 0; c < 3; ++c) {
      const int32_t b = key[static_cast<size_t>(c)], x = key[static_cast<size_t>((c + 1) % 3)], y = key[static_cast<size_t>((c + 2) % 3)];
      if (node_tris[static_cast<size_t>(b)] != 2 || uses[pair_key(b, x)] != 2 || uses[pair_key(b, y)] != 2) continue;
      drop[list[0]] = drop[list[1]] = 1;
      fin_nodes_.insert(b);
      dropped += 2;
      break;
    }
  }
  if (!dropped) return 0;
  std::vector<int32_t> tris;
  std::vector<int> faces, tags;
  for (size_t t = 0; t < tri_face_.size(); ++t)
    if (!drop[t]) {
      tris.insert(tris.end(), &tris_[3 * t], &tris_[3 * t] + 3);
      faces.push_back(tri_face_[t]);
      tags.push_back(tri_tag_[t]);
    }
  tris_ = std::move(tris);
  tri_face_ = std::move(faces);
  tri_tag_ = std::move(tags);
  return dropped;
}

std::vector<char> ModelMesh::boundary_nodes(size_t nodes, const std::vector<int32_t>& triangles) {
  std::unordered_map<uint64_t, int> uses;
  for (size_t t = 0; t + 2 < triangles.size(); t += 3)
    for (int c = 0; c < 3; ++c) ++uses[pair_key(triangles[t + static_cast<size_t>(c)], triangles[t + static_cast<size_t>((c + 1) % 3)])];
  std::vector<char> boundary(nodes, 0);
  for (const auto& [key, n] : uses)
    if (n == 1) boundary[key >> 32] = boundary[key & 0xffffffffULL] = 1;
  return boundary;
}

int64_t ModelMesh::add_face(int face_tag, const std::vector<double>& xyz, const std::vector<int32_t>& triangles,
                            const std::vector<int>& triangle_tags) {
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
  std::map<std::array<int32_t, 3>, std::vector<size_t>> by_corners;
  int64_t dropped = 0;
  for (size_t t = 0; t + 2 < triangles.size(); t += 3) {
    const int32_t a = global[static_cast<size_t>(triangles[t])], b = global[static_cast<size_t>(triangles[t + 1])],
                  c = global[static_cast<size_t>(triangles[t + 2])];
    if (a == b || b == c || a == c) {
      ++dropped;
      continue;
    }
    std::array<int32_t, 3> key{a, b, c};
    std::sort(key.begin(), key.end());
    by_corners[key].push_back(kept.size());
    kept.push_back({a, b, c});
    kept_tags.push_back(triangle_tags.empty() ? face_tag : triangle_tags[t / 3]);
  }
  std::vector<char> fold(kept.size(), 0);
  for (const auto& [key, list] : by_corners)
    if (list.size() > 1)
      for (size_t i : list) fold[i] = 1;
  for (size_t i = 0; i < kept.size(); ++i) {
    if (fold[i]) {
      ++dropped;
      continue;
    }
    tris_.insert(tris_.end(), kept[i].begin(), kept[i].end());
    tri_face_.push_back(face_tag);
    tri_tag_.push_back(kept_tags[i]);
  }
  return dropped;
}

ConformityCounts ModelMesh::conformity() const {
  std::unordered_map<uint64_t, int> uses;
  // Per edge, whether some face uses it other than twice (triangles are added face by face, so a
  // face's uses of an edge are counted in a row).
  std::unordered_map<uint64_t, std::pair<int, int>> run;  // edge -> (face of the current run, its count)
  std::unordered_map<uint64_t, char> odd_in_a_face;
  for (size_t t = 0; t + 2 < tris_.size(); t += 3)
    for (int c = 0; c < 3; ++c) {
      const uint64_t key = pair_key(tris_[t + static_cast<size_t>(c)], tris_[t + static_cast<size_t>((c + 1) % 3)]);
      ++uses[key];
      auto [it, fresh] = run.emplace(key, std::make_pair(tri_face_[t / 3], 0));
      if (!fresh && it->second.first != tri_face_[t / 3]) {
        if (it->second.second != 2) odd_in_a_face[key] = 1;
        it->second = {tri_face_[t / 3], 0};
      }
      ++it->second.second;
    }
  for (const auto& [key, r] : run)
    if (r.second != 2) odd_in_a_face[key] = 1;
  // Faces that lie on each other are meshed alike: their triangles at the edge are the same two
  // triples of points. Triangles that differ are faces folded onto each other, a defect. Points, not
  // nodes: the faces' interior nodes are not welded (see add_face), so two coincident faces meshed
  // alike (the touching faces of an assembly's volumes, or a body the file holds twice) have the
  // same triangles on nodes of their own.
  std::unordered_map<uint64_t, std::vector<std::array<int32_t, 3>>> around;
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
  for (size_t t = 0; t + 2 < tris_.size(); t += 3)
    for (int c = 0; c < 3; ++c) {
      const uint64_t key = pair_key(tris_[t + static_cast<size_t>(c)], tris_[t + static_cast<size_t>((c + 1) % 3)]);
      if (uses[key] <= 2 || odd_in_a_face.count(key) || expected_uses_.count(key)) continue;
      std::array<int32_t, 3> corners{point(tris_[t]), point(tris_[t + 1]), point(tris_[t + 2])};
      std::sort(corners.begin(), corners.end());
      around[key].push_back(corners);
    }
  for (auto& [key, triples] : around) {
    std::sort(triples.begin(), triples.end());
    if (std::unique(triples.begin(), triples.end()) - triples.begin() != 2) odd_in_a_face[key] = 1;
  }
  ConformityCounts out;
  out.edges = static_cast<int64_t>(uses.size());
  std::unordered_map<uint64_t, char> defect_edges;
  for (const auto& [key, n] : uses) {
    out.open_edges += n == 1;
    out.non_manifold_edges += n > 2;
    const auto it = expected_uses_.find(key);
    // Off the model edges: twice, or twice by each of several faces lying on each other (touching
    // volumes of an assembly whose faces coincide, meshed alike).
    const int want = it != expected_uses_.end() ? it->second : (odd_in_a_face.count(key) ? 2 : n);
    out.brep_edge_segments += it != expected_uses_.end();
    if (n != want) {
      defect_edges.emplace(key, 1);
      note_defect(out, key, n, want);
    }
    out.unexplained_open_edges += n < want;
    out.unexplained_non_manifold_edges += n > want;
  }
  // A model-edge segment no triangle uses at all is a gap as well (both faces left it out).
  for (const auto& [key, want] : expected_uses_)
    if (!uses.count(key)) {
      out.unexplained_open_edges += 1;
      note_defect(out, key, 0, want);
    }
  std::vector<int> faces;
  for (size_t t = 0; t + 2 < tris_.size(); t += 3) {
    bool bad = lo_lambda(&xyz_[3 * static_cast<size_t>(tris_[t])], &xyz_[3 * static_cast<size_t>(tris_[t + 1])],
                         &xyz_[3 * static_cast<size_t>(tris_[t + 2])]) < kZeroAreaLambda;
    out.zero_area_triangles += bad;
    for (int c = 0; c < 3 && !bad; ++c)
      bad = defect_edges.count(pair_key(tris_[t + static_cast<size_t>(c)], tris_[t + static_cast<size_t>((c + 1) % 3)])) > 0;
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
    const double l = lo_lambda(&xyz[3 * static_cast<size_t>(triangles[t])], &xyz[3 * static_cast<size_t>(triangles[t + 1])],
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

MeshDescription ModelMesh::description() const {
  MeshDescription d;
  d.xyz = xyz_;
  d.elements = tris_;
  d.element_group = tri_tag_;  // a merged face's triangles go back to the B-rep faces under them
  d.point_group = node_face_;
  for (int f : face_tags_) d.groups.push_back({f, "face_" + std::to_string(f)});
  d.obj_groups = true;
  d.digits17 = true;
  return d;
}

}  // namespace wefm_cli
