#pragma once
// swe-mps ensemble: the members of an ensemble file run on this machine (each a child
// process), submitted to Slurm, run one by one (--member N), or collected into products
// (docs/ensembles.md).

#include <string>

#include "swemps/cli/options.hpp"

namespace swemps::cli {

// Throws scenario::ScenarioError (a broken ensemble file or member scene), OutputError,
// UsageError, CommandFailed (members that did not finish; a member's run that failed).
void ensemble(const Options& options, const std::string& command_line);

}  // namespace swemps::cli
