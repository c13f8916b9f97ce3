#pragma once
// The pathlines of a shallow-water run (docs/provenance.md, "Pathlines"): the particles the
// scene's output.pathlines chooses, followed from its start time, a vertex each interval, and
// written as a vector file when the run ends.

#include <filesystem>
#include <optional>
#include <string>

#include "swemps/io/pathline_writer.hpp"
#include "swemps/maps/pathlines.hpp"
#include "swemps/scenario/build.hpp"
#include "swemps/scenario/scenario.hpp"
#include "swemps/swe/simulation.hpp"
#include "swemps/swe/state_record.hpp"

namespace swemps::cli {

class PathlineOutput {
 public:
  // For a scene with output.pathlines; the area its polygon gives is terrain.pathline_area.
  PathlineOutput(const scenario::Scenario& scene, const scenario::Terrain& terrain);

  // After every step, and on the starting state: the lines whose particles went in the step
  // end; the particles are chosen at the first state at or after the start time; a vertex
  // is kept at the first state at or after each interval since.
  void observe(swe::Simulation& sim);
  // The run's last state as every line's last vertex, then the file (the partial one that a
  // stopped run left removed). OutputError on failure.
  void finish(const swe::Simulation& sim);
  // A run that stops early: the lines so far, with the state `last` as their last vertex
  // (null: the state is not trusted, and the lines end at their last vertex), to
  // "<stem>.partial<ext>" (returned); the file a run restarted from the checkpoint finishes
  // is whole.
  std::filesystem::path close_stopped(const swe::Simulation* last);

  void save_state(swe::StateWriter& out) const;
  void restore_state(swe::StateReader& in);

  const std::filesystem::path& path() const { return file_; }
  double seconds() const { return seconds_; }

 private:
  void write(const swe::Simulation* last, const std::filesystem::path& file);

  scenario::PathlineOutput spec_;
  std::filesystem::path file_;
  maps::PathlineChoice choice_;
  std::shared_ptr<const terrain::Footprints> area_;
  io::PathlineLayer layer_;
  maps::PathlineRecorder recorder_;
  double next_vertex_s_ = 0.0;  // after start
  double seconds_ = 0.0;
};

}  // namespace swemps::cli
