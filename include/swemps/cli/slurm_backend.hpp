#pragma once
// The Slurm backend of swe-mps ensemble: the members as one job array (a task per member,
// `swe-mps ensemble FILE --member $SLURM_ARRAY_TASK_ID`, at most max_running at once) and a
// collection job (`--collect`) that starts once every task has ended, however it ended.

#include <cstddef>
#include <string>
#include <vector>

#include "swemps/cli/options.hpp"
#include "swemps/ensemble/ensemble.hpp"

namespace swemps::cli {

struct SlurmRequest {
  const ensemble::Ensemble& ensemble;
  std::vector<std::size_t> members;  // the members to run, ascending
  int threads = 1;                   // per member: --cpus-per-task
  const Options& options;            // the command line's sbatch settings
};

// Slurm's array notation of the indices, ranges joined: {0,1,2,5,7,8} -> "0-2,5,7-8".
std::string array_ranges(const std::vector<std::size_t>& indices);

// Writes <folder>/slurm/member.sbatch and collect.sbatch and submits them with sbatch. Throws
// CommandFailed when sbatch is missing or refuses (its message), OutputError when the scripts
// cannot be written.
void submit_to_slurm(const SlurmRequest& request);

}  // namespace swemps::cli
