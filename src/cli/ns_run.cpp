// A Navier-Stokes run: scene -> ns::Simulation in its tank -> netCDF maps of the column depth
// on the scene's grid, and a CSV series of the front, the Poisson solves and floor pressures;
// and, as a shallow-water run does, how it fails well: a stop signal leaves a readable file
// holding the state reached and a checkpoint to go on from, bit for bit.

#include <omp.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "swemps/cli/progress.hpp"
#include "swemps/cli/restart.hpp"
#include "swemps/cli/runs.hpp"
#include "swemps/cli/stop_signals.hpp"
#include "swemps/cli/timing.hpp"
#include "swemps/io/checkpoint.hpp"
#include "swemps/io/flood_products.hpp"
#include "swemps/ns/measures.hpp"
#include "swemps/ns/simulation.hpp"
#include "swemps/scenario/build.hpp"

namespace swemps::cli {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

constexpr const char* kRunStateLabel = "swe-mps Navier-Stokes run";

// The numerical choices of a run in one line, so a log says which scheme made its numbers
// (the scene's "scheme" and every key that overrode it: docs/scenario.md).
std::string describe_numerics(const ns::Settings& s) {
  const auto kernel = [](const ns::KernelChoice& k) {
    return fmt::format("{} at {} l0", kernels::kernel_type_name(k.spec.type), k.support_spacings);
  };
  const bool same_kernels =
      s.velocity_kernel.spec.type == s.pressure_kernel.spec.type &&
      s.velocity_kernel.support_spacings == s.pressure_kernel.support_spacings;
  return fmt::format(
      "kernel {}{}, source {}, gradient {}{}{}, free surface below {} n0{}, wall pressures {}, "
      "Courant {}, solver tolerance {}, collisions {}, {} operators",
      kernel(s.pressure_kernel),
      same_kernels ? "" : fmt::format(" ({} for viscosity)", kernel(s.velocity_kernel)),
      s.source == ns::SourceTerm::mixed ? fmt::format("mixed (gamma {})", s.source_gamma)
                                        : std::string("number-density"),
      ns::pressure_gradient_name(s.gradient),
      s.gradient_weights == ns::GradientWeights::kernel_slope ? " on the kernel's slope" : "",
      s.gradient == ns::PressureGradient::corrected_repulsive
          ? fmt::format(" (repulsion under {} l0)", s.repulsion_distance_spacings)
          : "",
      s.free_surface_beta,
      s.free_surface_asymmetry > 0.0
          ? fmt::format(" and one-sided beyond {} l0", s.free_surface_asymmetry)
          : "",
      s.boundary == ns::BoundaryPressure::extrapolated ? "extrapolated" : "solved (Poisson)",
      s.courant, s.solver.relative_tolerance, s.collision ? "on" : "off",
      s.operators == ns::Operators::least_squares ? "least-squares" : "MPS");
}

// The plan cell (along one axis) that holds coordinate x, or -1 outside the grid; cells are
// centred on x0 + i dx, as ns::column_depth bins them.
long cell_of(double x, double x0, double dx, std::size_t n) {
  const double c = std::floor((x - x0) / dx + 0.5);
  return c >= 0.0 && c < static_cast<double>(n) ? static_cast<long>(c) : -1;
}

// The column depth and depth-averaged velocity over each plan cell. The particles have equal
// volumes, so the mean velocity of those standing in a cell is the column's volume-weighted
// (depth-averaged) velocity; NaN where none stands. A 2D section has no cross-channel flow:
// v is 0 there, and every row k repeats row 0.
struct ColumnFields {
  std::vector<double> depth, u, v;
};

template <int Dim>
ColumnFields column_fields(const ns::Particles<Dim>& p, double spacing_m,
                           const ns::PlanGrid& grid) {
  const std::size_t cells = grid.nx * grid.ny;
  ColumnFields f{ns::column_depth<Dim>(p, spacing_m, grid), std::vector<double>(cells, 0.0),
                 std::vector<double>(cells, 0.0)};
  std::vector<double> count(cells, 0.0);
  for (std::size_t n = 0; n < p.fluid; ++n) {
    const long i = cell_of(p.position[0][n], grid.x0, grid.dx, grid.nx);
    if (i < 0) continue;
    long k = 0;
    if constexpr (Dim == 3) {
      k = cell_of(p.position[1][n], grid.y0, grid.dy, grid.ny);
      if (k < 0) continue;
    }
    const std::size_t c = static_cast<std::size_t>(k) * grid.nx + static_cast<std::size_t>(i);
    f.u[c] += p.velocity[0][n];
    if constexpr (Dim == 3) f.v[c] += p.velocity[1][n];
    count[c] += 1.0;
  }
  for (std::size_t c = 0; c < (Dim == 3 ? cells : grid.nx); ++c) {
    f.u[c] = count[c] > 0.0 ? f.u[c] / count[c] : kNaN;
    f.v[c] = count[c] > 0.0 ? f.v[c] / count[c] : kNaN;
  }
  if constexpr (Dim == 2) {
    for (std::size_t k = 1; k < grid.ny; ++k) {
      std::copy_n(f.u.begin(), grid.nx, f.u.begin() + static_cast<long>(k * grid.nx));
      std::copy_n(f.v.begin(), grid.nx, f.v.begin() + static_cast<long>(k * grid.nx));
    }
  }
  return f;
}

// Where a Navier-Stokes run stops: every multiple of the series interval (a sample) and
// every output time (maps and a sample), in order. Output times are landed on exactly;
// samples are taken at the end of the first step that reaches them, so that sampling never
// changes the run.
struct Stop {
  double time_s;
  bool maps;
};

std::vector<Stop> stops_of(const scenario::Output& output, double end_time_s) {
  // Within this of each other two stops are one, so rounding never makes a sliver of a step.
  const double slack = 1e-9 * end_time_s;
  std::vector<Stop> all;
  for (std::size_t k = 1;; ++k) {
    const double t = static_cast<double>(k) * output.series_interval_s;
    if (t > end_time_s - slack) break;
    all.push_back({t, false});
  }
  for (const double t : output.times_s) all.push_back({t, true});
  std::stable_sort(all.begin(), all.end(),
                   [](const Stop& a, const Stop& b) { return a.time_s < b.time_s; });
  std::vector<Stop> merged;
  for (const Stop& s : all) {
    if (!merged.empty() && s.time_s - merged.back().time_s <= slack) {
      // An output time is kept as given.
      if (s.maps) merged.back() = s;
      continue;
    }
    merged.push_back(s);
  }
  return merged;
}

// What happened between two output times, for the debug line at each.
struct Interval {
  std::size_t steps = 0;
  long long iterations = 0;
  int max_iterations = 0;
  double min_dt = std::numeric_limits<double>::infinity(), max_dt = 0.0;
};

template <int Dim>
RunReport run_in(const scenario::Scenario& scene, const RunContext& context,
                 const FrontObserver& observe_front) {
  const auto start = Clock::now();
  // From the start: a signal while the scene is built stops the run before its first step.
  StopSignals signals;
  const auto [scenario_hash, restart] = plan_checkpoints(context);
  // The series rows travel in the checkpoint only when there is one to write or read.
  const bool checkpoints = context.checkpoints || restart.has_value();
  const auto terrain = scenario::read_terrain(scene);
  const auto tank = scenario::ns_tank<Dim>(scene);
  auto sim = scenario::make_ns_simulation<Dim>(scene);
  // The run's own part of the checkpoint: where the file stands, the flood statistics and the
  // series rows so far; read as the output is set up.
  std::optional<swe::StateReader> run_state;
  std::optional<io::WriterPosition> resume_at;
  if (restart) {
    const std::string what = "the checkpoint '" + restart->file.string() + "'";
    try {
      swe::StateReader in(restart->checkpoint.simulation, what);
      sim.restore_state(in);
      in.expect_end();
      run_state.emplace(restart->checkpoint.run, what);
      run_state->expect(kRunStateLabel);
      resume_at = MapOutput::read_position(*run_state);
    } catch (const swe::StateError& e) {
      throw io::CheckpointError(e.what());
    }
  }
  const ns::Settings& settings = sim.settings();
  const double l0 = settings.spacing_m;
  const double floor_z = tank.interior.lower[Dim - 1];
  const auto& p0 = sim.particles();
  const std::size_t initial_fluid = p0.fluid;
  // A 2D section stands for a channel as wide as the domain: its area times that width is
  // the water's volume, as its column depth over the grid's cells also gives.
  const double width = Dim == 2 ? scene.domain.y_max - scene.domain.y_min : 1.0;
  const double particle_volume = std::pow(l0, Dim) * width;
  const double initial_volume = static_cast<double>(initial_fluid) * particle_volume;

  spdlog::info(
      "scene '{}': model ns ({}), {} fluid, {} wall and {} dummy particles, spacing {} m, tank "
      "{} m long{} and {} m high, end time {} s, output {}",
      scene.name, Dim == 2 ? "2D x-z section" : "3D", initial_fluid, p0.wall, p0.dummy, l0,
      tank.interior.upper[0] - tank.interior.lower[0],
      Dim == 3 ? fmt::format(", {} m wide", tank.interior.upper[1] - tank.interior.lower[1]) : "",
      tank.interior.upper[Dim - 1] - floor_z, scene.end_time_s, scene.output.path.string());
  spdlog::info("model ns numerics: {}", describe_numerics(sim.settings()));
  if (!scene.walls.empty()) {
    spdlog::info(
        "model ns: the tank's walls are the domain's sides and the floor; the scene's {} walls "
        "are not used",
        scene.walls.size());
  }

  const auto grid = scenario::output_grid(scene, terrain);
  const ns::PlanGrid plan{grid.x0, grid.y0, grid.dx, grid.dy, grid.nx, grid.ny};
  const std::string depth_name =
      Dim == 3 ? "water depth: volume of the fluid particles standing in the cell over its "
                 "area (Navier-Stokes column depth)"
               : "water depth: area of the vertical section's fluid particles standing in the "
                 "cell over its length (Navier-Stokes column depth, 2D section)";
  MapOutput file(scene, terrain, grid, context, false, depth_name,
                 Dim == 3 ? "Navier-Stokes, 3D" : "Navier-Stokes, 2D section", resume_at);

  std::vector<std::string> columns{"time_s",          "time_step_s",        "front_m",
                                   "fluid_particles", "poisson_iterations", "poisson_residual",
                                   "unknowns"};
  // Floor probes: the wall-particle row half a spacing below the floor carries the pressure
  // the water exerts on it.
  std::vector<std::array<double, Dim>> probes;
  for (const auto& g : scene.output.gauges) {
    columns.push_back(io::column_name(g.name) + "_floor_pressure_pa");
    std::array<double, Dim> at{};
    at[0] = g.position_m[0];
    if constexpr (Dim == 3) at[1] = g.position_m[1];
    at[Dim - 1] = floor_z - 0.5 * l0;
    probes.push_back(at);
  }
  CsvTable series(ns_series_path(scene.output.path), columns);
  // Every row so far, for the checkpoint: a restarted run writes the table anew from them,
  // which also drops rows a run killed after its checkpoint wrote beyond it.
  std::vector<double> series_rows;
  if (run_state) {
    try {
      file.restore_statistics(*run_state);
      const std::size_t saved_columns = run_state->count();
      series_rows = run_state->numbers();
      run_state->expect_end();
      if (saved_columns != columns.size() || series_rows.size() % columns.size() != 0) {
        throw swe::StateError(run_state->what() + " holds a series of " +
                              std::to_string(saved_columns) + " columns, this scene's has " +
                              std::to_string(columns.size()));
      }
    } catch (const swe::StateError& e) {
      throw io::CheckpointError(e.what());
    }
    for (std::size_t first = 0; first < series_rows.size(); first += columns.size()) {
      series.row(std::span<const double>(series_rows).subspan(first, columns.size()));
    }
  }

  double output_s = 0.0;
  const double wet = scene.output.wet_depth_m;
  // A sample and the output time right after it can fall on the same step (the run lands on
  // the output time while heading for the sample): the series gets that state once.
  std::size_t sampled_at_step = 0, mapped_at_step = 0;
  bool sampled = false, mapped = false;
  double last_front = 0.0;
  const auto sample = [&](bool maps) {
    const auto t0 = Clock::now();
    const auto& p = sim.particles();
    const ColumnFields f = column_fields<Dim>(p, l0, plan);
    const GriddedState state{f.depth, f.u, f.v};
    if (maps) {
      file.write_maps(sim.time(), state);
      mapped = true;
      mapped_at_step = sim.steps();
    }
    if (sampled && sampled_at_step == sim.steps()) {
      output_s += seconds_since(t0);
      return last_front;
    }
    sampled = true;
    sampled_at_step = sim.steps();
    std::vector<io::GaugeSample> at_gauges;
    for (const auto& g : scene.output.gauges) {
      const long i = cell_of(g.position_m[0], grid.x0, grid.dx, grid.nx);
      const long k = cell_of(g.position_m[1], grid.y0, grid.dy, grid.ny);
      if (i < 0 || k < 0) {
        at_gauges.push_back({kNaN, kNaN, kNaN});
        continue;
      }
      const std::size_t c = static_cast<std::size_t>(k) * grid.nx + static_cast<std::size_t>(i);
      const bool is_wet = f.depth[c] > wet;
      at_gauges.push_back(
          {f.depth[c], is_wet ? f.u[c] : kNaN, is_wet ? f.v[c] : kNaN,
           is_wet ? f.depth[c] + file.bed_at(g.position_m[0], g.position_m[1]) : kNaN});
    }
    const double volume = static_cast<double>(p.fluid) * particle_volume;
    const double lost = static_cast<double>(sim.totals().lost_particles) * particle_volume;
    file.update_statistics(sim.time(), state);
    file.sample_series(
        sim.time(), at_gauges,
        io::BalanceSample{.in_domain_m3 = volume,
                          .outflow_m3 = lost,
                          .relative_error = (volume - (initial_volume - lost)) / initial_volume});

    const double front = ns::front_position<Dim>(p, l0);
    const bool stepped = sim.steps() > 0;
    const auto& last = sim.last_step();
    // The stable step rather than the last one: the steps that landed on an output time may
    // have been shortened to do so.
    std::vector<double> row{sim.time(),
                            sim.stable_time_step(),
                            front,
                            static_cast<double>(p.fluid),
                            stepped ? static_cast<double>(last.poisson.iterations) : kNaN,
                            stepped ? last.poisson.relative_residual : kNaN,
                            stepped ? static_cast<double>(last.unknowns) : kNaN};
    for (const auto& at : probes) row.push_back(ns::pressure_at<Dim>(p, sim.pressure_kernel(), at));
    series.row(row);
    if (checkpoints) series_rows.insert(series_rows.end(), row.begin(), row.end());
    if (observe_front) observe_front(sim.time(), front);
    output_s += seconds_since(t0);
    last_front = front;
    return front;
  };

  if (restart) {
    spdlog::info("going on from checkpoint {} at t = {:.9g} s (step {})", restart->file.string(),
                 sim.time(), sim.steps());
    // The stopped run wrote and sampled the state it stopped at.
    sampled = mapped = true;
    sampled_at_step = mapped_at_step = sim.steps();
  } else {
    sample(true);
  }
  const double resumed_at_s = sim.time();
  Progress progress(scene.end_time_s, context.progress);
  progress.resume_from(sim.time(), sim.steps());
  const std::filesystem::path checkpoint_file = checkpoint_path(scene.output.path);
  // The file on disk first holds every record the checkpoint counts, so that a run killed
  // outright after the checkpoint can still go on from it.
  const auto write_checkpoint = [&] {
    const auto checkpoint_start = Clock::now();
    file.flush();
    swe::StateWriter state;
    sim.save_state(state);
    swe::StateWriter run;
    run.text(kRunStateLabel);
    file.save_state(run);
    run.count(columns.size());
    run.numbers(series_rows);
    write_run_checkpoint(checkpoint_file, scenario_hash, sim.time(), sim.steps(), state.bytes(),
                         run.bytes(), checkpoint_start);
  };
  // A run that stops early: with `state_kept`, the state it stopped at as a last map record
  // (not a series sample: the restarted run's series is the straight run's) and a checkpoint;
  // then the file is closed as <output>.partial with the status, and the series table stays
  // <table>.partial. Returns what was written, for the closing message.
  const auto close_early = [&](const std::string& status, const std::string& message,
                               bool state_kept) {
    if (state_kept && !(mapped && mapped_at_step == sim.steps())) {
      const ColumnFields f = column_fields<Dim>(sim.particles(), l0, plan);
      file.write_maps(sim.time(), GriddedState{f.depth, f.u, f.v});
    }
    if (state_kept && context.checkpoints) write_checkpoint();
    file.close_stopped(status, message);
    progress.finish();
    if (!state_kept) return file.partial_path().string();
    std::string written =
        fmt::format("the state at t = {:.9g} s to {}", sim.time(), file.partial_path().string());
    if (context.checkpoints) written += " and the checkpoint " + checkpoint_file.string();
    return written;
  };
  Interval interval;
  double particle_steps = 0.0;
  const auto stops = stops_of(scene.output, scene.end_time_s);
  // For each stop, the next output time at or after it: full steps towards a sample must not
  // carry the run past it.
  std::vector<double> next_map(stops.size(), scene.end_time_s);
  for (std::size_t k = stops.size(); k-- > 0;) {
    next_map[k] = stops[k].maps ? stops[k].time_s
                                : (k + 1 < stops.size() ? next_map[k + 1] : scene.end_time_s);
  }
  int stop_signal = 0;
  std::size_t outputs = 0;
  try {
    for (std::size_t k = 0; k < stops.size() && stop_signal == 0; ++k) {
      const Stop& stop = stops[k];
      // Taken before the run was restarted: a stop signal is only looked at before a step, so
      // every stop the stopped run reached was sampled.
      if (restart && stop.time_s <= resumed_at_s) continue;
      while (sim.time() < stop.time_s && (stop_signal = signals.received()) == 0) {
        // One step per call, so that progress and the per-step log follow every step. Series
        // samples are taken at the end of the first full step that reaches them; only output
        // times are landed on, in equal steps as advance_to takes them (a shortened step would
        // spike the number-density source, which scales as 1/dt^2).
        const double dt = sim.stable_time_step();
        const double remaining = next_map[k] - sim.time();
        if (!stop.maps && remaining > dt) {
          sim.advance(dt);
        } else if (remaining <= dt) {
          sim.advance_to(next_map[k]);
        } else {
          sim.advance(remaining / std::ceil(remaining / dt * (1.0 - 1e-12)));
        }
        const auto& last = sim.last_step();
        particle_steps += static_cast<double>(sim.particles().fluid);
        ++interval.steps;
        interval.iterations += last.poisson.iterations;
        interval.max_iterations = std::max(interval.max_iterations, last.poisson.iterations);
        interval.min_dt = std::min(interval.min_dt, last.time_step_s);
        interval.max_dt = std::max(interval.max_dt, last.time_step_s);
        spdlog::debug(
            "step {}: t = {:.6g} s, dt = {:.3g} s, Poisson {} iterations, residual {:.2e}{}, {} "
            "unknowns, {} surface particles, {} collisions",
            sim.steps(), sim.time(), last.time_step_s, last.poisson.iterations,
            last.poisson.relative_residual, last.poisson.converged ? "" : " (not converged)",
            last.unknowns, last.surface_particles, last.collisions);
        progress.update(sim.time(), sim.steps(), sim.particles().fluid);
      }
      if (stop_signal != 0) break;
      const double front = sample(stop.maps);
      if (!stop.maps) continue;
      ++outputs;
      if (context.checkpoints && context.checkpoint_every > 0 &&
          outputs % static_cast<std::size_t>(context.checkpoint_every) == 0 &&
          stop.time_s < scene.output.times_s.back()) {
        write_checkpoint();
      }
      const double steps = static_cast<double>(std::max<std::size_t>(interval.steps, 1));
      spdlog::debug(
          "wrote output at t = {:.6g} s: {} steps since the last (dt {:.3g} to {:.3g} s), Poisson "
          "iterations {:.1f} per step (at most {}), last residual {:.2e}, front at {:.4f} m",
          sim.time(), interval.steps, interval.min_dt, interval.max_dt,
          static_cast<double>(interval.iterations) / steps, interval.max_iterations,
          sim.last_step().poisson.relative_residual, front);
      interval = Interval{};
    }
    if (stop_signal != 0) {
      const std::string what = fmt::format("stopped by {} at t = {:.9g} s (step {})",
                                           signal_name(stop_signal), sim.time(), sim.steps());
      spdlog::warn("{}: writing the state reached and closing the output", what);
      std::string message = what + "; wrote " + close_early("interrupted", what, true);
      if (context.checkpoints) {
        message += "; to go on, run the same command with --restart " + checkpoint_file.string();
      }
      throw RunStopped(stop_signal, message);
    }
  } catch (const RunStopped&) {
    throw;  // closed above
  } catch (const std::exception& e) {
    // A breakdown (ns::SimulationError) happens inside a step, which leaves the particles
    // half moved: unlike a shallow-water run there is no last good state to write or go on
    // from. The maps written so far stay readable, closed with the reason.
    const bool breakdown = dynamic_cast<const ns::SimulationError*>(&e) != nullptr;
    try {
      const std::string written = close_early(breakdown ? "breakdown" : "failed", e.what(), false);
      spdlog::error("the {}; kept the output written so far in {}",
                    breakdown ? "simulation broke down" : "run failed", written);
    } catch (const std::exception& also) {
      spdlog::error("the run stopped, and its output could not be closed: {}", also.what());
    }
    throw;
  }
  progress.finish();
  file.finish();
  series.finish();

  const double wall_s = seconds_since(start);
  const auto& totals = sim.totals();
  const auto& p = sim.particles();
  spdlog::info(
      "done: {} steps to t = {:.6g} s; particles: {} fluid ({} at the start, {} lost), {} wall, "
      "{} dummy",
      totals.steps, sim.time(), p.fluid, initial_fluid, totals.lost_particles, p.wall, p.dummy);
  spdlog::info("wall time {:.3f} s, {:.4g} particle-steps/s ({} threads)", wall_s,
               wall_s > 0.0 ? particle_steps / wall_s : 0.0, omp_get_max_threads());
  const double per_step = totals.steps > 0 ? static_cast<double>(totals.poisson_iterations) /
                                                 static_cast<double>(totals.steps)
                                           : 0.0;
  spdlog::info(
      "Poisson: {}, {} preconditioner, tolerance {:.3g}, at most {} iterations: "
      "{:.1f} iterations per step on average, {} at most, {} unconverged solves",
      settings.operators == ns::Operators::least_squares ? "BiCGSTAB" : "conjugate gradients",
      ns::preconditioner_name(settings.solver.preconditioner), settings.solver.relative_tolerance,
      settings.solver.max_iterations, per_step, totals.max_poisson_iterations,
      totals.unconverged_solves);
  const auto& t = totals.phases;
  spdlog::info(
      "time per phase: sort {:.3f} s, neighbours {:.3f} s, explicit {:.3f} s, density {:.3f} s, "
      "assembly {:.3f} s, solve {:.3f} s, correction {:.3f} s, output {:.3f} s",
      t.sort, t.neighbors, t.explicit_part, t.density, t.assembly, t.solve, t.correction, output_s);
  spdlog::info("volume: initial {:.12g} m3, lost {:.6g} m3, now {:.12g} m3{}", initial_volume,
               static_cast<double>(totals.lost_particles) * particle_volume,
               static_cast<double>(p.fluid) * particle_volume,
               Dim == 2 ? " (section area times the domain's width)" : "");
  spdlog::info("wrote {} and {}", file.path().string(), series.path().string());

  RunReport report;
  report.steps = totals.steps;
  report.fluid_particles = initial_fluid;
  report.wall_particles = p.wall;
  report.dummy_particles = p.dummy;
  report.wall_s = wall_s;
  report.output = file.path();
  return report;
}

}  // namespace

std::filesystem::path ns_series_path(const std::filesystem::path& output) {
  std::filesystem::path p = output;
  p.replace_extension(".series.csv");
  return p;
}

RunReport run_ns(const scenario::Scenario& scene, const RunContext& context,
                 const FrontObserver& front) {
  return scene.dimension == 2 ? run_in<2>(scene, context, front) : run_in<3>(scene, context, front);
}

}  // namespace swemps::cli
