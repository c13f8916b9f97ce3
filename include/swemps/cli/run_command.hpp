#pragma once
// The swe-mps commands: `run` (scenario file -> simulation of the scene's model -> netCDF
// output, with progress and a summary), `compare` (compare_command.hpp) and `study`
// (study_command.hpp).

#include <string>

#include "swemps/cli/options.hpp"

namespace swemps::cli {

// Exit statuses (also listed in usage_text()).
enum ExitStatus : int {
  exit_ok = 0,
  exit_internal = 1,
  exit_input = 2,
  exit_breakdown = 3,
  exit_output = 4,
};

// Runs options.command on the scene; throws scenario::ScenarioError, swe::SimulationError,
// ns::SimulationError, OutputError.
void run(const Options& options, const std::string& command_line);

class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace swemps::cli
