#include "wefm/core/method/gauge.hpp"

#include <Eigen/Dense>
#include <cmath>

namespace wefm {

std::pair<Index, Index> longest_loop_segment(const Topology& tp, const TriMesh& m, Index loop) {
  const auto& lu = tp.loop_uses[static_cast<size_t>(loop)];
  double best = -1;
  std::pair<Index, Index> r{lu[0], lu[lu.size() > 1 ? 1 : 0]};
  for (size_t j = 0; j < lu.size(); ++j) {
    const Index a = lu[j], b = lu[(j + 1) % lu.size()];
    if (a == b) continue;
    const double L = (m.vertices[static_cast<size_t>(tp.use_vertex[static_cast<size_t>(b)])] - m.vertices[static_cast<size_t>(tp.use_vertex[static_cast<size_t>(a)])]).norm();
    if (L > best) {
      best = L;
      r = {a, b};
    }
  }
  return r;
}

std::pair<Index, Index> far_pair(const Topology& tp, const VectorXc& z, Index loop) {
  const auto& lu = tp.loop_uses[static_cast<size_t>(loop)];
  auto farthest = [&](Index from) {
    Index best = from;
    double d = -1;
    for (Index u : lu)
      if (std::abs(z[u] - z[from]) > d) {
        d = std::abs(z[u] - z[from]);
        best = u;
      }
    return best;
  };
  const Index a = farthest(lu[0]);
  const Index b = farthest(a);
  return {a, b};
}

std::pair<Index, Index> far_pair_3d(const TriMesh& m, const Topology& tp, Index loop) {
  const auto& lu = tp.loop_uses[static_cast<size_t>(loop)];
  auto pos = [&](Index u) -> const Vec3& { return m.vertices[static_cast<size_t>(tp.use_vertex[static_cast<size_t>(u)])]; };
  auto farthest = [&](Index from) {
    Index best = from;
    double d = -1;
    for (Index u : lu)
      if (u != from && (pos(u) - pos(from)).squaredNorm() > d) {
        d = (pos(u) - pos(from)).squaredNorm();
        best = u;
      }
    return best;
  };
  const Index a = farthest(lu[0]);
  return {a, farthest(a)};
}

VectorXc planar_projection(const TriMesh& m, const Topology& tp, double ls) {
  Vec3 mean = Vec3::Zero();
  for (const Vec3& p : m.vertices) mean += p;
  mean /= static_cast<double>(m.vertices.size());
  Eigen::Matrix3d C = Eigen::Matrix3d::Zero();
  for (const Vec3& p : m.vertices) C += (p - mean) * (p - mean).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(C);
  const Vec3 e1 = es.eigenvectors().col(2), e2 = es.eigenvectors().col(1);
  VectorXc z(tp.use_count);
  for (Index u = 0; u < tp.use_count; ++u) {
    const Vec3 d = (m.vertices[static_cast<size_t>(tp.use_vertex[static_cast<size_t>(u)])] - mean) / ls;
    z[u] = Complex(d.dot(e1), d.dot(e2));
  }
  return z;
}

GaugeChoice choose_gauges(const std::vector<LinearRow>& rows, const VectorXc& zr) {
  GaugeChoice g;
  if (rows.empty()) return g;
  // Each caller row acts on the gauge modes {1, z_ref} through (sum g, sum g z_ref).
  Eigen::MatrixXcd M(static_cast<Index>(rows.size()), 2);
  for (size_t r = 0; r < rows.size(); ++r) {
    Complex s1{0, 0}, s2{0, 0};
    double mag = 0;
    for (auto& [u, c] : rows[r].terms) {
      s1 += c;
      s2 += c * zr[u];
      mag += std::abs(c);
    }
    const double n = mag > 0 ? 1.0 / mag : 0.0;
    M(static_cast<Index>(r), 0) = s1 * n;
    M(static_cast<Index>(r), 1) = s2 * n / std::max(1e-300, zr.cwiseAbs().maxCoeff());
  }
  Eigen::JacobiSVD<Eigen::MatrixXcd> svd(M, Eigen::ComputeFullV);
  const auto sv = svd.singularValues();
  const int rank = (sv.size() > 0 && sv[0] > 1e-9 ? 1 : 0) + (sv.size() > 1 && sv[1] > 1e-9 * std::max(1.0, sv[0]) ? 1 : 0);
  if (rank == 2) {
    g.translation = g.vector = false;
  } else if (rank == 1) {
    // The caller fixes one combination (p, q) of translation and similarity; add the gauge that
    // completes it best: translation acts as (sum eta, 0), the vector gauge as (0, 1).
    const Eigen::Vector2cd pq = svd.matrixV().col(0).conjugate();
    const double det_t = std::abs(pq[1]), det_v = std::abs(pq[0]);
    g.translation = det_t >= det_v;
    g.vector = !g.translation;
  }
  // A translation-fixing row sum g z = c keeps the point c / sum g fixed under scaling about it.
  for (const auto& r : rows) {
    Complex s1{0, 0};
    double mag = 0;
    for (auto& [u, c] : r.terms) {
      s1 += c;
      mag += std::abs(c);
    }
    if (std::abs(s1) > 1e-9 * mag) {
      g.center = r.rhs / s1;
      break;
    }
  }
  return g;
}

}  // namespace wefm
