#include "wefm/core/method/seam_substitution.hpp"

#include <algorithm>
#include <map>

namespace wefm {

namespace {

// z_u = c z_root + sum coef_k q_k
struct Expr {
  Index root = -1;
  Complex c{1, 0};
  std::map<Index, Complex> q;
};

bool negligible(Complex v) { return std::abs(v) < 1e-12; }

}  // namespace

SeamSubstitution substitute_seams(const Topology& tp, const std::vector<EdgeMode>& mode, const std::vector<Complex>& rotation) {
  const Index n = tp.use_count;
  std::vector<Expr> ex(static_cast<size_t>(n));
  std::vector<std::vector<Index>> members(static_cast<size_t>(n));
  for (Index u = 0; u < n; ++u) {
    ex[static_cast<size_t>(u)].root = u;
    members[static_cast<size_t>(u)] = {u};
  }
  std::vector<Expr> closing;  // constraints closing a cycle: c z_root + q terms must vanish
  Index nq = 0;
  for (const RepeatedEdge& r : tp.repeated) {
    const EdgeMode md = mode[static_cast<size_t>(r.edge)];
    if (md != EdgeMode::Periodic && md != EdgeMode::Rotational && md != EdgeMode::Scar) continue;
    const Complex c = md == EdgeMode::Rotational ? rotation[static_cast<size_t>(r.edge)] : Complex(1, 0);
    const Index q = md == EdgeMode::Scar ? -1 : nq++;
    for (size_t j = 0; j < r.side_a.size(); ++j) {
      const Index a = r.side_a[j], b = r.side_b[j];
      if (a == b) continue;
      // Constraint: ex[a] - c ex[b] - q = 0.
      const Expr ea = ex[static_cast<size_t>(a)], eb = ex[static_cast<size_t>(b)];
      Expr diff;  // ea - c eb - q, over two roots in general
      for (auto& [k, v] : ea.q) diff.q[k] += v;
      for (auto& [k, v] : eb.q) diff.q[k] -= c * v;
      if (q >= 0) diff.q[q] -= 1.0;
      if (ea.root == eb.root) {
        diff.root = ea.root;
        diff.c = ea.c - c * eb.c;
        closing.push_back(diff);
        continue;
      }
      // Eliminate the root of the smaller class: ca z_ra - c cb z_rb + Q = 0.
      Index ra = ea.root, rb = eb.root;
      Complex ka = ea.c, kb = -c * eb.c;
      if (members[static_cast<size_t>(ra)].size() > members[static_cast<size_t>(rb)].size()) {
        std::swap(ra, rb);
        std::swap(ka, kb);
      }
      // z_ra = -(kb z_rb + Q) / ka
      Expr sub;
      sub.root = rb;
      sub.c = -kb / ka;
      for (auto& [k, v] : diff.q)
        if (!negligible(v)) sub.q[k] = -v / ka;
      for (Index m : members[static_cast<size_t>(ra)]) {
        Expr& em = ex[static_cast<size_t>(m)];
        Expr next;
        next.root = rb;
        next.c = em.c * sub.c;
        next.q = em.q;
        for (auto& [k, v] : sub.q) next.q[k] += em.c * v;
        em = std::move(next);
        members[static_cast<size_t>(rb)].push_back(m);
      }
      members[static_cast<size_t>(ra)].clear();
    }
  }
  SeamSubstitution out;
  out.use_to_reduced.assign(static_cast<size_t>(n), -1);
  Index kept = 0;
  for (Index u = 0; u < n; ++u)
    if (ex[static_cast<size_t>(u)].root == u) out.use_to_reduced[static_cast<size_t>(u)] = kept++;
  out.reduced = kept + nq;
  std::vector<Eigen::Triplet<Complex>> trip;
  trip.reserve(static_cast<size_t>(n) + 8);
  auto col_of_root = [&](Index r) { return out.use_to_reduced[static_cast<size_t>(r)]; };
  for (Index u = 0; u < n; ++u) {
    const Expr& e = ex[static_cast<size_t>(u)];
    trip.emplace_back(u, col_of_root(e.root), e.c);
    for (auto& [k, v] : e.q)
      if (!negligible(v)) trip.emplace_back(u, kept + k, v);
  }
  out.P.resize(n, out.reduced);
  out.P.setFromTriplets(trip.begin(), trip.end());
  out.P.makeCompressed();
  out.P_rows = out.P;
  out.kept = kept;
  for (const Expr& cl : closing) {
    LinearRow row;
    if (!negligible(cl.c)) row.terms.emplace_back(col_of_root(cl.root), cl.c);
    for (auto& [k, v] : cl.q)
      if (!negligible(v)) row.terms.emplace_back(kept + k, v);
    if (!row.terms.empty()) out.leftover.push_back(std::move(row));  // empty: the cycle is consistent
  }
  return out;
}

VectorXc reduce(const SeamSubstitution& sub, const VectorXc& z) {
  VectorXc y = VectorXc::Zero(sub.reduced);
  const Index n = static_cast<Index>(sub.use_to_reduced.size());
  for (Index u = 0; u < n; ++u)
    if (sub.use_to_reduced[static_cast<size_t>(u)] >= 0) y[sub.use_to_reduced[static_cast<size_t>(u)]] = z[u];
  // Each q: least-squares fit of P y = z over the uses whose expression holds that q alone, with
  // the kept uses fixed (exact when z satisfies the constraints).
  std::vector<Complex> num(static_cast<size_t>(sub.reduced), 0.0);
  std::vector<double> den(static_cast<size_t>(sub.reduced), 0.0);
  for (Index u = 0; u < n; ++u) {
    Complex rest = z[u];
    Index qk = -1;
    Complex qc{0, 0};
    int nqs = 0;
    for (SeamSubstitution::RowMajor::InnerIterator it(sub.P_rows, u); it; ++it) {
      if (it.col() < sub.kept) {
        rest -= it.value() * y[it.col()];
      } else {
        qk = static_cast<Index>(it.col());
        qc = it.value();
        ++nqs;
      }
    }
    if (nqs == 1) {
      num[static_cast<size_t>(qk)] += std::conj(qc) * rest;
      den[static_cast<size_t>(qk)] += std::norm(qc);
    }
  }
  for (Index k = sub.kept; k < sub.reduced; ++k)
    if (den[static_cast<size_t>(k)] > 0) y[k] = num[static_cast<size_t>(k)] / den[static_cast<size_t>(k)];
  return y;
}

LinearRow reduce_row(const SeamSubstitution& sub, const LinearRow& row) {
  std::map<Index, Complex> acc;
  for (auto& [u, g] : row.terms)
    for (SeamSubstitution::RowMajor::InnerIterator it(sub.P_rows, u); it; ++it) acc[static_cast<Index>(it.col())] += g * it.value();
  LinearRow out;
  out.rhs = row.rhs;
  for (auto& [k, v] : acc)
    if (!negligible(v)) out.terms.emplace_back(k, v);
  return out;
}

}  // namespace wefm
