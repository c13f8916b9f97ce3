#pragma once
// The products flood engineers hand on, made from a run's netCDF result: one GeoTIFF per
// whole-run map (maxima, arrival times, durations, hazard classes) on the run's grid and CRS,
// and the gauge series as a CSV table. Made from the file rather than from the run, so that a
// run's end and `swe-mps export` of any finished file give the same products.

#include <filesystem>
#include <string>
#include <vector>

#include "swemps/io/geotiff_writer.hpp"

namespace swemps::io {

// The maps a result can be exported as, by name: the whole-run maps of the netCDF file
// (max_depth, time_of_max_depth, max_surface_elevation, max_speed, max_depth_speed,
// max_depth_speed2, max_hazard_rating, arrival_time, inundation_duration, hazard_class_uk,
// hazard_class_aidr) and bed_elevation. arrival_time and inundation_duration give one file
// per depth threshold. Inline: the scene reader checks names against it without linking
// the writers.
inline const std::vector<std::string>& exportable_maps() {
  static const std::vector<std::string> names{
      "max_depth",           "time_of_max_depth", "max_surface_elevation", "max_speed",
      "max_depth_speed",     "max_depth_speed2",  "max_hazard_rating",     "arrival_time",
      "inundation_duration", "hazard_class_uk",   "hazard_class_aidr",     "bed_elevation"};
  return names;
}

// Writes the named maps of `result` (all of exportable_maps() when `names` is empty) as
// <prefix>_<name>.tif, or <prefix>_<name>_<threshold>m.tif per depth threshold, and returns
// the files written. A map the file lacks (bed_elevation of a flat scene) is skipped.
// Throws std::invalid_argument for a name that is not exportable, std::runtime_error naming
// the file when the result cannot be read (not a swe-mps result, no summary maps: a run that
// stopped early) or a GeoTIFF cannot be written.
std::vector<std::filesystem::path> export_maps(const std::filesystem::path& result,
                                               const std::vector<std::string>& names,
                                               TiffLayout layout,
                                               const std::filesystem::path& prefix);

// Writes the gauge series of `result` as CSV to `csv` (under <csv>.partial, then renamed):
// a header naming each column with its unit, then one row per series time: time_s, and per
// gauge <name>_depth_m, <name>_surface_elevation_m, <name>_u_m_s, <name>_v_m_s (empty where
// the value is missing: the gauge was dry). Returns false, writing nothing, when the result
// has no gauges. Throws std::runtime_error naming the file on failure.
bool export_gauges(const std::filesystem::path& result, const std::filesystem::path& csv);

}  // namespace swemps::io
