// load_cad_model: read, tessellate (BRepMesh at a deflection relative to the model size, or keep the
// file's triangulation), then import every face against one model-wide edge map.
#include "cad_model.hpp"

#include <chrono>
#include <cmath>

#include <BRepBndLib.hxx>
#include <BRepMesh_IncrementalMesh.hxx>
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <Standard_Failure.hxx>
#include <TopExp.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>

#include "cad_face_import.hpp"
#include "cad_reader.hpp"

namespace wefm_cad {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// Meshes `shape` (all faces, or with keep_triangulation only the faces that have none). Faces are
// meshed together so neighbouring faces share their edge discretisation.
void tessellate(const TopoDS_Shape& shape, const TopTools_IndexedMapOfShape& faces, const TessellationSettings& s,
                double deflection) {
  TopoDS_Shape target = shape;
  if (s.keep_triangulation) {
    BRep_Builder builder;
    TopoDS_Compound missing;
    builder.MakeCompound(missing);
    int count = 0;
    for (int i = 1; i <= faces.Extent(); ++i) {
      TopLoc_Location loc;
      if (BRep_Tool::Triangulation(TopoDS::Face(faces(i)), loc).IsNull()) {
        builder.Add(missing, faces(i));
        ++count;
      }
    }
    if (count == 0) return;
    target = missing;
  } else {
    BRepTools::Clean(shape);  // drop the file's triangulations so every face follows our deflection
  }
  BRepMesh_IncrementalMesh mesher(target, deflection, Standard_False, s.angular_deflection, Standard_True);
  (void)mesher;
}

}  // namespace

bool load_cad_model(const std::string& path, const TessellationSettings& settings, CadModel& model,
                    std::string& error) {
  model = CadModel{};
  model.path = path;
  if (!(settings.relative_deflection > 0) || !(settings.angular_deflection > 0)) {
    error = "the linear and angular deflections must be > 0";
    return false;
  }
  auto t0 = Clock::now();
  TopoDS_Shape shape;
  if (!read_cad_shape(path, shape, model.format, error)) return false;
  model.time_read = since(t0);
  try {
    TopTools_IndexedMapOfShape faces, edges;
    TopExp::MapShapes(shape, TopAbs_FACE, faces);
    TopExp::MapShapes(shape, TopAbs_EDGE, edges);
    model.edge_count = edges.Extent();
    if (faces.Extent() == 0) {
      error = path + ": the model has no face";
      return false;
    }
    Bnd_Box box;
    BRepBndLib::Add(shape, box);
    model.bbox_diagonal = box.IsVoid() ? 0.0 : std::sqrt(box.SquareExtent());
    model.linear_deflection = settings.relative_deflection * model.bbox_diagonal;
    if (!(model.linear_deflection > 0)) {
      error = path + ": the model has an empty bounding box";
      return false;
    }
    std::vector<bool> had_triangulation(static_cast<size_t>(faces.Extent()));
    for (int i = 1; i <= faces.Extent(); ++i) {
      TopLoc_Location loc;
      had_triangulation[static_cast<size_t>(i - 1)] = !BRep_Tool::Triangulation(TopoDS::Face(faces(i)), loc).IsNull();
    }
    t0 = Clock::now();
    tessellate(shape, faces, settings, model.linear_deflection);
    model.time_mesh = since(t0);
    t0 = Clock::now();
    for (int i = 1; i <= faces.Extent(); ++i) {
      model.faces.push_back(import_face(TopoDS::Face(faces(i)), edges, i));
      model.faces.back().triangulation_kept = settings.keep_triangulation && had_triangulation[static_cast<size_t>(i - 1)];
    }
    model.time_extract = since(t0);
  } catch (const Standard_Failure& f) {
    error = path + ": Open CASCADE: " + f.GetMessageString();
    return false;
  }
  return true;
}

}  // namespace wefm_cad
