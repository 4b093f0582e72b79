#include "batch_selection.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sys/stat.h>

#include "args.hpp"
#include "exit_codes.hpp"

namespace wefm_cli {

bool parse_shard(const std::string& text, Shard& shard, std::string& error) {
  const size_t slash = text.find('/');
  long long index = -1, count = 0;
  if (slash == std::string::npos || !parse_int(text.substr(0, slash), index) ||
      !parse_int(text.substr(slash + 1), count)) {
    error = "--shard: expected I/N (0-based shard I of N, e.g. 0/4), got '" + text + "'";
    return false;
  }
  if (count < 1 || index < 0 || index >= count) {
    error = "--shard " + text + ": I must be in 0.." + (count >= 1 ? std::to_string(count - 1) : "N-1") +
            " and N >= 1 (I is 0-based, as SLURM_ARRAY_TASK_ID with --array=0-" +
            (count >= 1 ? std::to_string(count - 1) : "N-1") + ")";
    return false;
  }
  shard = {index, count};
  return true;
}

void keep_shard(std::vector<BatchItem>& items, const Shard& shard) {
  std::vector<size_t> by_name(items.size());
  for (size_t k = 0; k < by_name.size(); ++k) by_name[k] = k;
  std::sort(by_name.begin(), by_name.end(), [&](size_t a, size_t b) { return items[a].name < items[b].name; });
  std::vector<char> keep(items.size(), 0);
  for (size_t k = 0; k < by_name.size(); ++k) keep[by_name[k]] = static_cast<long long>(k % shard.count) == shard.index;
  std::vector<BatchItem> kept;
  for (size_t k = 0; k < items.size(); ++k)
    if (keep[k]) kept.push_back(std::move(items[k]));
  items = std::move(kept);
}

bool earlier_result(const std::vector<std::string>& outputs, const std::string& report, FaceOutcome& outcome) {
  for (const std::string& path : outputs) {
    struct stat st;
    if (stat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) return false;
  }
  std::ifstream in(report);
  const nlohmann::json j = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
  if (!j.is_object()) return false;
  const std::string status = j.value("status", "");
  if (status != "ok" && status != "not_converged") return false;
  outcome = FaceOutcome{};
  outcome.exit_code = status == "ok" ? kExitOk : kExitSolver;
  outcome.snap.has_result = true;
  // Only numbers are read: a report edited by hand gives "-" in the summary, never an exception.
  const auto number = [](const nlohmann::json& obj, const char* key) {
    const auto it = obj.find(key);
    return it != obj.end() && it->is_number() ? it->get<double>() : NAN;
  };
  const auto count = [&](const nlohmann::json& obj, const char* key) {
    const double v = number(obj, key);
    return std::isfinite(v) ? static_cast<int64_t>(v) : int64_t{0};
  };
  outcome.snap.report.score = number(j, "score");
  outcome.snap.report.flipped_triangles = count(j, "flipped_triangles");
  outcome.snap.report.boundary_intersections = count(j, "boundary_intersections");
  const auto mesh = j.find("mesh");
  if (mesh != j.end() && mesh->is_object()) outcome.snap.info.triangles = count(*mesh, "triangles");
  return true;
}

}  // namespace wefm_cli
