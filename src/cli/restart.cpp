#include "swemps/cli/restart.hpp"

#include <spdlog/spdlog.h>

#include <string>

#include "swemps/cli/output.hpp"
#include "swemps/cli/timing.hpp"

namespace swemps::cli {

Restart read_restart(const std::filesystem::path& file, std::uint64_t scenario_hash,
                     const std::filesystem::path& scenario_file) {
  Restart r{file, io::read_checkpoint(file)};
  if (r.checkpoint.scenario_hash != scenario_hash) {
    throw io::CheckpointError("the checkpoint '" + file.string() + "' was written for another " +
                              "scenario than '" + scenario_file.string() +
                              "' (its text has changed, or it is another file): a run can only "
                              "go on with the scene it started with");
  }
  const std::string program = std::string("swe-mps ") + SWEMPS_VERSION;
  if (r.checkpoint.program != program) {
    spdlog::warn(
        "the checkpoint was written by {}, this is {}: the run goes on, but need not "
        "match one run straight through bit for bit",
        r.checkpoint.program, program);
  }
  return r;
}

CheckpointPlan plan_checkpoints(const RunContext& context) {
  CheckpointPlan plan;
  if (context.checkpoints || context.restart) {
    plan.scenario_hash = io::file_hash(context.scenario_file);
  }
  if (context.restart) {
    plan.restart = read_restart(*context.restart, plan.scenario_hash, context.scenario_file);
  }
  return plan;
}

void write_run_checkpoint(const std::filesystem::path& file, std::uint64_t scenario_hash,
                          double time_s, std::uint64_t steps, std::span<const std::byte> simulation,
                          std::span<const std::byte> run,
                          std::chrono::steady_clock::time_point started) {
  io::Checkpoint c;
  c.scenario_hash = scenario_hash;
  c.program = std::string("swe-mps ") + SWEMPS_VERSION;
  c.time_s = time_s;
  c.steps = steps;
  c.simulation.assign(simulation.begin(), simulation.end());
  c.run.assign(run.begin(), run.end());
  writing([&] { io::write_checkpoint(file, c); });
  spdlog::info("checkpoint at t = {:.9g} s (step {}): {} ({:.3f} MB, {:.3f} s)", time_s, steps,
               file.string(), static_cast<double>(c.simulation.size() + c.run.size()) / 1e6,
               seconds_since(started));
}

}  // namespace swemps::cli
