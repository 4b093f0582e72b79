#include "model_atlas.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "domain_picture.hpp"
#include "svg_text.hpp"
#include "exit_codes.hpp"
#include "text_out.hpp"

namespace wefm_cli {

namespace {

constexpr double kCell = 240;     // cell side in px
constexpr double kPad = 14;       // inner margin of a cell
constexpr double kLabel = 30;     // label band under the domain


void text(TextOut& out, double x, double y, int size, const std::string& s) {
  out.put("<text x=\"");
  out.fixed(x, 1);
  out.put("\" y=\"");
  out.fixed(y, 1);
  out.put("\" font-size=\"");
  out.integer(size);
  out.put("\">");
  put_escaped(out, s.size() > 60 ? s.substr(0, 57) + "..." : s);
  out.put("</text>\n");
}

void domain(TextOut& out, const FaceSnapshot& snap, double x0, double y0) {
  const DomainAnalysis a = analyse_domain(snap);
  const double side = kCell - 2 * kPad;
  const double box = kCell - 2 * kPad - kLabel;
  const double span = std::max({a.umax - a.umin, a.vmax - a.vmin, 1e-300});
  const double k = std::min(side, box) / span;
  const double ox = x0 + kPad + 0.5 * (side - (a.umax - a.umin) * k);
  const double oy = y0 + kPad + 0.5 * (box - (a.vmax - a.vmin) * k);
  auto pt = [&](int32_t use) {
    out.fixed(ox + (snap.uv[2 * use] - a.umin) * k, 1);
    out.put(',');
    out.fixed(oy + (a.vmax - snap.uv[2 * use + 1]) * k, 1);  // SVG y grows downwards
  };
  const size_t nt = a.log_ratio.size();
  for (size_t t = 0; t < nt; ++t) {
    out.put("<polygon points=\"");
    for (int c = 0; c < 3; ++c) {
      if (c) out.put(' ');
      pt(snap.tri_uses[3 * t + c]);
    }
    out.put("\" fill=\"");
    put_hex(out, a.flipped[t] ? kFlipFill : distortion_colour(a.log_ratio[t], a.limit));
    if (a.flipped[t]) {
      out.put("\" stroke=\"");
      put_hex(out, kFlipOutline);
      out.put("\" stroke-width=\"0.8");
    }
    out.put("\"/>\n");
  }
  auto segments = [&](const std::vector<std::array<int32_t, 2>>& segs, const Rgb& colour, double width) {
    if (segs.empty()) return;
    out.put("<path fill=\"none\" stroke=\"");
    put_hex(out, colour);
    out.put("\" stroke-width=\"");
    out.fixed(width, 1);
    out.put("\" d=\"");
    for (const auto& s : segs) {
      out.put('M');
      pt(s[0]);
      out.put('L');
      pt(s[1]);
    }
    out.put("\"/>\n");
  };
  segments(a.loop_segments, kLoopColour, 1.0);
  segments(a.seam_segments, kSeamColour, 1.6);
}

}  // namespace

int write_model_atlas(const std::string& path, const std::string& title, const std::vector<AtlasCell>& cells,
                      std::string& error) {
  const size_t n = std::max<size_t>(1, cells.size());
  const size_t cols = static_cast<size_t>(std::ceil(std::sqrt(static_cast<double>(n))));
  const size_t rows = (n + cols - 1) / cols;
  const double header = 36;
  TextOut out;
  if (!out.open(path)) {
    error = out.error();
    return out.failure_code();
  }
  out.put("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"");
  out.fixed(cols * kCell, 0);
  out.put("\" height=\"");
  out.fixed(rows * kCell + header, 0);
  out.put("\" font-family=\"sans-serif\" stroke-linejoin=\"round\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n");
  text(out, 10, 24, 16, title);
  for (size_t i = 0; i < cells.size(); ++i) {
    const double x0 = static_cast<double>(i % cols) * kCell, y0 = header + static_cast<double>(i / cols) * kCell;
    const AtlasCell& c = cells[i];
    out.put("<g>\n<rect x=\"");
    out.fixed(x0 + 2, 0);
    out.put("\" y=\"");
    out.fixed(y0 + 2, 0);
    out.put("\" width=\"");
    out.fixed(kCell - 4, 0);
    out.put("\" height=\"");
    out.fixed(kCell - 4, 0);
    out.put(c.snap && c.snap->has_result ? "\" fill=\"none\" stroke=\"#cccccc\"/>\n"
                                         : "\" fill=\"#eeeeee\" stroke=\"#cc0000\"/>\n");
    if (c.snap && c.snap->has_result) domain(out, *c.snap, x0, y0);
    text(out, x0 + kPad, y0 + kCell - kPad - 14, 12, c.title);
    text(out, x0 + kPad, y0 + kCell - kPad, 11, c.caption);
    out.put("</g>\n");
  }
  out.put("</svg>\n");
  if (!out.close()) {
    error = out.error();
    return out.failure_code();
  }
  return kExitOk;
}

}  // namespace wefm_cli
