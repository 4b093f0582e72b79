// Raster picture of the domain: the cheap choice for huge faces (cost ~ pixels + triangles, file size
// bounded by the image size). Text does not fit a tiny writer, so the colour bar has no labels; the
// scale is stored in the PNG's tEXt "Comment" chunk and printed in --report/summary terms there.
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "domain_picture.hpp"
#include "exit_codes.hpp"
#include "output_file.hpp"

#ifdef WEFM_CLI_HAVE_ZLIB
#include <zlib.h>
#endif

namespace wefm_cli {

#ifdef WEFM_CLI_HAVE_ZLIB

namespace {

constexpr int kSize = 1600;   // pixels of the domain's longer side
constexpr int kMargin = 12;
constexpr int kBarWidth = 24;

struct Image {
  int w, h;
  std::vector<uint8_t> rgb;
  Image(int w_, int h_) : w(w_), h(h_), rgb(static_cast<size_t>(w_) * h_ * 3, 255) {}
  void set(int x, int y, const Rgb& c) {
    if (x < 0 || y < 0 || x >= w || y >= h) return;
    std::memcpy(&rgb[(static_cast<size_t>(y) * w + x) * 3], c.data(), 3);
  }
};

// Pixel-centre coverage test with edge functions: no gaps or overlaps between neighbours.
void fill_triangle(Image& img, const double* p0, const double* p1, const double* p2, const Rgb& c) {
  const double area = (p1[0] - p0[0]) * (p2[1] - p0[1]) - (p1[1] - p0[1]) * (p2[0] - p0[0]);
  if (area == 0) return;
  const int x0 = std::max(0, static_cast<int>(std::floor(std::min({p0[0], p1[0], p2[0]}))));
  const int x1 = std::min(img.w - 1, static_cast<int>(std::ceil(std::max({p0[0], p1[0], p2[0]}))));
  const int y0 = std::max(0, static_cast<int>(std::floor(std::min({p0[1], p1[1], p2[1]}))));
  const int y1 = std::min(img.h - 1, static_cast<int>(std::ceil(std::max({p0[1], p1[1], p2[1]}))));
  const double s = area > 0 ? 1.0 : -1.0;
  auto edge = [](const double* a, const double* b, double x, double y) {
    return (b[0] - a[0]) * (y - a[1]) - (b[1] - a[1]) * (x - a[0]);
  };
  bool any = false;
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      const double px = x + 0.5, py = y + 0.5;
      if (s * edge(p0, p1, px, py) >= 0 && s * edge(p1, p2, px, py) >= 0 && s * edge(p2, p0, px, py) >= 0) {
        img.set(x, y, c);
        any = true;
      }
    }
  }
  // Sub-pixel triangles would vanish; give them the pixel under their first corner.
  if (!any) img.set(static_cast<int>(p0[0]), static_cast<int>(p0[1]), c);
}

void thick_line(Image& img, double xa, double ya, double xb, double yb, int radius, const Rgb& c) {
  const int steps = static_cast<int>(std::ceil(std::max(std::fabs(xb - xa), std::fabs(yb - ya)))) + 1;
  for (int i = 0; i <= steps; ++i) {
    const double t = static_cast<double>(i) / steps;
    const int x = static_cast<int>(xa + (xb - xa) * t), y = static_cast<int>(ya + (yb - ya) * t);
    for (int dy = -radius; dy <= radius; ++dy)
      for (int dx = -radius; dx <= radius; ++dx) img.set(x + dx, y + dy, c);
  }
}

void chunk(std::string& png, const char* type, const std::string& data) {
  auto be32 = [&](uint32_t v) {
    for (int s = 24; s >= 0; s -= 8) png.push_back(static_cast<char>((v >> s) & 0xff));
  };
  be32(static_cast<uint32_t>(data.size()));
  const size_t start = png.size();
  png.append(type, 4);
  png += data;
  be32(static_cast<uint32_t>(crc32(0, reinterpret_cast<const Bytef*>(png.data() + start), static_cast<uInt>(png.size() - start))));
}

}  // namespace

int write_domain_png(const std::string& path, const FaceSnapshot& snap, const DomainAnalysis& a, std::string& error) {
  const double du = std::max(a.umax - a.umin, 1e-300), dv = std::max(a.vmax - a.vmin, 1e-300);
  const double k = (kSize - 1) / std::max(du, dv);
  const int dw = static_cast<int>(std::ceil(du * k)) + 1, dh = static_cast<int>(std::ceil(dv * k)) + 1;
  Image img(dw + 3 * kMargin + kBarWidth, std::max(dh, 256) + 2 * kMargin);
  auto X = [&](double u) { return kMargin + (u - a.umin) * k; };
  auto Y = [&](double v) { return kMargin + (a.vmax - v) * k; };
  const size_t nt = a.log_ratio.size();
  std::vector<size_t> flipped;
  for (size_t t = 0; t < nt; ++t) {
    double p[3][2];
    for (int c = 0; c < 3; ++c) {
      const double* q = &snap.uv[2 * static_cast<size_t>(snap.tri_uses[3 * t + c])];
      p[c][0] = X(q[0]);
      p[c][1] = Y(q[1]);
    }
    if (a.flipped[t]) flipped.push_back(t);
    else fill_triangle(img, p[0], p[1], p[2], distortion_colour(a.log_ratio[t], a.limit));
  }
  // Flipped triangles last, so neighbours drawn over them cannot hide them.
  for (size_t t : flipped) {
    double p[3][2];
    for (int c = 0; c < 3; ++c) {
      const double* q = &snap.uv[2 * static_cast<size_t>(snap.tri_uses[3 * t + c])];
      p[c][0] = X(q[0]);
      p[c][1] = Y(q[1]);
    }
    fill_triangle(img, p[0], p[1], p[2], kFlipFill);
    for (int c = 0; c < 3; ++c) thick_line(img, p[c][0], p[c][1], p[(c + 1) % 3][0], p[(c + 1) % 3][1], 0, kFlipOutline);
  }
  auto draw = [&](const std::vector<std::array<int32_t, 2>>& segs, const Rgb& c) {
    for (const auto& s : segs) {
      const double* q0 = &snap.uv[2 * static_cast<size_t>(s[0])];
      const double* q1 = &snap.uv[2 * static_cast<size_t>(s[1])];
      thick_line(img, X(q0[0]), Y(q0[1]), X(q1[0]), Y(q1[1]), 1, c);
    }
  };
  draw(a.loop_segments, kLoopColour);
  draw(a.seam_segments, kSeamColour);
  // Colour bar: top = stretched (+L), bottom = shrunk (-L), a black tick at white (exact).
  const int bx = dw + 2 * kMargin, by = kMargin, bh = img.h - 2 * kMargin;
  for (int y = 0; y < bh; ++y) {
    const Rgb c = distortion_colour(a.limit * (1.0 - 2.0 * y / std::max(bh - 1, 1)), a.limit);
    for (int x = 0; x < kBarWidth; ++x) img.set(bx + x, by + y, c);
  }
  for (int x = -4; x < kBarWidth + 4; ++x) img.set(bx + x, by + bh / 2, kLoopColour);

  std::string raw;
  raw.reserve(static_cast<size_t>(img.h) * (img.w * 3 + 1));
  for (int y = 0; y < img.h; ++y) {
    raw.push_back('\0');  // filter type: none
    raw.append(reinterpret_cast<const char*>(&img.rgb[static_cast<size_t>(y) * img.w * 3]), static_cast<size_t>(img.w) * 3);
  }
  uLongf zsize = compressBound(static_cast<uLong>(raw.size()));
  std::string z(zsize, '\0');
  if (compress2(reinterpret_cast<Bytef*>(&z[0]), &zsize, reinterpret_cast<const Bytef*>(raw.data()),
                static_cast<uLong>(raw.size()), 6) != Z_OK) {
    error = path + ": PNG compression failed";
    return kExitIo;
  }
  z.resize(zsize);
  std::string png("\x89PNG\r\n\x1a\n", 8);
  std::string ihdr;
  for (uint32_t v : {static_cast<uint32_t>(img.w), static_cast<uint32_t>(img.h)})
    for (int s = 24; s >= 0; s -= 8) ihdr.push_back(static_cast<char>((v >> s) & 0xff));
  ihdr += std::string("\x08\x02\x00\x00\x00", 5);  // 8-bit RGB, deflate, no filter, no interlace
  chunk(png, "IHDR", ihdr);
  char comment[256];
  std::snprintf(comment, sizeof comment,
                "wefm UV domain; colour = log(UV area/3D area) after normalisation, blue -%.4g .. white 0 .. "
                "red +%.4g (x%.4g .. x%.4g); flipped: %lld",
                a.limit, a.limit, std::exp(-a.limit), std::exp(a.limit), static_cast<long long>(a.flips));
  chunk(png, "tEXt", std::string("Comment") + '\0' + comment);
  chunk(png, "IDAT", z);
  chunk(png, "IEND", "");
  return write_file_atomically(path, png, error);
}

#else

int write_domain_png(const std::string& path, const FaceSnapshot&, const DomainAnalysis&, std::string& error) {
  error = path + ": PNG output needs zlib, which this build lacks; write .svg instead";
  return kExitIo;
}

#endif

}  // namespace wefm_cli
