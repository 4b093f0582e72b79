#pragma once
// The JSON quality report (--report; batch writes one per face). Field names are stable snake_case
// and documented in apps/README.md ("Report format"); add fields, never rename them.
#include <string>
#include <utility>
#include <vector>

#include "face_job.hpp"
#include "face_snapshot.hpp"

namespace wefm_cli {

struct ReportContext {
  std::string input;
  std::vector<std::pair<std::string, std::string>> outputs;
  int exit_code = 0;
  std::string message;
  Timings timings;
  std::vector<std::string> warnings;
  int threads = 0;  // wefm_options.threads of the solve
};

int write_report_json(const std::string& path, const ReportContext& ctx, const FaceSnapshot& snap, std::string& error);

}  // namespace wefm_cli
