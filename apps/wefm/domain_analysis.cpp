#include "domain_picture.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_set>

namespace wefm_cli {

const Rgb kFlipFill{0, 0, 0};
const Rgb kFlipOutline{255, 0, 255};
const Rgb kDegenerate{150, 150, 150};
const Rgb kLoopColour{0, 0, 0};
const Rgb kSeamColour{0, 160, 60};

namespace {

uint64_t pair_key(int32_t a, int32_t b) {
  if (a > b) std::swap(a, b);
  return (static_cast<uint64_t>(static_cast<uint32_t>(a)) << 32) | static_cast<uint32_t>(b);
}

}  // namespace

Rgb distortion_colour(double log_ratio, double limit) {
  if (!std::isfinite(log_ratio)) return kDegenerate;
  const double t = std::clamp(log_ratio / limit, -1.0, 1.0);
  // ColorBrewer RdBu ends; white in the middle.
  static constexpr double kBlue[3] = {33, 102, 172}, kRed[3] = {178, 24, 43};
  const double* end = t < 0 ? kBlue : kRed;
  const double w = std::fabs(t);
  Rgb c;
  for (int i = 0; i < 3; ++i) c[i] = static_cast<uint8_t>(std::lround(255.0 * (1 - w) + end[i] * w));
  return c;
}

DomainAnalysis analyse_domain(const FaceSnapshot& snap) {
  DomainAnalysis a;
  const size_t nt = snap.tris.size() / 3;
  const auto& uv = snap.uv;
  const auto& xyz = snap.xyz;
  std::vector<double> signed_uv(nt), area3(nt);
  double sum_signed = 0, sum_abs = 0, sum3 = 0;
  for (size_t t = 0; t < nt; ++t) {
    const int32_t* u = &snap.tri_uses[3 * t];
    const double* p0 = &uv[2 * u[0]];
    const double* p1 = &uv[2 * u[1]];
    const double* p2 = &uv[2 * u[2]];
    signed_uv[t] = 0.5 * ((p1[0] - p0[0]) * (p2[1] - p0[1]) - (p1[1] - p0[1]) * (p2[0] - p0[0]));
    const int32_t* v = &snap.tris[3 * t];
    double e1[3], e2[3];
    for (int i = 0; i < 3; ++i) {
      e1[i] = xyz[3 * v[1] + i] - xyz[3 * v[0] + i];
      e2[i] = xyz[3 * v[2] + i] - xyz[3 * v[0] + i];
    }
    const double cx = e1[1] * e2[2] - e1[2] * e2[1], cy = e1[2] * e2[0] - e1[0] * e2[2],
                 cz = e1[0] * e2[1] - e1[1] * e2[0];
    area3[t] = 0.5 * std::sqrt(cx * cx + cy * cy + cz * cz);
    sum_signed += signed_uv[t];
    sum_abs += std::fabs(signed_uv[t]);
    sum3 += area3[t];
  }
  // Orientation is the majority's (a mirrored layout is not "all flipped"), as in uvcheck.py.
  const double orientation = sum_signed >= 0 ? 1.0 : -1.0;
  const double scale = sum_abs > 0 ? sum3 / sum_abs : 1.0;
  a.log_ratio.resize(nt);
  a.flipped.assign(nt, 0);
  std::vector<float> magnitudes;
  magnitudes.reserve(nt);
  for (size_t t = 0; t < nt; ++t) {
    a.flipped[t] = signed_uv[t] * orientation < 0;
    a.flips += a.flipped[t];
    const double r = std::fabs(signed_uv[t]) * scale;
    a.log_ratio[t] = area3[t] > 0 && r > 0 ? static_cast<float>(std::log(r / area3[t])) : std::nanf("");
    if (!a.flipped[t] && std::isfinite(a.log_ratio[t])) magnitudes.push_back(std::fabs(a.log_ratio[t]));
  }
  a.limit = std::log(1.1);
  if (!magnitudes.empty()) {
    const size_t k = std::min(magnitudes.size() - 1, magnitudes.size() * 99 / 100);
    std::nth_element(magnitudes.begin(), magnitudes.begin() + static_cast<std::ptrdiff_t>(k), magnitudes.end());
    a.limit = std::max(a.limit, static_cast<double>(magnitudes[k]));
  }
  const size_t nu = uv.size() / 2;
  if (nu) {
    a.umin = a.umax = uv[0];
    a.vmin = a.vmax = uv[1];
    for (size_t i = 1; i < nu; ++i) {
      a.umin = std::min(a.umin, uv[2 * i]);
      a.umax = std::max(a.umax, uv[2 * i]);
      a.vmin = std::min(a.vmin, uv[2 * i + 1]);
      a.vmax = std::max(a.vmax, uv[2 * i + 1]);
    }
  }
  // Seam segments are recognised by their 3D facet edge: the two sides of a repeated edge are
  // different uses of the same vertices, so this needs no assumption about how loops list uses.
  std::unordered_set<uint64_t> seam_edges;
  const auto& topo = snap.topology;
  for (size_t e = 0; e < topo.chains.size(); ++e) {
    if (topo.repeated[e] != 1) continue;
    const auto& c = topo.chains[e];
    for (size_t j = 0; j + 1 < c.size(); ++j) seam_edges.insert(pair_key(c[j], c[j + 1]));
  }
  for (const auto& loop : snap.loop_uses) {
    for (size_t j = 0; j < loop.size(); ++j) {
      const int32_t u0 = loop[j], u1 = loop[(j + 1) % loop.size()];
      if (u0 == u1 || u0 < 0 || u1 < 0 || static_cast<size_t>(u0) >= snap.use_vertex.size() ||
          static_cast<size_t>(u1) >= snap.use_vertex.size())
        continue;
      const bool seam = seam_edges.count(pair_key(snap.use_vertex[u0], snap.use_vertex[u1])) != 0;
      (seam ? a.seam_segments : a.loop_segments).push_back({u0, u1});
    }
  }
  return a;
}

int write_domain_picture(const std::string& path, const FaceSnapshot& snap, std::string& error) {
  const DomainAnalysis a = analyse_domain(snap);
  const bool png = path.size() >= 4 && (path.compare(path.size() - 4, 4, ".png") == 0 ||
                                        path.compare(path.size() - 4, 4, ".PNG") == 0);
  return png ? write_domain_png(path, snap, a, error) : write_domain_svg(path, snap, a, error);
}

}  // namespace wefm_cli
