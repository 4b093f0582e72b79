#include "cad_edge_nodes.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>

namespace wefm_cad {

namespace {

// The smallest local size a narrow face gets, as a fraction of h: a face narrower than h / 8 keeps
// slivers (a needle face cannot ask for millions of elements along its long edges).
constexpr double kNarrowestFraction = 8;
// The smallest a curved face gets: a hole or tube of radius down to h / 8 keeps six segments around.
constexpr double kSmallestRadiusFraction = 8;

double distance(const double* a, const double* b) {
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

// Arc-length size along an edge of length L: h inside, growing by `g` per unit length from the
// segment sizes s0 and s1 wanted at its two ends, min(h, s0 + g s, s1 + g (L - s)). Nodes sit at
// equal steps of the integral of 1 / size, which is closed-form on each linear piece.
class GradedSize {
 public:
  GradedSize(double length, double h, double s0, double s1, double g) : L_(length) {
    std::vector<double> cuts{0.0, length};
    if (g > 0) {
      for (double c : {(h - s0) / g, length - (h - s1) / g, (s1 - s0 + g * length) / (2 * g)})
        if (c > 0 && c < length) cuts.push_back(c);
    }
    std::sort(cuts.begin(), cuts.end());
    double phi = 0;
    for (size_t k = 0; k + 1 < cuts.size(); ++k) {
      const double a = cuts[k], b = cuts[k + 1];
      if (!(b > a)) continue;
      const double mid = 0.5 * (a + b);
      // The piece that is the minimum on [a, b]: size = c0 + c1 (s - a).
      Piece p{a, b, phi, h, 0.0};
      if (g > 0 && s0 + g * mid < p.c0) p.c0 = s0 + g * a, p.c1 = g;
      if (g > 0 && s1 + g * (length - mid) < p.c0 + p.c1 * (mid - a)) p.c0 = s1 + g * (length - a), p.c1 = -g;
      phi += p.integral(b);
      pieces_.push_back(p);
    }
    total_ = phi;
  }
  double total() const { return total_; }  // the integral of 1 / size over the edge
  // Arc length at which the integral reaches `phi`.
  double inverse(double phi) const {
    for (const Piece& p : pieces_) {
      const double span = p.integral(p.b);
      if (phi <= p.phi0 + span || &p == &pieces_.back()) {
        const double t = std::clamp(phi - p.phi0, 0.0, span);
        const double s = p.c1 == 0 ? p.a + p.c0 * t : p.a + p.c0 * (std::exp(p.c1 * t) - 1) / p.c1;
        return std::clamp(s, p.a, p.b);
      }
    }
    return L_;
  }

 private:
  struct Piece {
    double a, b, phi0, c0, c1;
    double integral(double s) const { return c1 == 0 ? (s - a) / c0 : std::log((c0 + c1 * (s - a)) / c0) / c1; }
  };
  double L_, total_ = 0;
  std::vector<Piece> pieces_;
};

// Nodes at the given arc lengths (sorted, first 0, last the full length) along the edge's chain.
EdgeNodes place(const CadFace& face, const CadEdge& edge, const std::vector<double>& targets) {
  const size_t m = edge.vertices.size();
  std::vector<const double*> p(m);
  for (size_t i = 0; i < m; ++i) p[i] = &face.xyz[3 * static_cast<size_t>(edge.vertices[i])];
  std::vector<double> s(m, 0.0);  // arc length at each chain vertex
  for (size_t i = 1; i < m; ++i) s[i] = s[i - 1] + distance(p[i - 1], p[i]);
  EdgeNodes out;
  out.xyz.insert(out.xyz.end(), p[0], p[0] + 3);
  size_t seg = 1;
  for (size_t k = 1; k + 1 < targets.size(); ++k) {
    const double target = targets[k];
    while (seg + 1 < m && s[seg] < target) ++seg;
    const double len = s[seg] - s[seg - 1];
    const double t = len > 0 ? std::clamp((target - s[seg - 1]) / len, 0.0, 1.0) : 0.0;
    for (int c = 0; c < 3; ++c) out.xyz.push_back(p[seg - 1][c] + t * (p[seg][c] - p[seg - 1][c]));
  }
  out.xyz.insert(out.xyz.end(), p[m - 1], p[m - 1] + 3);
  return out;
}

long long uniform_count(double length, double h, bool closed) { return std::max<long long>(closed ? 3 : 1, std::llround(length / h)); }

// Model vertices as the chain ends that coincide (within `tol`), numbered in order of appearance;
// a hash of grid cells of side `tol` finds the candidates.
class VertexIds {
 public:
  explicit VertexIds(double tol) : tol_(tol > 0 ? tol : 1e-300) {}
  int of(const double* p) {
    long long c[3];
    for (int k = 0; k < 3; ++k) c[k] = static_cast<long long>(std::floor(p[k] / tol_));
    for (long long dx = -1; dx <= 1; ++dx)
      for (long long dy = -1; dy <= 1; ++dy)
        for (long long dz = -1; dz <= 1; ++dz) {
          const auto range = cells_.equal_range(key(c[0] + dx, c[1] + dy, c[2] + dz));
          for (auto it = range.first; it != range.second; ++it) {
            const auto& q = pts_[static_cast<size_t>(it->second)];
            if (std::fabs(q[0] - p[0]) <= tol_ && std::fabs(q[1] - p[1]) <= tol_ && std::fabs(q[2] - p[2]) <= tol_) return it->second;
          }
        }
    pts_.push_back({p[0], p[1], p[2]});
    const int id = static_cast<int>(pts_.size()) - 1;
    cells_.emplace(key(c[0], c[1], c[2]), id);
    return id;
  }
  size_t size() const { return pts_.size(); }

 private:
  static unsigned long long key(long long i, long long j, long long k) {
    return static_cast<unsigned long long>(i) * 73856093ULL ^ static_cast<unsigned long long>(j) * 19349663ULL ^
           static_cast<unsigned long long>(k) * 83492791ULL;
  }
  double tol_;
  std::vector<std::array<double, 3>> pts_;
  std::unordered_multimap<unsigned long long, int> cells_;
};

}  // namespace

double chain_length(const CadFace& f, const CadEdge& e) {
  double length = 0;
  for (size_t i = 0; i + 1 < e.vertices.size(); ++i)
    length += distance(&f.xyz[3 * static_cast<size_t>(e.vertices[i])], &f.xyz[3 * static_cast<size_t>(e.vertices[i + 1])]);
  return length;
}

// The face's smaller radius of curvature, from its facets: across each facet edge inside the face,
// the mean distance of the two opposite corners from the edge over the angle between the facets'
// normals (on a cylinder's facets, its radius). A low quantile, not the minimum, so one skewed facet
// does not decide it; infinite on a flat face.
double curvature_radius(const CadFace& f) {
  const size_t n = f.triangles.size() / 3;
  auto point = [&](int32_t v) { return &f.xyz[3 * static_cast<size_t>(v)]; };
  auto normal = [&](size_t t) {
    const double *a = point(f.triangles[3 * t]), *b = point(f.triangles[3 * t + 1]), *c = point(f.triangles[3 * t + 2]);
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    std::array<double, 3> m{u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    const double len = std::sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2]);
    for (double& x : m) x = len > 0 ? x / len : 0;
    return m;
  };
  // Distance of p from the line through a and b.
  auto off_line = [](const double* p, const double* a, const double* b) {
    const double e[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, w[3] = {p[0] - a[0], p[1] - a[1], p[2] - a[2]};
    const double c[3] = {e[1] * w[2] - e[2] * w[1], e[2] * w[0] - e[0] * w[2], e[0] * w[1] - e[1] * w[0]};
    const double le = std::sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
    return le > 0 ? std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]) / le : 0.0;
  };
  std::unordered_map<unsigned long long, size_t> first;  // directed edge -> the corner opposite it
  std::vector<double> radii;
  for (size_t t = 0; t < n; ++t)
    for (size_t c = 0; c < 3; ++c) {
      const int32_t va = f.triangles[3 * t + c], vb = f.triangles[3 * t + (c + 1) % 3];
      const auto a = static_cast<unsigned long long>(static_cast<uint32_t>(va)), b = static_cast<unsigned long long>(static_cast<uint32_t>(vb));
      const auto it = first.find(b << 32 | a);
      if (it == first.end()) {
        first.emplace(a << 32 | b, 3 * t + (c + 2) % 3);
        continue;
      }
      const auto n0 = normal(it->second / 3), n1 = normal(t);
      const double angle = std::acos(std::clamp(n0[0] * n1[0] + n0[1] * n1[1] + n0[2] * n1[2], -1.0, 1.0));
      if (!(angle > 1e-3)) continue;
      const double h0 = off_line(point(f.triangles[it->second]), point(va), point(vb));
      const double h1 = off_line(point(f.triangles[3 * t + (c + 2) % 3]), point(va), point(vb));
      radii.push_back(0.5 * (h0 + h1) / angle);
    }
  if (radii.size() < 4) return std::numeric_limits<double>::infinity();
  const size_t q = radii.size() / 10;
  std::nth_element(radii.begin(), radii.begin() + static_cast<std::ptrdiff_t>(q), radii.end());
  return radii[q];
}

double face_area(const CadFace& f) {
  double area = 0;
  for (size_t t = 0; t + 2 < f.triangles.size(); t += 3) {
    const double* a = &f.xyz[3 * static_cast<size_t>(f.triangles[t])];
    const double* b = &f.xyz[3 * static_cast<size_t>(f.triangles[t + 1])];
    const double* c = &f.xyz[3 * static_cast<size_t>(f.triangles[t + 2])];
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double x = u[1] * v[2] - u[2] * v[1], y = u[2] * v[0] - u[0] * v[2], z = u[0] * v[1] - u[1] * v[0];
    area += 0.5 * std::sqrt(x * x + y * y + z * z);
  }
  return area;
}

std::vector<double> local_face_sizes(const CadModel& model, double h) {
  std::vector<double> sizes(model.faces.size(), h);
  for (size_t k = 0; k < model.faces.size(); ++k) {
    const CadFace& f = model.faces[k];
    if (!f.error.empty()) continue;
    const double area = face_area(f);
    double perimeter = 0;  // over the loops: a seam counts twice, as it bounds the domain twice
    for (const auto& loop : f.loops)
      for (const CadEdgeUse& u : loop) perimeter += chain_length(f, f.edges[static_cast<size_t>(u.edge)]);
    // A curved face gets at least about six segments around a full turn (a hexagon's side is its
    // radius): coarser, the chords of a thin tube or a small hole fold onto each other.
    // Curvature may ask for smaller elements than narrowness: a small hole needs its six segments
    // around whatever its length, while a long narrow strip cannot ask for millions along it.
    const double width = perimeter > 0 ? std::max(2 * area / perimeter, h / kNarrowestFraction) : h;
    sizes[k] = std::clamp(std::min(width, curvature_radius(f)), h / kSmallestRadiusFraction, h);
  }
  return sizes;
}

std::map<long long, EdgeNodes> discretise_model_edges(const CadModel& model, double h, const std::vector<double>& face_sizes,
                                                      double gradation) {
  std::map<long long, double> edge_size;
  for (size_t k = 0; k < model.faces.size(); ++k) {
    const double hf = k < face_sizes.size() ? face_sizes[k] : h;
    for (const CadEdge& e : model.faces[k].edges) {
      auto [it, fresh] = edge_size.emplace(e.id, hf);
      if (!fresh) it->second = std::min(it->second, hf);
    }
  }
  // Each edge once, from the first face that has it.
  struct Chain {
    const CadFace* face;
    const CadEdge* edge;
    double length, size;
    bool closed;
    int v0, v1;
  };
  std::map<long long, Chain> chains;
  VertexIds vertices(1e-7 * model.bbox_diagonal);
  for (const CadFace& f : model.faces) {
    if (!f.error.empty()) continue;
    for (const CadEdge& e : f.edges) {
      if (e.degenerated || e.vertices.size() < 2 || chains.count(e.id)) continue;
      const int v0 = vertices.of(&f.xyz[3 * static_cast<size_t>(e.vertices.front())]);
      const int v1 = vertices.of(&f.xyz[3 * static_cast<size_t>(e.vertices.back())]);
      chains.emplace(e.id, Chain{&f, &e, chain_length(f, e), edge_size.at(e.id), e.vertices.front() == e.vertices.back(), v0, v1});
    }
  }
  // At each model vertex, the shortest uniform segment of the edges meeting there: every edge
  // grades down to it, so a short edge does not end next to a segment many times its length.
  std::vector<double> vertex_size(vertices.size(), 1e300);
  for (const auto& [id, c] : chains) {
    const double u = c.length / static_cast<double>(uniform_count(c.length, c.size, c.closed));
    for (int v : {c.v0, c.v1}) vertex_size[static_cast<size_t>(v)] = std::min(vertex_size[static_cast<size_t>(v)], u);
  }
  std::map<long long, EdgeNodes> nodes;
  for (const auto& [id, c] : chains) {
    std::vector<double> targets;
    if (gradation > 0) {
      const GradedSize sz(c.length, c.size, vertex_size[static_cast<size_t>(c.v0)], vertex_size[static_cast<size_t>(c.v1)], gradation);
      const long long n = std::max<long long>(c.closed ? 3 : 1, std::llround(sz.total()));
      for (long long k = 0; k <= n; ++k) targets.push_back(sz.inverse(sz.total() * static_cast<double>(k) / static_cast<double>(n)));
    } else {
      const long long n = uniform_count(c.length, c.size, c.closed);
      for (long long k = 0; k <= n; ++k) targets.push_back(c.length * static_cast<double>(k) / static_cast<double>(n));
    }
    nodes.emplace(id, place(*c.face, *c.edge, targets));
  }
  return nodes;
}

}  // namespace wefm_cad
