// Flatten a mesh file read by OpenMesh and write it back with per-corner UVs, through
// wefm/openmesh.hpp. Edges marked as features would be cut as seams; an OBJ read by OpenMesh
// carries none, so give a disk-like face (or use wefm's --seams with the CLI).
//
//   flatten_openmesh IN.obj OUT.obj
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <cstdio>
#include <string>

#include "wefm/openmesh.hpp"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s IN.obj OUT.obj\n", argv[0]);
    return 2;
  }
  OpenMesh::TriMesh_ArrayKernelT<> mesh;
  if (!OpenMesh::IO::read_mesh(mesh, argv[1])) {
    std::fprintf(stderr, "cannot read %s\n", argv[1]);
    return 3;
  }
  mesh.request_halfedge_texcoords2D();
  wefm_report report;
  wefm_report_init(&report, sizeof report);
  std::string message;
  const wefm_status st = wefm::openmesh::flatten(mesh, nullptr, &report, &message);
  if (st != WEFM_OK && st != WEFM_ERROR_NOT_CONVERGED) {
    std::fprintf(stderr, "wefm: %s: %s\n", wefm_status_string(st), message.c_str());
    return 5;
  }
  OpenMesh::IO::Options out(OpenMesh::IO::Options::FaceTexCoord);
  if (!OpenMesh::IO::write_mesh(mesh, argv[2], out)) {
    std::fprintf(stderr, "cannot write %s\n", argv[2]);
    return 3;
  }
  std::printf("wrote %s: score %.6f, %lld flipped triangle(s)\n", argv[2], report.score, static_cast<long long>(report.flipped_triangles));
  return 0;
}
