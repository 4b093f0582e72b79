#pragma once
// What the caller of a running mesh_domain can do: stop it, and hear how far it got. Meshing checks
// it between steps and every few hundred node insertions, so a stop takes effect within
// milliseconds whatever the face's size.
#include <atomic>
#include <functional>

namespace wefm::meshing {

struct MeshControl {
  // Set from another thread to stop: Error(cancelled).
  const std::atomic<bool>* cancel = nullptr;
  // Told the fraction done in [0, 1] (non-decreasing); returning false stops like `cancel`.
  std::function<bool(double fraction)> progress;

  // Throws Error(cancelled) when either asks to stop; reports `fraction` to `progress`.
  void check(double fraction) const;
};

}  // namespace wefm::meshing
