#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "domain_picture.hpp"
#include "svg_text.hpp"
#include "exit_codes.hpp"
#include "text_out.hpp"

namespace wefm_cli {

namespace {

constexpr double kDomainPx = 1000;  // the longer side of the domain in the picture
constexpr double kMargin = 20;
constexpr double kLegendWidth = 190;
constexpr int kBins = 32;           // colour bins per side of white, for the large-mesh mode

struct View {
  double k = 1, u0 = 0, v1 = 0;
  double x(double u) const { return kMargin + (u - u0) * k; }
  double y(double v) const { return kMargin + (v1 - v) * k; }  // SVG y grows downwards
};


void point(TextOut& out, const View& view, const double* p) {
  out.fixed(view.x(p[0]), 2);
  out.put(',');
  out.fixed(view.y(p[1]), 2);
}

std::string ratio_label(double log_ratio) {
  char buf[32];
  const double r = std::exp(log_ratio);
  std::snprintf(buf, sizeof buf, r >= 10 || r < 0.1 ? "&#215;%.3g" : "&#215;%.2f", r);
  return buf;
}

// Each triangle its own <polygon>: easy to inspect and to count (the tests do).
void polygons(TextOut& out, const FaceSnapshot& snap, const DomainAnalysis& a, const View& view) {
  const size_t nt = a.log_ratio.size();
  for (size_t t = 0; t < nt; ++t) {
    const bool flip = a.flipped[t];
    const Rgb fill = flip ? kFlipFill : distortion_colour(a.log_ratio[t], a.limit);
    out.put("<polygon points=\"");
    for (int c = 0; c < 3; ++c) {
      if (c) out.put(' ');
      point(out, view, &snap.uv[2 * static_cast<size_t>(snap.tri_uses[3 * t + c])]);
    }
    out.put("\" fill=\"");
    put_hex(out, fill);
    out.put("\" stroke=\"");
    // Stroking with the fill colour hides the hairline gaps anti-aliasing leaves between triangles.
    put_hex(out, flip ? kFlipOutline : fill);
    out.put(flip ? "\" stroke-width=\"1.5\"/>\n" : "\"/>\n");
  }
}

// Large meshes: triangles grouped by quantised colour, one <path> (one subpath per triangle) per
// group, so the file has ~70 elements instead of a million and viewers stay responsive.
void binned_paths(TextOut& out, const FaceSnapshot& snap, const DomainAnalysis& a, const View& view) {
  const size_t nt = a.log_ratio.size();
  const int n_bins = 2 * kBins + 1 + 2;  // colour bins, degenerate, flipped
  const int degenerate_bin = 2 * kBins + 1, flip_bin = degenerate_bin + 1;
  std::vector<int> bin(nt);
  std::vector<size_t> count(n_bins, 0);
  for (size_t t = 0; t < nt; ++t) {
    int b;
    if (a.flipped[t]) b = flip_bin;
    else if (!std::isfinite(a.log_ratio[t])) b = degenerate_bin;
    else b = kBins + static_cast<int>(std::lround(std::clamp(a.log_ratio[t] / a.limit, -1.0, 1.0) * kBins));
    bin[t] = b;
    ++count[b];
  }
  for (int b = 0; b < n_bins; ++b) {
    if (!count[b]) continue;
    Rgb fill = b == flip_bin ? kFlipFill
               : b == degenerate_bin ? kDegenerate
                                     : distortion_colour(a.limit * (b - kBins) / kBins, a.limit);
    out.put("<path fill=\"");
    put_hex(out, fill);
    out.put("\" stroke=\"");
    put_hex(out, b == flip_bin ? kFlipOutline : fill);
    out.put("\" d=\"");
    for (size_t t = 0; t < nt; ++t) {
      if (bin[t] != b) continue;
      for (int c = 0; c < 3; ++c) {
        out.put(c ? 'L' : 'M');
        const double* p = &snap.uv[2 * static_cast<size_t>(snap.tri_uses[3 * t + c])];
        out.fixed(view.x(p[0]), 1);
        out.put(',');
        out.fixed(view.y(p[1]), 1);
      }
      out.put('Z');
    }
    out.put("\"/>\n");
  }
}

void segments(TextOut& out, const FaceSnapshot& snap, const View& view,
              const std::vector<std::array<int32_t, 2>>& segs) {
  out.put("<path d=\"");
  for (const auto& s : segs) {
    out.put('M');
    point(out, view, &snap.uv[2 * static_cast<size_t>(s[0])]);
    out.put('L');
    point(out, view, &snap.uv[2 * static_cast<size_t>(s[1])]);
  }
  out.put("\"/>\n");
}

void legend(TextOut& out, const DomainAnalysis& a, double x0, double height) {
  const double bar_top = kMargin + 30, bar_h = std::min(300.0, height - 2 * kMargin - 150);
  out.put("<g id=\"legend\" font-family=\"sans-serif\" font-size=\"12\">\n");
  out.put("<defs><linearGradient id=\"distortion\" x1=\"0\" y1=\"1\" x2=\"0\" y2=\"0\">\n");
  for (int i = 0; i <= 8; ++i) {
    const double t = -1.0 + i / 4.0;
    out.put("<stop offset=\"");
    out.fixed(i / 8.0, 3);
    out.put("\" stop-color=\"");
    put_hex(out, distortion_colour(t * a.limit, a.limit));
    out.put("\"/>\n");
  }
  out.put("</linearGradient></defs>\n");
  char buf[1536];
  std::snprintf(buf, sizeof buf,
                "<text x=\"%.1f\" y=\"%.1f\">area UV/3D (normalised)</text>\n"
                "<rect x=\"%.1f\" y=\"%.1f\" width=\"24\" height=\"%.1f\" fill=\"url(#distortion)\" stroke=\"#000\"/>\n",
                x0, kMargin + 15, x0, bar_top, bar_h);
  out.put(buf);
  for (int i = 0; i <= 4; ++i) {
    const double t = 1.0 - i / 2.0;  // top = stretched
    const double y = bar_top + bar_h * i / 4.0;
    const std::string label = ratio_label(t * a.limit) + (i == 0 ? " stretched" : i == 4 ? " shrunk" : i == 2 ? " exact" : "");
    std::snprintf(buf, sizeof buf, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#000\"/>"
                  "<text x=\"%.1f\" y=\"%.1f\">%s</text>\n",
                  x0 + 24, y, x0 + 30, y, x0 + 34, y + 4, label.c_str());
    out.put(buf);
  }
  double y = bar_top + bar_h + 30;
  std::snprintf(buf, sizeof buf,
                "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#000000\" stroke-width=\"3\"/>"
                "<text x=\"%.1f\" y=\"%.1f\">loop</text>\n"
                "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#00a03c\" stroke-width=\"3\"/>"
                "<text x=\"%.1f\" y=\"%.1f\">repeated edge (seam)</text>\n"
                "<rect x=\"%.1f\" y=\"%.1f\" width=\"24\" height=\"12\" fill=\"#000000\" stroke=\"#ff00ff\" stroke-width=\"1.5\"/>"
                "<text x=\"%.1f\" y=\"%.1f\">flipped (%lld)</text>\n"
                "<rect x=\"%.1f\" y=\"%.1f\" width=\"24\" height=\"12\" fill=\"#969696\"/>"
                "<text x=\"%.1f\" y=\"%.1f\">zero 3D area</text>\n",
                x0, y, x0 + 24, y, x0 + 34, y + 4, x0, y + 22, x0 + 24, y + 22, x0 + 34, y + 26, x0, y + 38,
                x0 + 34, y + 48, static_cast<long long>(a.flips), x0, y + 60, x0 + 34, y + 70);
  out.put(buf);
  out.put("</g>\n");
}

}  // namespace

int write_domain_svg(const std::string& path, const FaceSnapshot& snap, const DomainAnalysis& a, std::string& error) {
  const double du = std::max(a.umax - a.umin, 1e-300), dv = std::max(a.vmax - a.vmin, 1e-300);
  View view;
  view.k = kDomainPx / std::max(du, dv);
  view.u0 = a.umin;
  view.v1 = a.vmax;
  const double width = 2 * kMargin + du * view.k + kLegendWidth;
  const double height = std::max(2 * kMargin + dv * view.k, 520.0);
  TextOut out;
  if (!out.open(path)) {
    error = out.error();
    return out.failure_code();
  }
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
                "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" viewBox=\"0 0 %.0f %.0f\">\n",
                width, height, width, height);
  out.put(buf);
  out.put("<title>wefm UV domain</title>\n<desc>");
  put_escaped(out, "triangles: " + std::to_string(a.log_ratio.size()) + ", flipped: " + std::to_string(a.flips) +
                   ", colour scale +-" + std::to_string(a.limit) + " in log(UV area/3D area)");
  out.put("</desc>\n<rect x=\"0\" y=\"0\" width=\"100%\" height=\"100%\" fill=\"#ffffff\"/>\n");
  out.put("<g id=\"triangles\" stroke-width=\"0.3\" stroke-linejoin=\"round\">\n");
  if (a.log_ratio.size() <= kSvgPolygonLimit) polygons(out, snap, a, view);
  else binned_paths(out, snap, a, view);
  out.put("</g>\n<g id=\"loops\" fill=\"none\" stroke=\"#000000\" stroke-width=\"2.5\" stroke-linecap=\"round\">\n");
  segments(out, snap, view, a.loop_segments);
  out.put("</g>\n<g id=\"seams\" fill=\"none\" stroke=\"#00a03c\" stroke-width=\"3\" stroke-linecap=\"round\">\n");
  segments(out, snap, view, a.seam_segments);
  out.put("</g>\n");
  legend(out, a, 2 * kMargin + du * view.k, height);
  out.put("</svg>\n");
  if (!out.close()) {
    error = out.error();
    return out.failure_code();
  }
  return kExitOk;
}

}  // namespace wefm_cli
