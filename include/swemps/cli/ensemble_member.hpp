#pragma once
// One member of an ensemble, in its own folder: its scene (scenario.json), the run of it
// (`swe-mps run`, in a child process whose output goes to run.out) and a record of how the run
// ended (record.txt), which the collection reads. Every backend runs a member through here, so
// that a member run locally and one run by a scheduler are the same run.

#include <filesystem>
#include <limits>
#include <optional>
#include <string>

#include "swemps/ensemble/ensemble.hpp"

namespace swemps::cli {

// How a member's run ended.
struct MemberRecord {
  // "ok"; "breakdown" (the simulation broke down); "input" (the scene could not be read or
  // built); "output" (its files could not be written); "stopped" (by SIGINT or SIGTERM, after
  // writing what it had); "timeout" (stopped at the ensemble's run_time_limit); "killed" (by
  // a signal it could not handle: SIGKILL, out of memory); "failed" (anything else).
  std::string status = "failed";
  int exit_status = 1;  // the run's, as a shell reports it (128 + n for signal n)
  double wall_s = std::numeric_limits<double>::quiet_NaN();
  double peak_memory_mib = std::numeric_limits<double>::quiet_NaN();
  std::string host;      // where it ran
  std::string job;       // the scheduler's job, "12345_3" for a Slurm array task; empty locally
  std::string message;   // why it did not finish: the run's last message; empty when ok
  bool resumed = false;  // the run went on from the checkpoint an earlier run left
};

std::filesystem::path member_folder(const ensemble::Ensemble& ensemble, std::size_t index);

// The record a member's last run left; nullopt when there is none (never run, or killed before
// it could write one) or it cannot be read.
std::optional<MemberRecord> read_member_record(const std::filesystem::path& folder);

// Writes the member's scene into its folder (made if missing), after reading it as its run
// will, and returns the scene's path. Throws scenario::ScenarioError naming the member.
std::filesystem::path write_member_scene(const ensemble::Ensemble& ensemble,
                                         const ensemble::Member& member);

// Runs the member: writes its scene, clears what an earlier run left (record, result), runs
// `swe-mps run` on it with `threads` OpenMP threads in a child process (stopped after the
// ensemble's run_time_limit), and writes and returns its record. SIGINT and SIGTERM reach the
// run, which stops as a run does, leaving a checkpoint; this process waits for it and records
// how it ended. A member whose earlier run did not finish but left a checkpoint and its
// partial result, for the same scene, goes on from there (`swe-mps run --restart`), to the
// same result as a run straight through; anything else an unfinished run left is removed.
MemberRecord run_member(const ensemble::Ensemble& ensemble, const ensemble::Member& member,
                        int threads);

}  // namespace swemps::cli
