#pragma once
// The swe-mps commands: `run` (scenario file -> simulation of the scene's model -> netCDF
// output, with progress and a summary), `compare` (compare_command.hpp), `study`
// (study_command.hpp) and `ensemble` (ensemble_command.hpp).

#include <stdexcept>
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
  // An ensemble some of whose members did not finish.
  exit_members_failed = 5,
  // Stopped by a signal after writing what the run had: 128 + the signal's number, as a shell
  // reports a process the signal ended (130 for SIGINT, 143 for SIGTERM).
  exit_signal = 128,
};

// Runs options.command on the scene; throws scenario::ScenarioError, swe::SimulationError,
// ns::SimulationError, OutputError, RunStopped, io::CheckpointError, UsageError.
void run(const Options& options, const std::string& command_line);

class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A command that ends with an exit status of its own and a message: an ensemble whose members
// did not all finish, a member whose run failed (its run's status).
class CommandFailed : public std::runtime_error {
 public:
  CommandFailed(int status, const std::string& message)
      : std::runtime_error(message), status_(status) {}
  int status() const { return status_; }

 private:
  int status_;
};

// A run stopped by SIGINT or SIGTERM, after it wrote the state it stopped at and closed its
// files; what() says what was written and how to go on.
class RunStopped : public std::runtime_error {
 public:
  RunStopped(int signal_number, const std::string& message)
      : std::runtime_error(message), signal_number_(signal_number) {}
  int signal_number() const { return signal_number_; }

 private:
  int signal_number_;
};

}  // namespace swemps::cli
