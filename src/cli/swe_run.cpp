// A shallow-water run: scene -> swe::Simulation -> netCDF maps, gauges and volume balance;
// and how it fails well: a breakdown or a stop signal still leaves a readable file holding the
// state reached, and a checkpoint to go on from.

#include <omp.h>
#include <spdlog/fmt/fmt.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "swemps/cli/pathline_output.hpp"
#include "swemps/cli/progress.hpp"
#include "swemps/cli/restart.hpp"
#include "swemps/cli/runs.hpp"
#include "swemps/cli/statistics_sampling.hpp"
#include "swemps/cli/stop_signals.hpp"
#include "swemps/cli/timing.hpp"
#include "swemps/io/checkpoint.hpp"
#include "swemps/scenario/build.hpp"
#include "swemps/swe/simulation.hpp"

namespace swemps::cli {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

constexpr const char* kRunStateLabel = "swe-mps shallow-water run";

// When the next series sample is due: the first multiple of `interval_s` after `time_s`.
// Samples are taken at the end of the first step that reaches one, so that sampling never
// shortens a step: the run is the same whatever the series interval.
double next_sample_time(double time_s, double interval_s) {
  // A step ending a rounding error short of a multiple counts as reaching it.
  const double multiples = std::floor(time_s / interval_s * (1.0 + 1e-12) + 1e-12);
  return (multiples + 1.0) * interval_s;
}

// The file of a shallow-water run: maps at output times; gauges, the volume balance and the
// flood statistics at every sample. Timed, for the summary.
class SweOutput {
 public:
  SweOutput(const scenario::Scenario& scene, const scenario::Terrain& terrain,
            const swe::RegularGrid& grid, const RunContext& context,
            const std::optional<io::WriterPosition>& resume)
      : grid_(grid),
        gravity_(scene.numerics.gravity_m_s2),
        cells_(scenario::map_reader(scene, terrain, grid)),
        gauges_(scene.output.gauges),
        write_particles_(scene.output.write_particles),
        file_(scene, terrain, grid, context, scene.output.write_particles, "", "", resume) {
    for (const auto& g : gauges_) {
      gauge_bed_m_.push_back(file_.bed_at(g.position_m[0], g.position_m[1]));
      gauge_cells_.push_back(scenario::gauge_reader(scene, terrain, grid, g.position_m));
    }
  }

  // At most once a state: a run that stops just after writing an output time's maps does not
  // write them twice.
  void write_maps(swe::Simulation& sim) {
    if (mapped_ && mapped_step_ == sim.steps() && mapped_time_s_ == sim.time()) return;
    const auto start = Clock::now();
    const auto& f = fields(sim);
    file_.write_maps(sim.time(), {f.depth, f.u, f.v, f.label_depth, f.entry_time},
                     write_particles_ ? &sim.particles() : nullptr);
    mapped_ = true;
    mapped_step_ = sim.steps();
    mapped_time_s_ = sim.time();
    seconds_ += seconds_since(start);
  }

  // The flood statistics, so that a peak between series samples is kept: at most once a step,
  // and once a wave could have crossed half a map cell since the last sample (the Courant
  // number 0.5 of a grid model on those cells; half a particle spacing where the cells are
  // finer: statistics_interval), or when `due_now` (an output time, so that the
  // envelopes hold every map written). A cell's water cannot change faster than that, so the
  // envelopes keep every peak the maps can show; the particles' steps are several times
  // shorter (the fastest of a few thousand sets them), and sampling each would cost as much
  // again as the run's own summations on the valley flood.
  void update_statistics(swe::Simulation& sim, bool due_now = false) {
    if (counted_ && counted_step_ == sim.steps()) return;
    if (counted_ && !due_now && sim.time() < next_statistics_s_ * (1.0 - 1e-12)) return;
    // The state's depths are the next step's (refresh() is cached): not the statistics' cost.
    sim.refresh();
    const auto start = Clock::now();
    const auto& f = fields(sim);
    file_.update_statistics(sim.time(), {f.depth, f.u, f.v, f.label_depth, f.entry_time});
    counted_ = true;
    counted_step_ = sim.steps();
    ++statistics_samples_;
    next_statistics_s_ = sim.time() + statistics_interval(sim.particles());
    statistics_seconds_ += seconds_since(start);
  }

  // A series sample: the gauges and the volume balance; at most once a step.
  void sample(swe::Simulation& sim) {
    if (sampled_ && sampled_step_ == sim.steps()) return;
    const auto start = Clock::now();
    sim.refresh();
    std::vector<io::GaugeSample> at_gauges;
    const std::size_t labels = sim.particles().label_count();
    for (std::size_t k = 0; k < gauges_.size(); ++k) {
      // The level of the water in the cell around the gauge less the bed at its point
      // (maps::gauge_reader, CellAverages::level).
      const auto around = gauge_cells_[k].fields(sim.particles(), sim.kernel());
      const double surface = gauge_cells_[k].level(0, around.depth.front());
      const double depth = surface > gauge_bed_m_[k] ? surface - gauge_bed_m_[k] : 0.0;
      const bool wet = depth > file_.wet_depth_m();
      at_gauges.push_back({depth, wet ? around.u.front() : kNaN, wet ? around.v.front() : kNaN,
                           wet ? surface : kNaN});
      // The shares of the water in the gauge's cell (its volume is its depth there).
      const double cell_depth = around.depth.front();
      for (std::size_t label = 0; label < labels; ++label) {
        at_gauges.back().source_share.push_back(
            wet && cell_depth > 0.0 ? around.label_depth[label] / cell_depth : kNaN);
      }
    }
    const auto& ledger = sim.ledger();
    std::vector<double> label_volume(labels), label_error(labels);
    for (std::size_t k = 0; k < labels; ++k) {
      label_volume[k] = sim.particles().label_volume(k);
      label_error[k] = sim.relative_label_volume_change(k);
    }
    const io::BalanceSample balance{.in_domain_m3 = sim.fluid_volume(),
                                    .inflow_m3 = ledger.added_m3,
                                    .rain_m3 = ledger.rain_m3,
                                    .outflow_m3 = ledger.removed_m3,
                                    .relative_error = sim.relative_volume_change(),
                                    .source_in_domain_m3 = label_volume,
                                    .source_inflow_m3 = ledger.label_added_m3,
                                    .source_outflow_m3 = ledger.label_removed_m3,
                                    .source_relative_error = label_error};
    file_.sample_series(sim.time(), at_gauges, balance);
    sampled_ = true;
    sampled_step_ = sim.steps();
    seconds_ += seconds_since(start);
  }

  void finish() { file_.finish(); }
  void close_stopped(const std::string& status, const std::string& message) {
    file_.close_stopped(status, message);
  }
  void flush() { file_.flush(); }
  void save_state(swe::StateWriter& out) const {
    file_.save_state(out);
    out.number(next_statistics_s_);
  }
  void restore_statistics(swe::StateReader& in) {
    file_.restore_statistics(in);
    next_statistics_s_ = in.number();
  }
  // The state of a restored simulation was written by the run that stopped there.
  void restored(const swe::Simulation& sim) {
    mapped_ = true;
    mapped_step_ = sim.steps();
    mapped_time_s_ = sim.time();
    counted_ = true;
    counted_step_ = sim.steps();
  }
  // Time spent writing (maps, series) and gridding the state for the statistics.
  double seconds() const { return seconds_ + statistics_seconds_; }
  double statistics_seconds() const { return statistics_seconds_; }
  std::size_t statistics_samples() const { return statistics_samples_; }
  const std::filesystem::path& path() const { return file_.path(); }
  const std::filesystem::path& partial_path() const { return file_.partial_path(); }

 private:
  // Until the next statistics sample: kMapCourant times the shortest length the maps resolve
  // (CellAverages::resolved_length_m: a cell, or the finest particle spacing where cells are
  // finer), at the fastest wave speed |u| + sqrt(g h) of any particle; 0 (the next step)
  // without water. Where cells are finer than the particles, a wave crossing half a cell
  // changes what the cells read by less than the envelopes resolve anyway: each particle's
  // water is spread over its kernel. Measured on Thacker's bowl (2 cm cells, 4 cm particles):
  // 758 samples instead of 1,448, and the maximum-depth map within 0.58 mm of the one sampled
  // at every half cell (0.6 % of the deepest water; 5 um on average).
  double statistics_interval(const particles::SweParticles& p) const {
    const double fastest = fastest_wave_m_s(p, gravity_);
    if (!(fastest > 0.0)) return 0.0;
    return kMapCourant * cells_.resolved_length_m() / fastest;
  }

  // The gridded fields of the current state, computed once per state (maps and sample share
  // them at an output time).
  const maps::CellFields& fields(swe::Simulation& sim) {
    sim.refresh();
    if (fields_step_ != sim.steps() || !has_fields_) {
      fields_ = cells_.fields(sim.particles(), sim.kernel());
      fields_step_ = sim.steps();
      has_fields_ = true;
    }
    return fields_;
  }

  swe::RegularGrid grid_;
  double gravity_;
  maps::CellAverages cells_;  // what a map cell reads of the particles
  std::vector<scenario::Gauge> gauges_;
  std::vector<double> gauge_bed_m_;              // the bed elevation at each gauge
  std::vector<maps::CellAverages> gauge_cells_;  // the cell each gauge reads the water in
  bool write_particles_;
  MapOutput file_;
  maps::CellFields fields_;
  std::size_t fields_step_ = 0, sampled_step_ = 0, mapped_step_ = 0, counted_step_ = 0;
  bool has_fields_ = false, sampled_ = false, mapped_ = false, counted_ = false;
  double mapped_time_s_ = 0.0;
  double seconds_ = 0.0, statistics_seconds_ = 0.0;
  double next_statistics_s_ = 0.0;      // the statistics' next sample is due at this time
  std::size_t statistics_samples_ = 0;  // this process's, for the log
};

// A raster bed with cells under 3 particle spacings can be rough inside one kernel support,
// where a point-sampled bed cannot balance the smoothed depth: still water over such a bed was
// measured to start moving and, under the seed scheme at 1 spacing, to break down
// (docs/robustness.md, "Hard cases"). The balanced bed term (numerics.bed_term) sees the bed
// through the same kernel as the depth and keeps such water at rest to round-off: no warning.
void warn_if_bed_finer_than_particles(const scenario::Scenario& scene,
                                      const scenario::Terrain& terrain) {
  if (!terrain.bed_raster) return;
  if (scene.numerics.scheme == swe::SchemeKind::conservative &&
      scene.numerics.bed_term == swe::BedTerm::balanced) {
    return;
  }
  double spacing = 0.0;
  for (const auto& w : scene.water) spacing = std::max(spacing, w.spacing_m);
  for (const auto& in : scene.inflows) spacing = std::max(spacing, in.spacing_m);
  // The natural cells: a refined warp is smooth within them, rough only from one to the next.
  const auto& g = terrain.bed_cells;
  const double cell = std::min(g.cell_width, g.cell_height);
  constexpr double kSmoothCells = 3.0;  // in particle spacings; see docs/robustness.md
  if (spacing <= 0.0 || cell >= kSmoothCells * spacing) return;
  spdlog::warn(
      "the bed raster's cells ({:.3g} m) are narrower than 3 particle spacings (3 x {:.3g} m): "
      "a bed rough from cell to cell can set still water moving; where water should rest, "
      "choose numerics.bed_term \"balanced\" or resample the bed to cells of {:.3g} m or more",
      cell, spacing, kSmoothCells * spacing);
}

// Restores the simulation and the run's own state (the output position, the next series
// sample, the flood statistics) from a checkpoint, within the run's output set up from it.
class RunState {
 public:
  explicit RunState(const Restart& restart)
      : in_(restart.checkpoint.run, "the checkpoint '" + restart.file.string() + "'") {
    in_.expect(kRunStateLabel);
    next_sample_s_ = in_.number();
    position_ = MapOutput::read_position(in_);
  }
  double next_sample_s() const { return next_sample_s_; }
  const io::WriterPosition& position() const { return position_; }
  // The rest of the record: the flood statistics, and the pathlines when the scene has them.
  void restore_statistics(SweOutput& output, PathlineOutput* pathlines) {
    output.restore_statistics(in_);
    if (pathlines) pathlines->restore_state(in_);
    in_.expect_end();
  }

 private:
  swe::StateReader in_;
  double next_sample_s_ = 0.0;
  io::WriterPosition position_;
};

std::vector<std::byte> run_state(const SweOutput& output, const PathlineOutput* pathlines,
                                 double next_sample_s) {
  swe::StateWriter out;
  out.text(kRunStateLabel);
  out.number(next_sample_s);
  output.save_state(out);
  if (pathlines) pathlines->save_state(out);
  return {out.bytes().begin(), out.bytes().end()};
}

void log_starting_volumes(const scenario::StartingVolumes& v) {
  if (!v.balance) {
    if (v.from_terrain)
      spdlog::info("water from terrain: geometric volume {:.6g} m3", v.geometric_m3);
    return;
  }
  const auto& b = *v.balance;
  const double ratio = b.volume_before_m3 > 0.0 ? b.volume_after_m3 / b.volume_before_m3 : kNaN;
  spdlog::info(
      "water from terrain: geometric volume {:.6g} m3, balanced particle volume {:.6g} m3 "
      "(ratio {:.6f})",
      b.volume_before_m3, b.volume_after_m3, ratio);
  if (b.max_depth_error_m > v.balance_tolerance_m) {
    spdlog::warn(
        "volume balancing stopped after {} iterations with a depth error of {:.3g} m (tolerance "
        "{:.3g} m): the water does not start quite at rest",
        b.iterations, b.max_depth_error_m, v.balance_tolerance_m);
  } else {
    spdlog::info("volume balancing: {} iterations, depth error {:.3g} m", b.iterations,
                 b.max_depth_error_m);
  }
  if (b.removed_particles > 0) {
    spdlog::warn(
        "volume balancing removed {} shore particles that no positive volume could balance",
        b.removed_particles);
  }
}

// `ending`: "done", or how the run stopped early.
void log_summary(const swe::Simulation& sim, const std::string& ending,
                 std::size_t initial_particles, std::size_t initial_particle_steps, double wall_s,
                 double output_s, const std::filesystem::path& path) {
  const auto& t = sim.phase_times();
  const double steps_per_s =
      wall_s > 0.0 ? static_cast<double>(sim.particle_steps() - initial_particle_steps) / wall_s
                   : 0.0;
  spdlog::info("{}: {} steps to t = {:.6g} s, particles {} -> {}", ending, sim.steps(), sim.time(),
               initial_particles, sim.particles().fluid_count());
  spdlog::info("wall time {:.3f} s, {:.4g} particle-steps/s ({} threads)", wall_s, steps_per_s,
               omp_get_max_threads());
  const auto& ledger = sim.ledger();
  spdlog::info(
      "volume: initial {:.12g} m3, in {:.6g} m3, rain {:.6g} m3, out {:.6g} m3, now {:.12g} m3, "
      "relative change {:.3e}",
      ledger.initial_m3, ledger.added_m3, ledger.rain_m3, ledger.removed_m3, sim.fluid_volume(),
      sim.relative_volume_change());
  spdlog::info(
      "time per phase: sort {:.3f} s, neighbours {:.3f} s, depth {:.3f} s, gradient {:.3f} s, "
      "shift {:.3f} s, integrate {:.3f} s, walls {:.3f} s, snapshots {:.3f} s, output {:.3f} s",
      t.sort, t.neighbors, t.depth, t.gradient, t.shift, t.integrate, t.walls, t.snapshots,
      output_s);
  spdlog::info(
      "neighbour rows: {} searches of every row, {} repairs of the rows around changed "
      "particles",
      sim.search_counts().searches, sim.search_counts().repairs);
  if (const auto& n = sim.neighbor_counts(); !n.empty()) {
    spdlog::info("neighbours per particle over the run: min {}, median {}, max {}", n.min(),
                 n.median(), n.max());
  }
  for (const auto& e : sim.effect_times()) {
    spdlog::info("effect '{}': {:.3f} s{}", e.name, e.seconds,
                 e.report.empty() ? "" : " (" + e.report + ")");
  }
  if (sim.wall_reflections() > 0) {
    spdlog::info("{} particle moves crossed a wall and were reflected back",
                 sim.wall_reflections());
  }
  spdlog::info("wrote {}", path.string());
}

}  // namespace

double swe_front(const particles::SweParticles& p, double wet_depth_m) {
  double front = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < p.fluid_count(); ++i) {
    if (p.depth[i] > wet_depth_m) front = std::max(front, p.x[i]);
  }
  return std::isfinite(front) ? front : kNaN;
}

RunReport run_swe(const scenario::Scenario& scene, const RunContext& context,
                  const FrontObserver& front) {
  const auto start = Clock::now();
  // From the start: a signal while the scene is built stops the run before its first step.
  StopSignals signals;
  const auto [scenario_hash, restart] = plan_checkpoints(context);

  auto built = scenario::build(scene);
  auto& sim = built.simulation;
  std::optional<RunState> resumed;
  if (restart) {
    try {
      swe::StateReader in(restart->checkpoint.simulation,
                          "the checkpoint '" + restart->file.string() + "'");
      sim.restore_state(in);
      in.expect_end();
      resumed.emplace(*restart);
    } catch (const swe::StateError& e) {
      throw io::CheckpointError(e.what());
    }
  }
  const std::size_t initial_particles = sim.particles().fluid_count();
  const std::size_t initial_particle_steps = sim.particle_steps();
  spdlog::info("scene '{}': {} particles, end time {} s, {} walls, {} inflows, output {}",
               scene.name, initial_particles, scene.end_time_s, scene.walls.size(),
               scene.inflows.size(), scene.output.path.string());
  for (const auto& read : built.terrain.buildings) {
    spdlog::info("{}: {} building footprints from layer '{}'", read.key_path, read.footprints,
                 read.layer);
  }
  if (restart) {
    spdlog::info("going on from checkpoint {} at t = {:.9g} s (step {})", restart->file.string(),
                 sim.time(), sim.steps());
  } else {
    log_starting_volumes(built.volumes);
  }
  warn_if_bed_finer_than_particles(scene, built.terrain);
  if (built.terrain.bed_refinement > 1) {
    const auto& cells = built.terrain.bed_cells;
    const auto& fine = built.terrain.bed_raster->geometry();
    spdlog::info("bed: warped cells of {:.4g} m sampled on {} x {} cells of {:.4g} m",
                 cells.cell_width, fine.columns, fine.rows, fine.cell_width);
  }

  const auto grid = scenario::output_grid(scene, built.terrain);
  std::optional<io::WriterPosition> resume_at;
  if (resumed) resume_at = resumed->position();
  const std::filesystem::path checkpoint_file = checkpoint_path(scene.output.path);
  if (!restart && context.checkpoints) {
    std::filesystem::path partial = scene.output.path;
    partial += ".partial";
    std::error_code ec;
    if (std::filesystem::exists(partial, ec)) {
      spdlog::warn(
          "replacing {}, left by an earlier run that did not finish (--restart {} would "
          "have gone on with it)",
          partial.string(), checkpoint_file.string());
    }
  }
  SweOutput output(scene, built.terrain, grid, context, resume_at);
  std::optional<PathlineOutput> pathlines;
  if (scene.output.pathlines) pathlines.emplace(scene, built.terrain);
  PathlineOutput* const followed = pathlines ? &*pathlines : nullptr;
  const double interval = scene.output.series_interval_s;
  double next_sample = next_sample_time(0.0, interval);
  if (resumed) {
    try {
      resumed->restore_statistics(output, followed);
    } catch (const swe::StateError& e) {
      throw io::CheckpointError(e.what());
    }
    next_sample = resumed->next_sample_s();
    output.restored(sim);
  } else {
    output.write_maps(sim);
    output.update_statistics(sim);
    output.sample(sim);
    if (pathlines) pathlines->observe(sim);
  }
  // The depths the front is read from are those the next step uses (refresh() is cached).
  const auto observe = [&] {
    if (!front) return;
    sim.refresh();
    front(sim.time(), swe_front(sim.particles(), scene.output.wet_depth_m));
  };
  observe();
  Progress progress(scene.end_time_s, context.progress);
  progress.resume_from(sim.time(), sim.steps());
  const auto after_step = [&] {
    progress.update(sim.time(), sim.steps(), sim.particles().fluid_count());
    observe();
    output.update_statistics(sim);
    if (pathlines) pathlines->observe(sim);
    if (sim.time() < next_sample * (1.0 - 1e-12)) return;
    output.sample(sim);
    next_sample = next_sample_time(sim.time(), interval);
  };

  // The file on disk first holds every record the checkpoint counts, so that a run killed
  // outright after the checkpoint can still go on from it.
  const auto write_checkpoint = [&] {
    const auto checkpoint_start = Clock::now();
    output.flush();
    swe::StateWriter state;
    sim.save_state(state);
    write_run_checkpoint(checkpoint_file, scenario_hash, sim.time(), sim.steps(), state.bytes(),
                         run_state(output, followed, next_sample), checkpoint_start);
  };
  // A run that stops early: the state it stopped at as a last map record (the state a
  // breakdown went back to is the last good one), a checkpoint, then the file closed as
  // <output>.partial with the status. Returns what was written, for the closing message.
  const auto close_early = [&](const std::string& status, const std::string& message,
                               bool state_kept) {
    if (state_kept) output.write_maps(sim);
    if (state_kept && context.checkpoints) write_checkpoint();
    output.close_stopped(status, message);
    std::optional<std::filesystem::path> stopped_pathlines;
    if (pathlines) stopped_pathlines = pathlines->close_stopped(state_kept ? &sim : nullptr);
    progress.finish();
    log_summary(sim,
                status == "breakdown" ? "broke down"
                : status == "failed"  ? "failed"
                                      : "stopped",
                initial_particles, initial_particle_steps, seconds_since(start), output.seconds(),
                output.partial_path());
    const std::string and_pathlines =
        stopped_pathlines ? " (pathlines " + stopped_pathlines->string() + ")" : "";
    if (!state_kept) return output.partial_path().string() + and_pathlines;
    std::string written = fmt::format("the state at t = {:.9g} s to {}{}", sim.time(),
                                      output.partial_path().string(), and_pathlines);
    if (context.checkpoints) written += " and the checkpoint " + checkpoint_file.string();
    return written;
  };

  int stop_signal = 0;
  std::size_t outputs = 0;
  try {
    for (const double target : scene.output.times_s) {
      if (sim.reached(target)) continue;  // written before the run was restarted
      while (!sim.reached(target) && (stop_signal = signals.received()) == 0) {
        sim.step_towards(target);
        after_step();
      }
      // A stop that lands on an output time still writes it as the run straight through
      // would, series sample included, so that the restarted run's file is the same.
      if (sim.reached(target)) {
        output.write_maps(sim);
        output.update_statistics(sim, true);
        output.sample(sim);
        spdlog::debug("wrote output at t = {} s", sim.time());
        ++outputs;
        if (context.checkpoints && context.checkpoint_every > 0 && stop_signal == 0 &&
            outputs % static_cast<std::size_t>(context.checkpoint_every) == 0 &&
            target < scene.output.times_s.back()) {
          write_checkpoint();
        }
      }
      if (stop_signal != 0) break;
    }
    // A signal during the last step stops nothing: the run is complete.
    if (stop_signal != 0 && !sim.reached(scene.output.times_s.back())) {
      const std::string what = fmt::format("stopped by {} at t = {:.9g} s (step {})",
                                           signal_name(stop_signal), sim.time(), sim.steps());
      spdlog::warn("{}: writing the state reached and closing the output", what);
      const std::string written = close_early("interrupted", what, true);
      std::string message = what + "; wrote " + written;
      if (context.checkpoints) {
        message += "; to go on, run the same command with --restart " + checkpoint_file.string();
      }
      throw RunStopped(stop_signal, message);
    }
  } catch (const swe::SimulationError& e) {
    // The breakdown is what the run ends with, whatever happens while its state is written.
    try {
      const std::string written = close_early("breakdown", e.what(), e.at_last_good_state());
      spdlog::error("the simulation broke down; wrote {}", written);
    } catch (const std::exception& also) {
      spdlog::error("the simulation broke down, and its last good state could not be written: {}",
                    also.what());
    }
    throw;
  } catch (const RunStopped&) {
    throw;  // closed above
  } catch (const std::exception& e) {
    // Anything else (memory running out while particles split, a disk filling up): the maps
    // written so far stay readable, closed with the reason. The state of the step that
    // failed is not trusted, so nothing of it is written.
    try {
      const std::string written = close_early("failed", e.what(), false);
      spdlog::error("the run failed; kept the output written so far in {}", written);
    } catch (const std::exception& also) {
      spdlog::error("the run failed, and its output could not be closed: {}", also.what());
    }
    throw;
  }
  progress.finish();
  output.finish();
  if (pathlines) pathlines->finish(sim);
  spdlog::info(
      "flood statistics sampled {} times (a wave crossing half a map cell or particle spacing, "
      "and every output time): {:.3f} s of the output time (gridding and accumulating)",
      output.statistics_samples(), output.statistics_seconds());
  const double wall_s = seconds_since(start);
  log_summary(sim, "done", initial_particles, initial_particle_steps, wall_s, output.seconds(),
              output.path());
  RunReport report;
  report.steps = sim.steps();
  report.fluid_particles = initial_particles;
  report.final_fluid_particles = sim.particles().fluid_count();
  report.particle_steps = sim.particle_steps();
  report.relative_volume_change = sim.relative_volume_change();
  report.wall_s = wall_s;
  report.output = output.path();
  report.phases = sim.phase_times();
  report.effects = sim.effect_times();
  report.output_s = output.seconds();
  return report;
}

}  // namespace swemps::cli
