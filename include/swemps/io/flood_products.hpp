#pragma once
// The products flood engineers hand on, made from a run's netCDF result: one GeoTIFF per
// whole-run map (maxima, arrival times, durations, hazard classes) on the run's grid and CRS,
// and the gauge series as a CSV table. Made from the file rather than from the run, so that a
// run's end and `swe-mps export` of any finished file give the same products.

#include <filesystem>
#include <string>
#include <vector>

#include "swemps/io/geotiff_writer.hpp"
#include "swemps/maps/flood_statistics.hpp"
#include "swemps/maps/provenance_maxima.hpp"

namespace swemps::io {

// The maps a result can be exported as, by name (maps::summary_map_names(), and the
// provenance maxima's maps::provenance_map_names()).
inline const std::vector<std::string>& exportable_maps() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> all = maps::summary_map_names();
    const auto& provenance = maps::provenance_map_names();
    all.insert(all.end(), provenance.begin(), provenance.end());
    return all;
  }();
  return names;
}

// Writes the named maps of `result` (all of exportable_maps() when `names` is empty) as
// <prefix>_<name>.tif, or <prefix>_<name>_<threshold>m.tif per depth threshold, and returns
// the files written; max_source_depth and max_source_share as <prefix>_<name>_<source>.tif per
// source of the water. A map the file lacks (bed_elevation of a flat scene) is skipped.
// Throws std::invalid_argument for a name that is not exportable, std::runtime_error naming
// the file when the result cannot be read (not a swe-mps result: no summary maps) or a
// GeoTIFF cannot be written. The .partial file of a run that stopped early has its summary.
std::vector<std::filesystem::path> export_maps(const std::filesystem::path& result,
                                               const std::vector<std::string>& names,
                                               TiffLayout layout,
                                               const std::filesystem::path& prefix);

// A column name that spreadsheet and data-frame readers take as it is: letters, digits, '_',
// '-' and '.' kept, anything else (spaces, commas, quotes) replaced by '_'.
std::string column_name(const std::string& text);

// Writes the gauge series of `result` as CSV to `csv` (under <csv>.partial, then renamed):
// a header naming each column with its unit, then one row per series time: time_s, and per
// gauge <name>_depth_m, <name>_surface_elevation_m, <name>_u_m_s, <name>_v_m_s (empty where
// the value is missing: the gauge was dry) and, with provenance sources, <name>_share_<source>
// for each source (empty where the gauge was not wet). Returns false, writing nothing, when the result
// has no gauges. Throws std::runtime_error naming the file on failure.
bool export_gauges(const std::filesystem::path& result, const std::filesystem::path& csv);

}  // namespace swemps::io
