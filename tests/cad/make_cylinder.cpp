// Writes tests/data/cylinder.step: an Open CASCADE cylinder solid (radius 10, height 25), whose
// lateral face is a full cylinder with a seam edge. Run once to regenerate the checked-in file:
//   build/.../tests/cad/wefm_make_cylinder tests/data/cylinder.step
#include <cstdio>

#include <BRepPrimAPI_MakeCylinder.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <Interface_Static.hxx>
#include <STEPControl_Writer.hxx>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUT.step\n", argv[0]);
    return 2;
  }
  const TopoDS_Shape cylinder = BRepPrimAPI_MakeCylinder(10.0, 25.0).Shape();
  STEPControl_Writer writer;
  Interface_Static::SetCVal("write.step.schema", "AP214IS");
  if (writer.Transfer(cylinder, STEPControl_AsIs) != IFSelect_RetDone || writer.Write(argv[1]) != IFSelect_RetDone) {
    std::fprintf(stderr, "cannot write %s\n", argv[1]);
    return 1;
  }
  return 0;
}
