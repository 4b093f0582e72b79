#pragma once
// Owning pointers for the C API's handles, and the wall-clock helper the commands time stages with.
#include <chrono>
#include <memory>

#include <wefm/wefm.h>

namespace wefm_cli {

struct FaceDeleter {
  void operator()(wefm_face* f) const { wefm_face_release(f); }
};
struct MeshDeleter {
  void operator()(wefm_mesh* m) const { wefm_mesh_release(m); }
};
struct DomainMeshDeleter {
  void operator()(wefm_domain_mesh* m) const { wefm_domain_mesh_release(m); }
};
using OwnedFace = std::unique_ptr<wefm_face, FaceDeleter>;
using OwnedMesh = std::unique_ptr<wefm_mesh, MeshDeleter>;
using OwnedDomainMesh = std::unique_ptr<wefm_domain_mesh, DomainMeshDeleter>;

using Clock = std::chrono::steady_clock;
inline double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

}  // namespace wefm_cli
