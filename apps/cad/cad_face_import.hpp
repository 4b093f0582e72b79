#pragma once
// One tessellated OCCT face -> CadFace (triangulation + topology). See cad_face_import.cpp for how
// seams and degenerate edges are merged.
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS_Face.hxx>

#include "cad_model.hpp"

namespace wefm_cad {

// `edges` is the model's edge map (ids are its 1-based indices, so an edge keeps its id in every face
// that uses it). `index` is the face's 1-based index in the model. On failure face.error says why;
// the face is otherwise left partly filled.
CadFace import_face(const TopoDS_Face& face, const TopTools_IndexedMapOfShape& edges, int index);

// OCCT surface type of a face in the index's vocabulary (plane, cylinder, ..., bspline, other).
std::string surface_type_name(const TopoDS_Face& face);

}  // namespace wefm_cad
