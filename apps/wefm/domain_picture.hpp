#pragma once
// Pictures of the UV domain (--svg). What is drawn, whatever the format:
//  * triangles coloured by area distortion log(UV area / 3D area) after scaling the UV layout to the
//    3D area, on a diverging map: blue = shrunk, white = exact, red = stretched. The colour scale is
//    symmetric, +-L with L the 99th percentile of |log ratio| (at least log 1.1 so a near-isometric
//    map stays white instead of amplifying noise); beyond L colours saturate;
//  * flipped triangles black with a magenta outline; zero-area 3D triangles grey;
//  * loops bold black, repeated edges (seams) bold green on both of their sides.
// Format by extension: ".png" writes a raster (cheap at any size); anything else writes SVG: one
// <polygon> per triangle up to kSvgPolygonLimit triangles, above it one <path> per colour bin.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "face_snapshot.hpp"

namespace wefm_cli {

constexpr size_t kSvgPolygonLimit = 200000;

struct DomainAnalysis {
  std::vector<float> log_ratio;        // per triangle; NaN for zero-area 3D triangles
  std::vector<uint8_t> flipped;        // per triangle
  int64_t flips = 0;
  double limit = 0;                    // L of the colour scale
  double umin = 0, umax = 0, vmin = 0, vmax = 0;
  std::vector<std::array<int32_t, 2>> loop_segments;  // use pairs along loops (not seams)
  std::vector<std::array<int32_t, 2>> seam_segments;  // use pairs along repeated edges, both sides
};

DomainAnalysis analyse_domain(const FaceSnapshot& snap);

using Rgb = std::array<uint8_t, 3>;
Rgb distortion_colour(double log_ratio, double limit);
extern const Rgb kFlipFill, kFlipOutline, kDegenerate, kLoopColour, kSeamColour;

// Returns 0 or 3 with a message.
int write_domain_picture(const std::string& path, const FaceSnapshot& snap, std::string& error);
int write_domain_svg(const std::string& path, const FaceSnapshot& snap, const DomainAnalysis& a, std::string& error);
int write_domain_png(const std::string& path, const FaceSnapshot& snap, const DomainAnalysis& a, std::string& error);

}  // namespace wefm_cli
