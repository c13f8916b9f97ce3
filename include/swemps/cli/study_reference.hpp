#pragma once
// The maps a study with a map reference compares its runs with (study::MapReference, or its
// own finest run): read once, before any run starts where they come from files, so that a
// study does not run for hours to fail on its reference; and each finished run's result file
// measured against them. The arithmetic is study/map_comparison.hpp's; this reads the files.

#include <cstddef>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "swemps/scenario/scenario.hpp"
#include "swemps/study/map_comparison.hpp"
#include "swemps/study/study.hpp"
#include "swemps/terrain/gridded_field.hpp"

namespace swemps::cli {

// A reference's maximum depth in the scene's CRS, and its depth series at gauges.
struct ReferenceMaps {
  std::shared_ptr<const terrain::GriddedField> max_depth;
  struct Gauge {
    std::string name;
    std::vector<double> time_s, depth_m;
  };
  std::vector<Gauge> gauges;
};

// Reads a map reference for the base scene of a study: its raster in the scene's CRS, its
// gauge table's columns for gauges the scene has. Throws scenario::ScenarioError (study) at
// /reference/... for a raster or table that cannot be read, a column the table lacks or a
// gauge the scene does not have.
ReferenceMaps read_reference_maps(const study::MapReference& reference,
                                  const scenario::Scenario& scene);

// A finished run's result file as a reference (the finest run's): its maximum depth and all
// its gauges. Throws std::runtime_error naming the file.
ReferenceMaps reference_from_result(const std::filesystem::path& result);

// One gauge's peak against the reference's: run - reference in depth (m) and time (s).
struct GaugePeakError {
  std::string gauge;
  double peak_m = 0.0, depth_error_m = 0.0, time_error_s = 0.0;
};

struct MapMeasures {
  study::MaxDepthComparison max_depth;
  std::vector<GaugePeakError> gauges;  // in the reference's order; NaN for a gauge the run lacks
};

// The run's maximum depth on its own output cells against the reference averaged over them,
// over the cells wet (deeper than wet_depth_m) in either; and its gauge peaks. Throws
// std::runtime_error naming the file when the result cannot be read.
MapMeasures measure_result(const std::filesystem::path& result, const ReferenceMaps& reference,
                           double wet_depth_m);

}  // namespace swemps::cli
