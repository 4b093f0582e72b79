#include "wefm/core/meshing/mesh_control.hpp"

#include "wefm/core/sys/error.hpp"

namespace wefm::meshing {

void MeshControl::check(double fraction) const {
  if (cancel && cancel->load()) fail(Errc::cancelled, "meshing cancelled");
  if (progress && !progress(fraction)) fail(Errc::cancelled, "meshing cancelled by the progress callback");
}

}  // namespace wefm::meshing
