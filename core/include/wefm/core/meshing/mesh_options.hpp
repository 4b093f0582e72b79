#pragma once
// What a caller asks of the domain mesher (wefm_mesh_options) and what it reports back
// (wefm_mesh_report): the same fields, in core types.
#include <array>
#include <cstdint>

#include "wefm/core/sys/types.hpp"

namespace wefm::meshing {

// Automatic: transfinite where the domain is four-sided (four_corners) and the grid is good, else free.
enum class MeshType : int { Free = 0, Transfinite = 1, Automatic = 2 };
// Free meshes: triangles; quads where pairs of triangles make good ones (a triangle left as four
// nodes, the last -1); or quads only.
enum class Elements : int { Triangles = 0, QuadDominant = 1, Quads = 2 };

struct MeshOptions {
  MeshType type = MeshType::Free;
  double size = 0;                        // target 3D element size h
  std::array<Index, 4> corners{{-1, -1, -1, -1}};  // transfinite corners as uses on the outer loop
  bool quads = true;
  int smoothing_iterations = 5;
  double corner_angle_deg = 30;
  double min_angle_deg = 28;
  std::int64_t max_elements = 0;
  Elements elements = Elements::Triangles;
  bool split_chords = false;  // free meshes: split every edge between boundary nodes that leaves the surface (smoothing.hpp)
};

// Why MeshType::Automatic made a free mesh: None where it made the grid (or was not asked).
enum class AutomaticFallback : int { None = 0, NotFourSided = 1, GridRefused = 2, PoorGrid = 3 };

struct MeshReport {
  std::int64_t nodes = 0, elements = 0;
  int nodes_per_element = 3;
  double lambda_mesh = 0, lambda_min = 0, fraction_below_0_6 = 0;
  double scaled_jacobian_min = 0, scaled_jacobian_mean = 0;
  double wiggle_max = 0, wiggle_mean = 0;
  double time_boundary = 0, time_mesh = 0, time_smooth = 0, time_map = 0;
  std::int64_t quads = 0;               // elements with four nodes
  double quad_area_fraction = 0;        // their share of the mesh's 3D area
  std::int64_t outside_nodes = 0;  // nodes whose UV fell outside the solved domain (mapped to the nearest point)
  bool transfinite = false;        // the mesh is a transfinite grid (asked for, or chosen by Automatic)
  AutomaticFallback automatic_fallback = AutomaticFallback::None;
  double refused_grid_scaled_jacobian_min = 0;  // PoorGrid: the worst quad of the grid not kept
};

}  // namespace wefm::meshing
