#pragma once
// Which of the found faces one `wefm batch` run flattens: --shard I/N splits a batch over the tasks
// of a job array (Slurm, --array=0-(N-1)), --skip-existing resumes a run that stopped part way.
#include <string>
#include <vector>

#include "batch_inputs.hpp"
#include "face_job.hpp"

namespace wefm_cli {

struct Shard {
  long long index = 0;  // 0-based: SLURM_ARRAY_TASK_ID of --array=0-(N-1)
  long long count = 1;
};

// "I/N" with 0 <= I < N (whole numbers, nothing else). False with a message otherwise.
bool parse_shard(const std::string& text, Shard& shard, std::string& error);

// Keeps the items of `shard`, in their order: the k-th item in byte order of the output names (unique
// within a batch, the same in every task that lists the same inputs) belongs to shard k mod N, so
// the N shards are disjoint, cover the batch, and differ in size by one face at most.
void keep_shard(std::vector<BatchItem>& items, const Shard& shard);

// A face flattened by an earlier run: every output exists as a regular file (written whole: outputs
// are renamed into place, output_file.hpp) and the report (.json) parses and says a result was
// written ("ok" or "not_converged"). Then `outcome` holds the report's exit code, triangle count
// and scores for the summary, and the function returns true.
bool earlier_result(const std::vector<std::string>& outputs, const std::string& report, FaceOutcome& outcome);

}  // namespace wefm_cli
