#pragma once
// Everything the outputs need from a face handle, copied out once through the public getters, so the
// writers (OBJ, report, SVG/PNG, topology) work on plain vectors and never touch the handle.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "topology_file.hpp"
#include "wefm/wefm.h"

namespace wefm_cli {

struct EdgeDecision {
  int32_t edge = -1;                 // library edge index
  long long id = -1;                 // id in the topology file (or the index)
  int mode = WEFM_EDGE_AUTO;         // decision (AUTO resolved)
  int requested = WEFM_EDGE_AUTO;    // what the user asked for (per edge or default)
  std::array<double, 5> scores{};    // indexed by wefm_edge_mode, NaN = not tried
};

struct FaceSnapshot {
  // Mesh (input order).
  wefm_mesh_info info{};
  std::vector<double> xyz;       // 3 per vertex
  std::vector<int32_t> tris;     // 3 per triangle
  // Topology the library used (ids from the topology file when one was given).
  TopologyFile topology;
  std::vector<std::vector<int32_t>> loop_uses;
  int64_t use_count = 0;
  // Result (valid when has_result).
  bool has_result = false;
  std::vector<int32_t> use_vertex;   // 1 per use
  std::vector<int32_t> tri_uses;     // 3 per triangle
  std::vector<double> uv;            // 2 per use
  std::vector<EdgeDecision> decisions;  // repeated edges only
  wefm_report report{};
  std::vector<double> steps;         // 3 per continuation step
};

// Copies the topology (after a successful wefm_face_build). `ids` maps edges to file ids (may be
// empty: ids are the indices). Returns the failing status and leaves the message on the face.
wefm_status snapshot_topology(wefm_face* face, const std::vector<long long>& ids, FaceSnapshot& snap);

// Copies the result (after a solve that left one). `requested` per edge: the mode the user forced.
wefm_status snapshot_result(wefm_face* face, const std::vector<int>& requested, int default_mode, FaceSnapshot& snap);

}  // namespace wefm_cli
