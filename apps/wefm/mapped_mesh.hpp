#pragma once
// `wefm mesh-model`: one face meant to be mapped (four-sided, named by the caller, a thin tube)
// meshed as a transfinite grid on the model's edge nodes, or free on the same nodes where the grid
// is refused or not good enough, so the model conforms either way.
#include <array>
#include <cstdint>
#include <string>

#include "wefm/wefm.h"

namespace wefm_cli {

// How a face is to be meshed mapped.
struct MappedRequest {
  wefm_mesh_options options{};  // WEFM_MESH_TRANSFINITE: the grid wherever the library makes one;
                                // WEFM_MESH_AUTO: only a good one (the library's quad floor), else its free mesh
  double most_elements = 0;     // > 0: a grid with more than this many times the free mesh's elements is not kept
  std::array<int32_t, 4> corner_vertices{-1, -1, -1, -1};  // the corners as vertices of the face; -1: the
                                                           // library picks the domain's sharpest four
};

struct MappedOutcome {
  wefm_status status = WEFM_OK;  // of the mesh handed back
  bool transfinite = false;      // the grid was kept
  std::string refused;           // else why not (empty when the grid was kept)
};

// The transfinite grid of the solved `face`, unless the library refuses it (not four corners, unlike
// counts; with WEFM_MESH_AUTO also a grid whose worst quad is below the library's floor), or it has
// more elements than allowed against the free mesh (a grid carries an edge's fine segments all across
// the face, where a free mesh grades back up): then the free mesh with `free_options` (the options
// of request.options but for the type and corners). The mesh goes to *out (the caller releases it).
MappedOutcome mesh_mapped(wefm_face* face, const MappedRequest& request, const wefm_mesh_options& free_options, wefm_domain_mesh** out);

}  // namespace wefm_cli
