#pragma once
// Reading a CAD file into an Open CASCADE shape, by extension: STEP, IGES or OCCT's BREP text format.
#include <string>

#include <TopoDS_Shape.hxx>

namespace wefm_cad {

// Sets `format` to "step", "iges" or "brep". False + message when the extension is unknown, the file
// cannot be read or it holds no shape.
bool read_cad_shape(const std::string& path, TopoDS_Shape& shape, std::string& format, std::string& error);

}  // namespace wefm_cad
