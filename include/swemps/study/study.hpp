#pragma once
// An accuracy-cost study: one scene run many times with its numerical knobs (particle spacing,
// splitting, scheme and its parameters, Courant number) set to every combination of
// the values listed, each run measured against a reference: an analytic solution at the
// scene's end time, a reference map of the maximum depth (a converged grid model's), or the
// study's own finest run. What runs the combinations (processes, timing, the table) is the
// study command; this module says what the runs are and what each one measures. No file formats here: the
// study file is read by scenario::load_study.

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "swemps/scenario/scenario.hpp"
#include "swemps/swe/settings.hpp"
#include "swemps/swe/simulation.hpp"
#include "swemps/verification/ritter.hpp"

namespace swemps::study {

// Splitting as a knob: off, or on with this area-ratio threshold.
struct SplittingChoice {
  std::optional<double> area_ratio_threshold;  // absent: no splitting

  bool operator==(const SplittingChoice&) const = default;
};

// One run's knobs. Each one absent means "as the scene has it".
struct RunKnobs {
  std::optional<double> spacing_m;  // of every water body
  std::optional<SplittingChoice> splitting;
  std::optional<swe::SchemeKind> scheme;
  std::optional<swe::GradientVariant> gradient;  // seed scheme only
  std::optional<double> kappa;                    // conservative scheme only
  std::optional<double> dissipation;              // conservative scheme only
  std::optional<double> shifting;                 // conservative scheme only
  std::optional<double> cfl;
  std::optional<double> alpha_e;  // seed scheme only

  bool operator==(const RunKnobs&) const = default;
};

// The values each knob takes; an empty axis is not swept (the scene's value is kept).
struct Sweep {
  std::vector<double> spacing_m;
  std::vector<SplittingChoice> splitting;
  std::vector<swe::SchemeKind> scheme;
  std::vector<swe::GradientVariant> gradient;
  std::vector<double> kappa;
  std::vector<double> dissipation;
  std::vector<double> shifting;
  std::vector<double> cfl;
  std::vector<double> alpha_e;
};

// Ritter's dam break as the reference; gravity is the scene's.
struct RitterReference {
  double dam_x_m = 0.0;
  double initial_depth_m = 0.0;  // h0; errors are relative to it
  double reservoir_start_x_m = 0.0;
};

// Which column of a gauge table holds which of the scene's gauges.
struct GaugeColumn {
  std::string gauge;   // the scene's gauge name
  std::string column;  // the table's column of its depth (m)
};

// A map of the whole-run maximum depth from a model the study trusts (a grid model refined
// until it converged, a surveyed flood), on any grid: each run's map is compared with it
// averaged over the run's output cells (map_comparison.hpp). Optionally the depth series at
// the scene's gauges, for the peaks.
struct MapReference {
  std::string max_depth;                // a raster GDAL opens: a file or a dataset name; m
  std::filesystem::path gauge_table;    // empty: no gauge series. CSV: time_s and depth columns
  std::vector<GaugeColumn> gauge_columns;
};

// The run of the finest spacing as the reference of the others (the first such run when
// several share it): what refining further would change, when nothing better is at hand.
struct FinestRunReference {};

using Reference = std::variant<RitterReference, MapReference, FinestRunReference>;

struct Study {
  std::filesystem::path scene;  // the scenario file every run starts from (absolute)
  Reference reference;
  // Map references: a cell is wet deeper than this (m); absent: the scene's output wet depth.
  std::optional<double> wet_depth_m;
  Sweep sweep;
  // The profile the errors are measured on has cells of side spacing / this ratio.
  double profile_spacing_ratio = 4.0;
  std::optional<int> jobs;  // runs at once; absent: one per core
  // A run still going after this many seconds is stopped and recorded as "timeout", so that
  // one run whose time step collapses cannot hold the study up for hours. Absent: no limit.
  std::optional<double> run_time_limit_s;
  std::filesystem::path output;  // the CSV table (absolute)
};

// Every combination of the sweep's values, the first axis (spacing) slowest and the last
// (alpha_e) fastest, in the order the values are listed. A study with no axis swept has one
// run: the scene as it is. A knob of one scheme is left out of the runs of the other (the
// scheme of a run is its scheme knob, or else the scene's), and runs made equal by that are
// kept once: scheme [seed, conservative] x gradient [mps, summation] x kappa [1.2, 1.3] is
// four runs, not eight. Throws std::invalid_argument when a swept knob applies to no run.
std::vector<RunKnobs> expand(const Sweep& sweep, swe::SchemeKind scene_scheme);

// Sets the knobs that are given on a loaded scene; the spacing is that of every water body
// and every inflow. Splitting on keeps the scene's other
// splitting settings (or the defaults when it has none) and sets the threshold.
void apply(const RunKnobs& knobs, scenario::Scenario& scene);

// The particle spacing a run of the scene has: the finest of its water bodies and inflows (0
// without any).
double finest_spacing(const scenario::Scenario& scene);

// What a finished run measures, besides its cost.
struct RunMeasures {
  std::size_t particles_end = 0;
  std::size_t steps = 0, particle_steps = 0;
  double relative_volume_change = 0.0;
  verification::RitterErrors errors{};
};

// The run's state at the scene's end time (refreshed) against Ritter's solution, on the
// profile along the scene's domain with cells of finest_spacing / profile_spacing_ratio.
RunMeasures measure(const swe::Simulation& simulation, const scenario::Scenario& scene,
                    const RitterReference& reference, double profile_spacing_ratio);

// A run's cost and error, for the Pareto front.
struct CostError {
  double cost = 0.0;   // wall time, s
  double error = 0.0;  // fan L1 / h0
};

// The runs no other run beats: none costs no more and errs no more while being better in one
// of the two. Runs whose cost or error is not finite (broken down) are left out; equal runs
// are all kept. Indices into `runs`, cheapest first.
std::vector<std::size_t> pareto_front(const std::vector<CostError>& runs);

// Names for the table and messages: "mps" / "summation"; "seed" / "conservative".
std::string gradient_name(swe::GradientVariant gradient);
std::string scheme_name(swe::SchemeKind scheme);
std::string describe(const RunKnobs& knobs);  // "spacing 0.05 m, splitting 1.5, mps"

}  // namespace swemps::study
