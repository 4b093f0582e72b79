#pragma once
// The symbolic analysis of K_PP on a thread of its own, started before the coefficients.
//
// Why: the analysis (minimum degree ordering, CHOLMOD's symbolic factorisation, the own
// factorisation's map of K's entries) is serial and needs only K's pattern, which the topology
// and the boundary loops fix; the coefficients and K's values need the analysis only when
// factorising. Side by side on two cores they stop waiting for each other. The layout is the same
// bits either way (the analysis reads no value).
#include <future>
#include <vector>

#include "wefm/core/method/energy_assembler.hpp"
#include "wefm/core/linalg/partitioned_kkt.hpp"
#include "wefm/core/sys/types.hpp"

namespace wefm {

class EarlyAnalysis {
 public:
  // Starts copying K's pattern (the assembler's) into kkt with x0, x1 split off, then analysing
  // it with `points` for the ordering. kkt, pattern and points must outlive this object; kkt is
  // not to be used until wait() returns, nor the assembler changed or freed until copied() does.
  EarlyAnalysis(const EnergyAssembler& pattern, PartitionedKKT& kkt, Index x0, Index x1, const std::vector<Vec3>* points);
  // Joins the thread (an analysis in progress runs to its end), its error dropped: the caller is
  // leaving on an error of its own.
  ~EarlyAnalysis();
  EarlyAnalysis(const EarlyAnalysis&) = delete;
  EarlyAnalysis& operator=(const EarlyAnalysis&) = delete;

  // Waits until the pattern is copied.
  void copied();
  // Waits for the analysis; rethrows its error (Error(out_of_memory) above the memory limit).
  void wait();

 private:
  std::promise<void> copied_;
  std::shared_future<void> copied_future_;
  std::future<void> analysis_;
};

// Whether a face is worth the thread: two threads or more, and large enough that the analysis
// takes long against starting a thread.
bool early_analysis_pays(Index uses, int threads);

}  // namespace wefm
