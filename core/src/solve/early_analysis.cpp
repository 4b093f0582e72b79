#include "wefm/core/solve/early_analysis.hpp"

#include <exception>

namespace wefm {

namespace {

// Below this many uses the analysis is too short to be worth a thread of its own
// (docs/PERFORMANCE.md, "Measurements behind design choices").
constexpr Index kMinUses = 20000;

}  // namespace

bool early_analysis_pays(Index uses, int threads) { return threads >= 2 && uses >= kMinUses; }

EarlyAnalysis::EarlyAnalysis(const EnergyAssembler& pattern, PartitionedKKT& kkt, Index x0, Index x1,
                             const std::vector<Vec3>* points)
    : copied_future_(copied_.get_future().share()) {
  analysis_ = std::async(std::launch::async, [this, &pattern, &kkt, x0, x1, points] {
    try {
      kkt.set_pattern(static_cast<Index>(pattern.outer().size()) - 1, pattern.outer().data(), pattern.rows().data(), x0, x1, points);
    } catch (...) {
      copied_.set_exception(std::current_exception());
      throw;
    }
    copied_.set_value();
    kkt.analyse_pattern();
  });
}

EarlyAnalysis::~EarlyAnalysis() {
  if (analysis_.valid()) analysis_.wait();
}

void EarlyAnalysis::copied() { copied_future_.get(); }

void EarlyAnalysis::wait() { analysis_.get(); }

}  // namespace wefm
