// `swe-mps check SCENE`: the scene is loaded, its output target tested, its rasters read and
// its simulation built exactly as `run` does before its first step, so that a scene run would
// refuse is refused here with the same message; then, instead of the run, a report on standard
// output: the domain and CRS, the rasters, the particles, the memory, the first time step and a
// wall-time estimate with its band, from the scene and a coarser pilot of it stepped in memory
// (wall_time_estimate.hpp). Nothing is written: no output file is opened.

#include "swemps/cli/check_command.hpp"

#include <ogr_spatialref.h>
#include <omp.h>
#include <spdlog/fmt/fmt.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <string>
#include <variant>
#include <vector>

#include "swemps/boundaries/hydrograph.hpp"
#include "swemps/boundaries/inflow_line.hpp"
#include "swemps/hydrology/rain.hpp"
#include "swemps/cli/output.hpp"
#include "swemps/cli/output_target.hpp"
#include "swemps/cli/report_text.hpp"
#include "swemps/cli/runs.hpp"
#include "swemps/cli/statistics_sampling.hpp"
#include "swemps/cli/timing.hpp"
#include "swemps/cli/wall_time_estimate.hpp"
#include "swemps/io/hydrograph_csv.hpp"
#include "swemps/maps/flood_statistics.hpp"
#include "swemps/maps/pathlines.hpp"
#include "swemps/scenario/build.hpp"
#include "swemps/scenario/coarsen.hpp"
#include "swemps/scenario/memory_check.hpp"

namespace swemps::cli {

namespace {

// The scene itself is stepped for this much wall time (its window, the whole run if that
// reaches the end time); a pilot run stops after the second, and its steps so far are carried
// to the end time.
constexpr double kWindowS = 5.0;
constexpr double kPilotBudgetS = 30.0;
// Without a particle to time (an inflow that let none in within the budget), a rate from
// docs/performance.md is assumed: 5e5 particle-steps/s per thread, below every rate measured
// there with the default scheme.
constexpr double kAssumedRatePerThread = 5e5;

// ---------------------------------------------------------------------------------------------
// Words and numbers

// A map coordinate to the centimetre, as it would be typed into a scene file.
std::string coord(double v) {
  std::string s = fmt::format("{:.2f}", v);
  while (s.back() == '0') s.pop_back();
  if (s.back() == '.') s.pop_back();
  return s == "-0" ? "0" : s;
}

std::string box(double x0, double x1, double y0, double y1) {
  return fmt::format("[{}, {}] x [{}, {}] m", coord(x0), coord(x1), coord(y0), coord(y1));
}

// ---------------------------------------------------------------------------------------------
// Scene, domain and rasters

void scene_section(const scenario::Scenario& scene, const Options& options,
                   const swe::RegularGrid& grid, const std::string& model) {
  heading("Scene");
  row("name", scene.name);
  row("file", std::filesystem::absolute(options.scenario).lexically_normal().string());
  row("model", model);
  const std::size_t maps = scene.output.times_s.size();
  row("end time", fmt::format("{} s, maps at t = 0 and {} later output time{}",
                              num(scene.end_time_s), maps, maps == 1 ? "" : "s"));
  // check_output_target has made and removed a file beside it: the folder takes new files.
  std::error_code ec;
  row("output",
      scene.output.path.string() + (std::filesystem::exists(scene.output.path, ec)
                                        ? " (folder writable; the file there will be replaced)"
                                        : " (folder writable)"));
  row("output grid",
      fmt::format("{} x {} cells of {} x {} m over {}", count(double(grid.nx)),
                  count(double(grid.ny)), num(grid.dx), num(grid.dy),
                  box(grid.x0 - 0.5 * grid.dx, grid.x0 + (grid.nx - 0.5) * grid.dx,
                      grid.y0 - 0.5 * grid.dy, grid.y0 + (grid.ny - 0.5) * grid.dy)));
}

std::string crs_name(const std::string& wkt) {
  if (wkt.empty()) return "none (local metres)";
  OGRSpatialReference crs;
  if (crs.importFromWkt(wkt.c_str()) != OGRERR_NONE) return "(a CRS GDAL cannot name)";
  std::string name = crs.GetName() ? crs.GetName() : "unnamed";
  const char* authority = crs.GetAuthorityName(nullptr);
  const char* code = crs.GetAuthorityCode(nullptr);
  if (authority && code) name += fmt::format(" ({}:{})", authority, code);
  return name;
}

void domain_section(const scenario::Scenario& scene, const scenario::Terrain& terrain) {
  const auto& d = terrain.domain;
  const double wide_m = d.x_max - d.x_min, high_m = d.y_max - d.y_min;
  // Kilometres for terrain, metres for a flume.
  const bool km = std::max(wide_m, high_m) >= 1e3;
  const double unit = km ? 1e3 : 1.0;
  const char* name = km ? "km" : "m";
  heading("Domain and CRS");
  row("domain",
      box(d.x_min, d.x_max, d.y_min, d.y_max) +
          (scene.domain_from_bed ? " (the bed raster's extent)" : " (as the file gives it)"));
  row("size", fmt::format("{} x {} {} ({} {}2)", num(wide_m / unit), num(high_m / unit), name,
                          num(wide_m * high_m / (unit * unit)), name));
  row("CRS", crs_name(terrain.crs_wkt));
}

// The cells of `field` that overlap the domain: their value range and nodata, beside the
// nodata of the raster as read (a warp leaves nodata outside the source's footprint).
void raster_rows(const std::string& what, const std::filesystem::path& file,
                 const terrain::GriddedField& field, const scenario::Rectangle& d) {
  const auto& g = field.geometry();
  double low = std::numeric_limits<double>::infinity(), high = -low;
  std::size_t inside = 0, nodata_inside = 0, nodata = 0;
  for (std::size_t r = 0; r < g.rows; ++r) {
    const double top = g.y_top - static_cast<double>(r) * g.cell_height;
    const bool row_in = top > d.y_min && top - g.cell_height < d.y_max;
    for (std::size_t c = 0; c < g.columns; ++c) {
      const double left = g.x_left + static_cast<double>(c) * g.cell_width;
      const bool in = row_in && left < d.x_max && left + g.cell_width > d.x_min;
      const double v = field.at(c, r);
      nodata += std::isnan(v) ? 1 : 0;
      inside += in ? 1 : 0;
      nodata_inside += in && std::isnan(v) ? 1 : 0;
      if (!in || std::isnan(v)) continue;
      low = std::min(low, v);
      high = std::max(high, v);
    }
  }
  row(what, file.string());
  row("  extent", box(g.x_left, g.x_right(), g.y_bottom(), g.y_top));
  row("  cells", fmt::format("{} x {} of {} x {} m", count(double(g.columns)),
                             count(double(g.rows)), num(g.cell_width), num(g.cell_height)));
  row("  values in the domain",
      inside > nodata_inside
          ? fmt::format("{} to {} ({} cells)", num(low), num(high), count(double(inside)))
          : "none (every cell there is nodata)");
  row("  nodata",
      fmt::format("{} in the domain, {} of {} cells in all", count(double(nodata_inside)),
                  count(double(nodata)), count(double(g.columns * g.rows))));
}

void rasters_section(const scenario::Scenario& scene, const scenario::Terrain& terrain) {
  heading("Rasters (as read, in the scene's CRS)");
  bool any = false;
  if (const auto* bed = std::get_if<scenario::RasterBedSpec>(&scene.bed);
      bed && terrain.bed_raster) {
    raster_rows("bed", bed->raster.path, *terrain.bed_raster, terrain.domain);
    if (terrain.bed_refinement > 1) {
      row("  refinement",
          fmt::format("each warped cell of {} x {} m split {} x {} before "
                      "interpolating",
                      num(terrain.bed_cells.cell_width), num(terrain.bed_cells.cell_height),
                      terrain.bed_refinement, terrain.bed_refinement));
    }
    any = true;
  }
  if (scene.manning_n && terrain.roughness) {
    const auto* land_use = std::get_if<scenario::LandUseSpec>(&*scene.manning_n);
    raster_rows(
        land_use ? "Manning's n of land use" : "Manning's n",
        land_use ? land_use->raster.path : std::get<scenario::RasterSpec>(*scene.manning_n).path,
        *terrain.roughness, terrain.domain);
    any = true;
  }
  for (std::size_t i = 0; i < scene.water.size() && i < terrain.water_depth.size(); ++i) {
    const auto* depth = std::get_if<scenario::DepthRaster>(&scene.water[i].depth);
    if (!depth || !terrain.water_depth[i]) continue;
    raster_rows(fmt::format("water {} depth", i), depth->raster.path, *terrain.water_depth[i],
                terrain.domain);
    any = true;
  }
  for (std::size_t i = 0; i < scene.water.size() && i < terrain.displacement.size(); ++i) {
    const auto& body = scene.water[i];
    if (const auto* rise = std::get_if<scenario::DisplacementRaster>(&body.displacement);
        rise && terrain.displacement[i]) {
      raster_rows(fmt::format("water {} surface displacement", i), rise->raster.path,
                  *terrain.displacement[i], terrain.domain);
      any = true;
    }
    if (body.velocity_rasters && terrain.velocity_u[i] && terrain.velocity_v[i]) {
      raster_rows(fmt::format("water {} velocity u", i), body.velocity_rasters->u.path,
                  *terrain.velocity_u[i], terrain.domain);
      raster_rows(fmt::format("water {} velocity v", i), body.velocity_rasters->v.path,
                  *terrain.velocity_v[i], terrain.domain);
      any = true;
    }
  }
  if (!any) row("none", "the scene reads no raster");
}

// ---------------------------------------------------------------------------------------------
// What inflows will add over the run

struct InflowOutlook {
  double volume_m3 = 0.0;     // let in by the end time: the hydrograph's integral
  double particles = 0.0;     // that volume in particles of spacing^2 x depth
  std::string depth_assumed;  // how the depth was taken, for the report
};

InflowOutlook inflow_outlook(const scenario::Inflow& in, double end_time_s, double gravity) {
  const auto* table = std::get_if<std::vector<std::array<double, 2>>>(&in.hydrograph);
  const boundaries::Hydrograph q(
      table ? *table : io::read_hydrograph_csv(std::get<std::filesystem::path>(in.hydrograph)));
  InflowOutlook out;
  out.volume_m3 = q.volume(0.0, end_time_s);
  const double cell_m2 = in.spacing_m * in.spacing_m;
  if (in.depth_m) {
    out.particles = out.volume_m3 / (cell_m2 * *in.depth_m);
    out.depth_assumed = fmt::format("depth {} m", num(*in.depth_m));
    return out;
  }
  // Without a depth the line lets water in at the critical depth of the discharge of the
  // moment, so each bit of volume Q dt makes particles of l^2 h_c(Q): summed over the run.
  const auto& [a, b] = in.line;
  const double length_m = std::hypot(b[0] - a[0], b[1] - a[1]);
  constexpr int kPieces = 2000;
  const double dt_s = end_time_s / kPieces;
  for (int k = 0; k < kPieces; ++k) {
    const double discharge = q.discharge((k + 0.5) * dt_s);
    if (discharge <= 0.0) continue;
    out.particles +=
        discharge * dt_s / (cell_m2 * boundaries::critical_depth_m(discharge / length_m, gravity));
  }
  out.depth_assumed = out.particles > 0.0
                          ? fmt::format("no depth given: the critical depth, {} m on average",
                                        num(out.volume_m3 / (out.particles * cell_m2)))
                          : "no depth given";
  return out;
}

// ---------------------------------------------------------------------------------------------
// Time step and timing

// Steps to the end time at a constant dt: a run also lands on every output time, which may
// split the step across each one before the end in two.
double steps_to_end(const scenario::Scenario& scene, double dt_s) {
  const std::size_t times = scene.output.times_s.size();
  return std::ceil(scene.end_time_s / dt_s) + static_cast<double>(times > 0 ? times - 1 : 0);
}

void time_step_section(const scenario::Scenario& scene, double dt_s, const std::string& note) {
  heading("Time step");
  row("first stable step", fmt::format("{:.9g} s", dt_s));
  row("steps to the end", fmt::format("{} at the first step's dt, output times landed on{}",
                                      count(steps_to_end(scene, dt_s)), note));
}

std::string threads_text() {
  const int threads = omp_get_max_threads();
  return fmt::format("{} thread{}", threads, threads == 1 ? "" : "s");
}

// Before a stretch of stepping in memory: what it is, shown while it runs.
void stepping_line(const std::string& what, double budget_s) {
  std::printf("  %s, stepped in memory (%s at most):\n", what.c_str(), duration(budget_s).c_str());
  std::fflush(stdout);
}

std::string reached_text(bool finished, double reached_s, const std::string& short_of_end) {
  return finished ? std::string("to its end time")
                  : fmt::format("to t = {} s{}", num(reached_s), short_of_end);
}

// The estimate, the band around it, and what it was made of.
void estimate_lines(const WallTimeEstimate& e, double reading_s) {
  std::printf("  about %s on %s: between %s and %s\n", duration(e.seconds).c_str(),
              threads_text().c_str(), duration(EstimateBand::kLow * e.seconds).c_str(),
              duration(EstimateBand::kHigh * e.seconds + EstimateBand::kFixedS).c_str());
  std::printf("    of which %s stepping, ", duration(e.stepping_s).c_str());
  if (e.statistics_samples > 0.0) {
    std::printf("%s for %s samples of the flood statistics, ", duration(e.statistics_s).c_str(),
                count(e.statistics_samples).c_str());
  }
  std::printf("%s reading the scene\n", duration(reading_s).c_str());
  // Measured, not a correction applied: docs/outputs.md, "Check".
  std::printf(
      "  The band is where the runs of the shipped scenes fell around such an estimate; writing "
      "maps adds to it.\n");
}

// A pilot run of the scene at the widest factor up to `factor` that builds (lowering it), its
// particles at the start, for the window it is measured against.
using PilotRunner =
    std::function<PilotRun(int& factor, const SceneWindow& window, double& pilot_start)>;

// The wall-time section: the scene stepped in memory for its window; where that does not
// reach the end time, a pilot run to it, scaled by the window. `start_particles` and
// `end_particles` (what inflows bring by the end) price the run from the window's rate alone,
// which sizes the pilot, and stands as a lower bound where no pilot can run.
void estimate_section(const scenario::Scenario& scene, int dimensions, const Stepper& stepper,
                      double dt_s, double start_particles, double end_particles,
                      double map_length_m,
                      const std::function<double(double)>& seconds_per_sample,
                      double reading_s, const PilotRunner& pilot_for) {
  heading("Wall-time estimate");
  stepping_line("the scene itself", kWindowS);
  SceneWindow window;
  try {
    window = step_window(scene.end_time_s, stepper, map_length_m, kWindowS);
  } catch (const swe::SimulationError&) {
    std::printf("\n  The steps broke down at t = %s s: the run would too.\n",
                num(stepper.time_s()).c_str());
    throw;
  }
  std::printf("    %s: %s steps, %s particle-steps in %s\n",
              reached_text(window.finished, window.until_s, "").c_str(),
              count(double(window.steps)).c_str(), count(window.particle_steps).c_str(),
              duration(window.seconds).c_str());
  // A sample grids the particles of the moment: priced at the run's mean count.
  const auto mean_particles = [](double particle_steps, double steps) {
    return steps > 0.0 ? particle_steps / steps : 0.0;
  };
  if (window.finished) {
    const double per_sample_s =
        seconds_per_sample(mean_particles(window.particle_steps, double(window.steps)));
    estimate_lines(whole_window(window, per_sample_s, reading_s), reading_s);
    return;
  }
  const double rate = window.measured()
                          ? window.rate()
                          : kAssumedRatePerThread * static_cast<double>(omp_get_max_threads());
  const double steps = steps_to_end(scene, dt_s);
  const double from_window_s = steps * 0.5 * (start_particles + end_particles) / rate;
  int factor = pilot_factor(from_window_s, dimensions, kPilotBudgetS);
  try {
    double pilot_start = 0.0;
    const PilotRun run = pilot_for(factor, window, pilot_start);
    std::printf(
        "    %s: %s steps, %s particle-steps in %s (%s s a step and %s s a "
        "particle-step)\n",
        reached_text(run.finished, run.reached_s,
                     ", where its time ran out (carried on to the end time in "
                     "proportion)")
            .c_str(),
        count(double(run.steps)).c_str(), count(run.particle_steps).c_str(),
        duration(run.seconds).c_str(), fmt::format("{:.2g}", run.seconds_per_step).c_str(),
        fmt::format("{:.2g}", run.seconds_per_particle_step).c_str());
    const double f = static_cast<double>(factor);
    const double start_ratio = start_particles > 0.0 && pilot_start > 0.0
                                   ? start_particles / pilot_start
                                   : std::pow(f, dimensions);
    const auto unpriced = scale_pilot(run, start_ratio, 0.0, reading_s);
    const double per_sample_s =
        seconds_per_sample(mean_particles(unpriced.particle_steps, unpriced.steps));
    const auto e = scale_pilot(run, start_ratio, per_sample_s, reading_s);
    std::printf(
        "    scaled to the scene: %.3g times the pilot's steps, %.3g times its particles "
        "a step, %.3g times its cost (%s): %s steps, %s particle-steps\n",
        e.step_ratio, e.particle_ratio, e.cost_ratio,
        e.calibrated
            ? fmt::format("steps and cost as the scene's own to t = {} s", num(window.until_s))
                  .c_str()
            : "steps as the first stable steps give them",
        count(e.steps).c_str(), count(e.particle_steps).c_str());
    estimate_lines(e, reading_s);
  } catch (const std::exception& e) {
    std::printf(
        "  at least about %s on %s (%s steps at dt = %s s, %s -> %s particles, at %s "
        "particle-steps/s)\n",
        duration(from_window_s + reading_s).c_str(), threads_text().c_str(), count(steps).c_str(),
        num(dt_s).c_str(), count(start_particles).c_str(), count(end_particles).c_str(),
        fmt::format("{:.2e}", rate).c_str());
    std::printf(
        "  No pilot run could be made (at %d times the spacing: %s); a flood that speeds "
        "up shortens the time step, and the shipped floods took up to 8 times this.\n",
        factor, e.what());
  }
}

void memory_section(const scenario::MemoryNeed& need, const std::string& not_counted) {
  // The scene's build has already refused a need beyond the usable memory, as in a run.
  const auto usable = static_cast<double>(scenario::usable_memory_bytes());
  std::string what = count(need.particles) + " particles";
  if (need.peak_particles > need.particles) what += ", " + count(need.peak_particles) + " at peak";
  heading("Memory");
  row("need", fmt::format("about {} ({}, {} grid cells{})", scenario::bytes_text(need.bytes()),
                          what, count(need.grid_cells), not_counted));
  row("usable", usable == 0.0
                    ? "unknown (not checked)"
                    : fmt::format("{} ({:.2g} % of it needed)", scenario::bytes_text(usable),
                                  100.0 * need.bytes() / usable));
}

// ---------------------------------------------------------------------------------------------
// Shallow water

// The particles at the start and what the scene does to their number; returns the particles
// inflows will add by the end time.
double particles_section(const scenario::Scenario& scene, swe::Simulation& sim) {
  heading("Particles");
  row("fluid at the start",
      fmt::format("{} ({} m3 of water)", count(double(sim.particles().fluid_count())),
                  num(sim.fluid_volume())));
  double spacing = 0.0;
  for (const auto& w : scene.water) spacing = std::max(spacing, w.spacing_m);
  if (!scene.water.empty()) row("spacing", num(spacing) + " m (the coarsest water body's)");
  double inflow_particles = 0.0;
  row("inflows", scene.inflows.empty() ? "none" : count(double(scene.inflows.size())));
  for (const auto& in : scene.inflows) {
    const InflowOutlook o = inflow_outlook(in, scene.end_time_s, scene.numerics.gravity_m_s2);
    inflow_particles += o.particles;
    row("  " + in.name,
        fmt::format("spacing {} m; {} m3 by the end time, about {} particles ({})",
                    num(in.spacing_m), num(o.volume_m3), count(o.particles), o.depth_assumed));
  }
  row("rain", scene.rain.empty() ? "none" : count(double(scene.rain.size())));
  for (const auto& effect : sim.effects()) {
    const auto* rain = dynamic_cast<const hydrology::Rain*>(effect.get());
    if (!rain) continue;
    row("  " + std::string(rain->name()),
        fmt::format("{} cells of {} m2 ({} m2); {} m3 falls by the end time, before losses",
                    count(double(rain->cell_count())), num(rain->cell_area_m2()),
                    num(rain->rain_area_m2()), num(rain->volume_due(0.0, scene.end_time_s))));
  }
  const auto& split = scene.splitting;
  row("splitting", !split ? "off"
                   : split->max_particles > 0
                       ? "on, capped at " + count(double(split->max_particles))
                       : "on, no cap");
  row("merging", scene.merging ? "on" : "off");
  std::size_t segments = 0;
  for (const auto& w : scene.walls) segments += w.polyline.size() - 1;
  row("walls", scene.walls.empty()
                   ? "none"
                   : fmt::format("{} polyline{}, {} segments; {} ghost particles mirrored now",
                                 scene.walls.size(), scene.walls.size() == 1 ? "" : "s", segments,
                                 count(double(sim.particles().ghost_count()))));
  std::string effects;
  for (const auto& e : sim.effect_times()) effects += (effects.empty() ? "" : ", ") + e.name;
  row("effects", effects.empty() ? "none" : effects);
  return inflow_particles;
}

// Each building file: what it held and what the footprints became.
void buildings_rows(const scenario::Scenario& scene, const scenario::Terrain& terrain) {
  if (scene.buildings.empty()) return;
  row("buildings",
      count(double(scene.buildings.size())) + (scene.buildings.size() == 1 ? " file" : " files"));
  for (std::size_t k = 0; k < terrain.buildings.size(); ++k) {
    const auto& read = terrain.buildings[k];
    const auto& spec = scene.buildings[k];
    std::string left_out;
    if (read.not_polygons + read.degenerate > 0) {
      left_out = fmt::format(
          "; left out: {} features without a polygon, {} polygons of fewer "
          "than 3 vertices",
          read.not_polygons, read.degenerate);
    }
    row("  " + spec.file.filename().string(),
        fmt::format("layer '{}': {} footprints, {}{}", read.layer, count(double(read.footprints)),
                    spec.as == scenario::BuildingsSpec::As::walls
                        ? "walls"
                        : "raised " + num(spec.height_m) + " m into the bed",
                    left_out));
  }
  if (!terrain.building_walls.empty()) {
    row("  wall segments", count(double(terrain.building_walls.size())));
  }
}

// The pathlines: how many particles a run starting now would follow, and where they go.
void pathlines_rows(const scenario::Scenario& scene, const scenario::Terrain& terrain,
                    const particles::SweParticles& p) {
  if (!scene.output.pathlines) return;
  const auto& spec = *scene.output.pathlines;
  std::string chosen = fmt::format("chosen at t = {} s", num(spec.start_s));
  if (spec.start_s == 0.0) {
    maps::PathlineChoice choice;
    choice.count = spec.count;
    if (spec.source) choice.label = scenario::provenance_label(scene, *spec.source);
    choice.area = terrain.pathline_area.get();
    const std::size_t n = maps::choose_pathline_particles(p, choice).size();
    chosen = n == 0 ? "none of the starting particles passes the filters"
                    : count(double(n)) + " particles, chosen at the start";
  }
  row("pathlines", fmt::format("{}, a vertex every {} s, to {}", chosen, num(spec.interval_s),
                               spec.file(scene.output.path).string()));
}

// What a run does at each sample of its flood statistics: grid the state and add it to the
// statistics (maps and series are written at their times only, and left out). Timed on the
// state the scene's window reached, the faster of two (the first pays for allocations); the
// gridding, which visits each particle's cells, scaled from the particles there to
// `mean_particles`, the run's mean.
double statistics_step_s(const scenario::Scenario& scene, const maps::CellAverages& cells,
                         swe::Simulation& sim, const swe::RegularGrid& grid,
                         double mean_particles) {
  sim.refresh();
  maps::FloodStatistics statistics(
      grid.nx * grid.ny,
      {scene.output.wet_depth_m, scene.output.depth_thresholds_m, scene.output.land_use,
       scene.output.tsunami ? std::optional<maps::TsunamiLevels>(scene.output.tsunami->levels)
                            : std::nullopt});
  double gridding_s = std::numeric_limits<double>::infinity(), update_s = gridding_s;
  for (int k = 0; k < 2; ++k) {
    auto started = Clock::now();
    const auto f = cells.fields(sim.particles(), sim.kernel());
    gridding_s = std::min(gridding_s, seconds_since(started));
    started = Clock::now();
    statistics.update(sim.time() + k, f.depth, f.u, f.v);
    update_s = std::min(update_s, seconds_since(started));
  }
  const double now = static_cast<double>(sim.particles().fluid_count());
  return update_s + gridding_s * (now > 0.0 && mean_particles > 0.0 ? mean_particles / now : 1.0);
}

// The pilot's simulation at the widest factor up to `factor` its scene builds at, lowering
// `factor` to it: a wider lattice can leave a lake's fill point dry or a tank's side short of
// a whole spacing (factor 1 is the scene itself, which has built).
template <class Build>
auto build_pilot(const scenario::Scenario& scene, int& factor, const Build& build) {
  for (;; --factor) {
    try {
      return build(scenario::coarsened(scene, factor));
    } catch (const scenario::ScenarioError&) {
      if (factor <= 1) throw;
    }
  }
}

// The scene's simulation as the estimate steps it: landing on each output time, as a run does.
Stepper swe_stepper(swe::Simulation& sim, const scenario::Scenario& scene) {
  const double gravity = scene.numerics.gravity_m_s2;
  return {[&sim, &scene] {
            const std::size_t before = sim.particle_steps();
            double target = scene.end_time_s;
            for (const double t : scene.output.times_s) {
              if (!sim.reached(t)) {
                target = std::min(target, t);
                break;
              }
            }
            sim.step_towards(target);
            return sim.particle_steps() - before;
          },
          [&sim] { return sim.particles().fluid_count(); }, [&sim] { return sim.time(); },
          [&sim, gravity] {
            sim.refresh();  // the depths the run's statistics see (cached for the next step)
            return fastest_wave_m_s(sim.particles(), gravity);
          },
          [&sim, &scene] {
            for (const double t : scene.output.times_s) {
              if (std::abs(sim.time() - t) <= 1e-9 * std::max(1.0, t)) return true;
            }
            return false;
          }};
}

void check_swe(const scenario::Scenario& scene, const Options& options) {
  const auto reading = Clock::now();
  auto built = scenario::build(scene);  // refuses a scene that does not fit in memory
  const double reading_s = seconds_since(reading);
  auto& sim = built.simulation;
  const auto grid = scenario::output_grid(scene, built.terrain);
  const bool seed = scene.numerics.scheme == swe::SchemeKind::seed;
  scene_section(scene, options, grid,
                fmt::format("shallow water, the {} scheme", seed ? "seed" : "conservative"));
  domain_section(scene, built.terrain);
  rasters_section(scene, built.terrain);

  const double dt_s = sim.stable_time_step();  // refreshes: ghosts and depths in place
  const double start = static_cast<double>(sim.particles().fluid_count());
  const double inflow_particles = particles_section(scene, sim);
  buildings_rows(scene, built.terrain);
  pathlines_rows(scene, built.terrain, sim.particles());
  // The need counts the particles at the start; those inflows let in come on top.
  memory_section(scenario::swe_memory_need(scene, built.terrain),
                 inflow_particles > 0.0 ? "; not counting the " + count(inflow_particles) +
                                              " particles inflows may add"
                                        : "");
  time_step_section(scene, dt_s,
                    scene.inflows.empty() ? "" : " (a lower bound: inflows add faster water)");

  // The count the inflows reach, from their volume over the run.
  const double end = start + inflow_particles;
  const auto cells = scenario::map_reader(scene, built.terrain, grid);
  estimate_section(
      scene, 2, swe_stepper(sim, scene), dt_s, start, end, cells.resolved_length_m(),
      [&](double mean_particles) {
        return statistics_step_s(scene, cells, sim, grid, mean_particles);
      },
      reading_s,
      [&](int& factor, const SceneWindow& window, double& pilot_start) {
        auto pilot = build_pilot(scene, factor, [](const scenario::Scenario& coarse) {
          return scenario::build(coarse).simulation;
        });
        stepping_line(fmt::format("a pilot run, the scene at {} times its spacing", factor),
                      kPilotBudgetS);
        pilot_start = static_cast<double>(pilot.particles().fluid_count());
        const PilotSetup setup{factor,
                               pilot.stable_time_step(),
                               dt_s,
                               scene.end_time_s,
                               cells.resolved_length_m(),
                               kPilotBudgetS,
                               window};
        return run_pilot(setup, swe_stepper(pilot, scene));
      });
}

// ---------------------------------------------------------------------------------------------
// Navier-Stokes

template <int Dim>
Stepper ns_stepper(ns::Simulation<Dim>& sim, double end_time_s) {
  return {[&sim, end_time_s] {
            const std::size_t fluid = sim.particles().fluid;
            sim.advance(std::min(sim.stable_time_step(), end_time_s - sim.time()));
            return fluid;
          },
          [&sim] { return sim.particles().fluid; },
          [&sim] { return sim.time(); },
          {},
          {}};
}

template <int Dim>
void check_ns(const scenario::Scenario& scene, const Options& options) {
  const auto reading = Clock::now();
  const auto terrain = scenario::read_terrain(scene);
  const auto tank = scenario::ns_tank<Dim>(scene);
  auto sim = scenario::make_ns_simulation<Dim>(scene);  // refuses what does not fit in memory
  const double reading_s = seconds_since(reading);
  const auto grid = scenario::output_grid(scene, terrain);
  scene_section(scene, options, grid,
                Dim == 2 ? "Navier-Stokes, 2D x-z section" : "Navier-Stokes, 3D");
  row("series table", ns_series_path(scene.output.path).string());
  domain_section(scene, terrain);
  rasters_section(scene, terrain);

  heading("Tank and particles");
  const auto& in = tank.interior;
  std::string size = num(in.upper[0] - in.lower[0]) + " m long";
  if constexpr (Dim == 3) size += ", " + num(in.upper[1] - in.lower[1]) + " m wide";
  row("interior", fmt::format("{}, {} m high; spacing {} m, {} solid layers, {} water boxes", size,
                              num(in.upper[Dim - 1] - in.lower[Dim - 1]), num(tank.spacing_m),
                              tank.solid_layers, tank.water.size()));
  const auto& p = sim.particles();
  const double start = static_cast<double>(p.fluid);
  row("fluid particles", count(start));
  row("wall and dummy",
      fmt::format("{} wall, {} dummy", count(double(p.wall)), count(double(p.dummy))));
  memory_section(scenario::ns_memory_need<Dim>(scene, tank), "");
  const double dt_s = sim.stable_time_step();
  time_step_section(scene, dt_s, "");

  estimate_section(
      scene, Dim, ns_stepper(sim, scene.end_time_s), dt_s, start, start, 0.0,
      [](double) { return 0.0; },
      reading_s,
      [&](int& factor, const SceneWindow& window, double& pilot_start) {
        auto pilot = build_pilot(scene, factor, [](const scenario::Scenario& coarse) {
          return scenario::make_ns_simulation<Dim>(coarse);
        });
        stepping_line(fmt::format("a pilot run, the scene at {} times its spacing", factor),
                      kPilotBudgetS);
        pilot_start = static_cast<double>(pilot.particles().fluid);
        const PilotSetup setup{
            factor, pilot.stable_time_step(), dt_s, scene.end_time_s, 0.0, kPilotBudgetS, window};
        return run_pilot(setup, ns_stepper(pilot, scene.end_time_s));
      });
}

}  // namespace

void check(const Options& options, const std::string& command_line) {
  // What run does before its first step, in the same order: the same scene is refused with
  // the same message and exit status.
  auto scene = scenario::load(options.scenario);
  if (options.output) scene.output.path = output_option(*options.output);
  check_output_target(scene.output.path);
  if (options.threads > 0) omp_set_num_threads(options.threads);
  (void)run_context(options, command_line, scene);

  if (scene.model == scenario::Model::ns) {
    if (scene.dimension == 2) {
      check_ns<2>(scene, options);
    } else {
      check_ns<3>(scene, options);
    }
  } else {
    check_swe(scene, options);
  }
  std::printf("\ncheck: OK — the scene can run\n");
  std::fflush(stdout);
}

}  // namespace swemps::cli
