#pragma once
// Going on from a checkpoint, whichever model wrote it: the file is read and checked against
// the scenario file before anything is built, so that a wrong checkpoint is refused at once.

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>

#include "swemps/cli/output.hpp"
#include "swemps/io/checkpoint.hpp"

namespace swemps::cli {

// What a run restarted from a checkpoint goes on from.
struct Restart {
  std::filesystem::path file;
  io::Checkpoint checkpoint;
};

// Reads the checkpoint; throws io::CheckpointError unless it was written for the scenario
// file whose text hashes to `scenario_hash`. A checkpoint of another program version is used
// with a warning.
Restart read_restart(const std::filesystem::path& file, std::uint64_t scenario_hash,
                     const std::filesystem::path& scenario_file);

// What a run knows of checkpoints before it builds anything: the scenario file's hash when it
// writes or reads them (0 otherwise), and the checkpoint it goes on from, read and checked.
struct CheckpointPlan {
  std::uint64_t scenario_hash = 0;
  std::optional<Restart> restart;
};
CheckpointPlan plan_checkpoints(const RunContext& context);

// Writes the checkpoint of a run at (time_s, steps) to `file`: the simulation's saved state
// and the run's own record, stamped with the scenario's hash and this program, and logs where
// it went, its size and the time it took (from `started`). Throws OutputError.
void write_run_checkpoint(const std::filesystem::path& file, std::uint64_t scenario_hash,
                          double time_s, std::uint64_t steps, std::span<const std::byte> simulation,
                          std::span<const std::byte> run,
                          std::chrono::steady_clock::time_point started);

}  // namespace swemps::cli
