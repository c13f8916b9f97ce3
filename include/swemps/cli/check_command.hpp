#pragma once
// `swe-mps check SCENE`: everything a run checks before its first step, and a report of what
// the run would be, without running it or writing anything: the domain and CRS, each raster's
// extent, cells, range and nodata, the particles, the memory, the first time step, and an
// estimate of the run's wall time from a few timed steps. Exit status as for `run`: a scene
// that `run` would refuse is refused here with the same message.

#include <string>

#include "swemps/cli/options.hpp"

namespace swemps::cli {

// Prints the report to standard output; throws what `run` throws before its first step
// (scenario::ScenarioError, UsageError, OutputError for an output path that cannot be
// written).
void check(const Options& options, const std::string& command_line);

}  // namespace swemps::cli
