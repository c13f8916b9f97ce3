#include "swemps/cli/pathline_output.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <system_error>

#include "swemps/cli/run_command.hpp"
#include "swemps/cli/timing.hpp"

namespace swemps::cli {

namespace {

constexpr const char* kStateLabel = "swe-mps pathlines";

// Whether `time_s` has reached `due_s`, a step ending a rounding error short counting.
bool reached(double time_s, double due_s) { return time_s >= due_s - 1e-12 * std::abs(due_s); }

// The first vertex time after `time_s`: start + a multiple of the interval.
double next_vertex_time(double time_s, double start_s, double interval_s) {
  const double multiples = std::floor((time_s - start_s) / interval_s * (1.0 + 1e-12) + 1e-12);
  return start_s + (std::max(multiples, 0.0) + 1.0) * interval_s;
}

// "<stem>.partial<ext>" beside `file`, as a stopped run's netCDF file keeps ".partial".
std::filesystem::path stopped_name(const std::filesystem::path& file) {
  std::filesystem::path partial = file;
  partial.replace_filename(file.stem().string() + ".partial" + file.extension().string());
  return partial;
}

}  // namespace

PathlineOutput::PathlineOutput(const scenario::Scenario& scene, const scenario::Terrain& terrain)
    : spec_(scene.output.pathlines.value()),
      file_(spec_.file(scene.output.path)),
      area_(terrain.pathline_area) {
  choice_.count = spec_.count;
  if (spec_.source) choice_.label = scenario::provenance_label(scene, *spec_.source);
  choice_.area = area_.get();
  layer_.crs_wkt = terrain.crs_wkt;
  if (scene.output.provenance.sources) layer_.source_names = scenario::provenance_labels(scene);
  if (scene.output.start_time_units) layer_.time_units = *scene.output.start_time_units;
}

void PathlineOutput::observe(swe::Simulation& sim) {
  const auto start = Clock::now();
  const double t = sim.time();
  if (recorder_.started()) {
    const auto ends = sim.take_pathline_ends();
    recorder_.end(ends, t);
    if (reached(t, next_vertex_s_)) {
      recorder_.record(sim.particles(), t);
      next_vertex_s_ = next_vertex_time(t, spec_.start_s, spec_.interval_s);
    }
  } else if (reached(t, spec_.start_s)) {
    const auto chosen = maps::choose_pathline_particles(sim.particles(), choice_);
    recorder_.start(sim.particles(), chosen, t);
    for (std::size_t k = 0; k < chosen.size(); ++k) {
      sim.start_pathline(chosen[k], static_cast<std::int32_t>(k));
    }
    next_vertex_s_ = next_vertex_time(t, spec_.start_s, spec_.interval_s);
    if (chosen.empty()) {
      std::string which = "no particle";
      if (spec_.source) which += " of source '" + *spec_.source + "'";
      if (area_) which += " inside the polygon";
      spdlog::warn("pathlines: {} at t = {:.6g} s, so none is followed{}", which, t,
                   spec_.source ? "; water that enters later is chosen by an "
                                  "output.pathlines.start after it has entered"
                                : "");
    } else {
      spdlog::info("pathlines: following {} particles from t = {:.6g} s, a vertex every {:.6g} s",
                   chosen.size(), t, spec_.interval_s);
    }
  }
  seconds_ += seconds_since(start);
}

void PathlineOutput::write(const swe::Simulation* last, const std::filesystem::path& file) {
  const auto start = Clock::now();
  // The run ends here (a checkpoint, if any, holds the lines as they were before this vertex).
  if (last) recorder_.record(last->particles(), last->time());
  try {
    io::write_pathlines(recorder_.lines(), layer_, file,
                        spec_.format == scenario::VectorFormat::geojson ? io::VectorFile::geojson
                                                                        : io::VectorFile::gpkg);
  } catch (const std::runtime_error& e) {
    throw OutputError(e.what());
  }
  seconds_ += seconds_since(start);
}

void PathlineOutput::finish(const swe::Simulation& sim) {
  write(&sim, file_);
  std::error_code ignored;
  std::filesystem::remove(stopped_name(file_), ignored);
  spdlog::info("wrote {} ({} pathlines, {} vertices; following and writing them took {:.3f} s)",
               file_.string(), recorder_.lines().size(), recorder_.vertices(), seconds_);
}

std::filesystem::path PathlineOutput::close_stopped(const swe::Simulation* last) {
  const std::filesystem::path file = stopped_name(file_);
  write(last, file);
  return file;
}

void PathlineOutput::save_state(swe::StateWriter& out) const {
  out.text(kStateLabel);
  out.number(next_vertex_s_);
  out.numbers(recorder_.state());
}

void PathlineOutput::restore_state(swe::StateReader& in) {
  in.expect(kStateLabel);
  next_vertex_s_ = in.number();
  try {
    recorder_.restore(in.numbers());
  } catch (const std::invalid_argument& e) {
    throw swe::StateError(in.what() + ": " + e.what());
  }
}

}  // namespace swemps::cli
