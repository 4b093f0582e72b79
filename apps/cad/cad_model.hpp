#pragma once
// A CAD model's faces as the flattener needs them: per face a triangulation (outward orientation) and
// its topology (edges as vertex chains with model-wide ids, loops of edge uses, the outer loop). This
// header is free of Open CASCADE types, so the CLI and the tests use it without OCCT's headers; only
// the .cpp files of apps/cad include OCCT. The library core and the C API never see it.
#include <cstdint>
#include <string>
#include <vector>

namespace wefm_cad {

// How faces get their triangulation.
struct TessellationSettings {
  // Linear deflection as a fraction of the model's bounding-box diagonal (the sample data's
  // "display-like" setting, 0.1 %), and the angular deflection in radians.
  double relative_deflection = 1e-3;
  double angular_deflection = 0.5;
  // Keep a triangulation the file already carries (BREP) instead of meshing again; faces without one
  // are meshed at the settings above.
  bool keep_triangulation = false;
};

struct CadEdge {
  long long id = -1;              // model-wide: index in TopExp::MapShapes(model, TopAbs_EDGE), 1-based
  std::vector<int32_t> vertices;  // chain of face vertices in the curve's direction (1 for degenerate)
  bool seam = false;              // closed on this face (BRep_Tool::IsClosed(edge, face))
  bool degenerated = false;       // pole or apex (BRep_Tool::Degenerated)
  std::string curve_type;         // OCCT's name: Line, Circle, BSplineCurve, ... ("Unknown" if degenerate)
};

struct CadEdgeUse {
  int32_t edge = 0;               // index into CadFace::edges
  bool reversed = false;          // walked against the chain's direction
};

struct CadFace {
  int index = 0;                  // 1-based, index in TopExp::MapShapes(model, TopAbs_FACE)
  std::string surface_type;       // plane, cylinder, cone, sphere, torus, bspline, bezier, revolution,
                                  // extrusion, offset, other
  std::vector<double> xyz;        // 3 per vertex (seam sides and degenerate points merged)
  std::vector<int32_t> triangles; // 3 per triangle, counter-clockwise seen from outside the face
  std::vector<CadEdge> edges;
  std::vector<std::vector<CadEdgeUse>> loops;  // each keeps the face on the left
  int outer_loop = -1;            // BRepTools::OuterWire
  int64_t dropped_triangles = 0;  // collapsed by merging seam sides / poles
  bool triangulation_kept = false;  // came from the file, not from BRepMesh
  std::string error;              // non-empty: the face could not be imported (why)
};

struct CadModel {
  std::string path;
  std::string format;             // step, iges, brep
  double bbox_diagonal = 0;
  double linear_deflection = 0;   // absolute, as used
  std::vector<CadFace> faces;     // every face of the model, in TopExp::MapShapes order
  int64_t edge_count = 0;         // model edges
  double time_read = 0, time_mesh = 0, time_extract = 0;  // seconds
};

// Reads STEP (.step/.stp), IGES (.iges/.igs) or OCCT BREP (.brep/.rle) and imports every face. Faces
// that cannot be imported carry `error`; the call fails (false + message) only when the file cannot
// be read at all.
bool load_cad_model(const std::string& path, const TessellationSettings& settings, CadModel& model,
                    std::string& error);

}  // namespace wefm_cad
