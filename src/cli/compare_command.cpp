#include "swemps/cli/compare_command.hpp"

#include <omp.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <string>
#include <variant>

#include "swemps/cli/output.hpp"
#include "swemps/cli/output_target.hpp"
#include "swemps/cli/runs.hpp"
#include "swemps/scenario/scenario.hpp"

namespace swemps::cli {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::filesystem::path with_suffix(const std::filesystem::path& stem, const std::string& suffix) {
  std::filesystem::path p = stem;
  p += suffix;
  return p;
}

// The times of the fronts table: t = 0, every multiple of the series interval, and the end.
std::vector<double> front_times(const scenario::Scenario& scene) {
  const double end = scene.end_time_s;
  const double slack = 1e-9 * end;
  std::vector<double> times{0.0};
  for (std::size_t k = 1;; ++k) {
    const double t = static_cast<double>(k) * scene.output.series_interval_s;
    if (t >= end - slack) break;
    times.push_back(t);
  }
  times.push_back(end);
  return times;
}

}  // namespace

double front_at(const FrontRecord& record, double t) {
  if (record.empty()) return kNaN;
  const double slack = 1e-9 * std::max(1.0, std::abs(record.back().first));
  if (t < record.front().first - slack || t > record.back().first + slack) return kNaN;
  const auto after =
      std::lower_bound(record.begin(), record.end(), t,
                       [](const auto& sample, double time) { return sample.first < time; });
  if (after == record.end()) return record.back().second;
  if (after == record.begin() || after->first == t) return after->second;
  const auto before = after - 1;
  const double w = (t - before->first) / (after->first - before->first);
  return before->second + w * (after->second - before->second);
}

double ritter_front(double x_dam_m, double depth_m, double gravity_m_s2, double t_s) {
  return x_dam_m + 2.0 * std::sqrt(gravity_m_s2 * depth_m) * t_s;
}

void compare(const Options& options, const std::string& command_line) {
  const auto scene = scenario::load(options.scenario);
  if (options.threads > 0) omp_set_num_threads(options.threads);
  const std::filesystem::path stem =
      options.output ? output_option(*options.output)
                     : std::filesystem::path(scene.output.path).replace_extension();

  scenario::Scenario swe_scene = scene;
  swe_scene.model = scenario::Model::swe;
  swe_scene.output.path = with_suffix(stem, ".swe.nc");
  // The Navier-Stokes side runs in 3D, and the scheme's defaults were read for the scene's
  // dimension (ns::scheme_settings): a 2D scene would run with the 2D ones.
  if (scene.dimension != 3) {
    throw scenario::ScenarioError("/dimension", std::to_string(scene.dimension),
                                  "3 or no key (compare runs the Navier-Stokes side in 3D)");
  }
  scenario::Scenario ns_scene = scene;
  ns_scene.model = scenario::Model::ns;
  ns_scene.output.path = with_suffix(stem, ".ns.nc");
  // Splitting and merging set the shallow-water particles' resolution where the water thins or
  // gathers; they are numerics, not physics, so the comparison keeps them for the shallow-water
  // run and needs no counterpart.
  if (ns_scene.splitting) {
    ns_scene.splitting.reset();
    spdlog::info("compare: particle splitting applies to the shallow-water run only");
  }
  if (ns_scene.merging) {
    ns_scene.merging.reset();
    spdlog::info("compare: particle merging applies to the shallow-water run only");
  }
  // Before anything runs, so that a scene model ns cannot take fails at once.
  scenario::check_ns_scene(ns_scene);
  const std::filesystem::path fronts_path = with_suffix(stem, ".fronts.csv");
  if (!stem.has_filename()) check_output_target(stem);  // -o "" would name ".swe.nc"
  for (const auto& file : {swe_scene.output.path, ns_scene.output.path, fronts_path}) {
    check_output_target(file);
  }

  // Ritter's dam is the downstream (largest x) edge of the first water body.
  const auto& dam = scene.water.front();
  double x_dam = -std::numeric_limits<double>::infinity();
  for (const auto& p : dam.polygon) x_dam = std::max(x_dam, p[0]);
  const double h0 = std::get<scenario::UniformDepth>(dam.depth).depth_m;
  const double g = scene.numerics.gravity_m_s2;

  const RunContext context{options.scenario, command_line, options.verbosity != Verbosity::quiet};
  FrontRecord swe_fronts, ns_fronts;
  const auto recorder = [](FrontRecord& record) {
    return [&record](double t, double front) {
      // Equal times (a sample at an output time) add nothing to the record.
      if (record.empty() || t > record.back().first) record.emplace_back(t, front);
    };
  };
  spdlog::info("compare 1/2: shallow water -> {}", swe_scene.output.path.string());
  const RunReport swe = run_swe(swe_scene, context, recorder(swe_fronts));
  spdlog::info("compare 2/2: Navier-Stokes, 3D -> {}", ns_scene.output.path.string());
  const RunReport ns = run_ns(ns_scene, context, recorder(ns_fronts));

  CsvTable fronts(fronts_path, {"time_s", "swe_front_m", "ns_front_m", "ritter_front_m"});
  for (const double t : front_times(scene)) {
    const std::vector<double> row{t, front_at(swe_fronts, t), front_at(ns_fronts, t),
                                  ritter_front(x_dam, h0, g, t)};
    fronts.row(row);
  }
  fronts.finish();

  const double end = scene.end_time_s;
  spdlog::info("compare: shallow water {} particles, {} steps, {:.2f} s wall time",
               swe.fluid_particles, swe.steps, swe.wall_s);
  spdlog::info(
      "compare: Navier-Stokes {} fluid, {} wall and {} dummy particles, {} steps, {:.2f} s wall "
      "time",
      ns.fluid_particles, ns.wall_particles, ns.dummy_particles, ns.steps, ns.wall_s);
  spdlog::info(
      "compare: fronts at t = {} s: shallow water {:.4f} m, Navier-Stokes {:.4f} m, Ritter {:.4f} "
      "m (dam at x = {} m, h0 = {} m)",
      end, front_at(swe_fronts, end), front_at(ns_fronts, end), ritter_front(x_dam, h0, g, end),
      x_dam, h0);
  spdlog::info("wrote {}", fronts.path().string());
}

}  // namespace swemps::cli
