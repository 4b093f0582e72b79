#pragma once
#include <string>

#include "face_job.hpp"

namespace wefm_cli {

// The one-screen human summary of a flatten run (stdout, unless --quiet).
void print_summary(const std::string& input, const FaceOutcome& outcome);

}  // namespace wefm_cli
