#pragma once
// `swe-mps compare`: one scene run twice, as shallow water (the scene as written) and as 3D
// Navier-Stokes (the same water columns extruded in z), with both surge fronts set against
// Ritter's dry-bed dam break.

#include <string>
#include <utility>
#include <vector>

#include "swemps/cli/options.hpp"

namespace swemps::cli {

// Writes <stem>.swe.nc, <stem>.ns.nc, <stem>.ns.series.csv and <stem>.fronts.csv; the stem is
// -o, or the scene's output path without its extension. The scene needs an "ns" block and
// must pass check_ns_scene, except that particle splitting is allowed (it refines the
// shallow-water run only). Throws scenario::ScenarioError, swe::SimulationError,
// ns::SimulationError, OutputError.
void compare(const Options& options, const std::string& command_line);

// A front position record: (time s, front m), times strictly increasing.
using FrontRecord = std::vector<std::pair<double, double>>;

// The record at time t, linear between its samples; NaN outside its time span (to a
// rounding tolerance of its last time).
double front_at(const FrontRecord& record, double t);

// Ritter's dry-bed front, x_dam + 2 sqrt(g h0) t.
double ritter_front(double x_dam_m, double depth_m, double gravity_m_s2, double t_s);

}  // namespace swemps::cli
