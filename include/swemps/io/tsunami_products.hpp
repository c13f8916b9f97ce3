#pragma once
// The products a tsunami study publishes beside its maps, made from a run's netCDF result as
// the flood products are (flood_products.hpp): the inundation line as a vector file whose
// vertices carry the ground elevation the water reached (the run-up along the line), and a
// table of the wave's arrival and largest rise at each gauge.

#include <filesystem>
#include <optional>

namespace swemps::io {

enum class VectorFile { gpkg, geojson };

// The run-up of one run, over all its inundation lines: the highest ground the water reached
// and, where the result has a still level, its height above that level.
struct InundationSummary {
  std::size_t lines = 0;
  double max_ground_elevation_m = 0.0;
  std::optional<double> max_runup_m;  // above the still level
  double x_m = 0.0, y_m = 0.0;        // where the highest ground is
};

// Whether `result` has the tsunami maps (a run with output.tsunami). Throws
// std::runtime_error naming the file when it cannot be read.
bool has_tsunami_maps(const std::filesystem::path& result);

// Writes the inundation line of `result` to `file` (GeoPackage layer "inundation_line", or
// GeoJSON), in the result's CRS: the lines where the largest depth over the run (max_depth)
// falls to the wet depth, interpolated linearly between cell centres, which bound the water's
// reach on land and around never-flooded ground offshore. Each line is a LineString Z whose
// vertices' Z is the bed elevation there, bilinear between cell centres (0 for a flat scene),
// with the attributes max_ground_elevation_m, max_runup_m (above the still level, where the
// result has one: a run with tsunami maps) and length_m. Returns the summary, or nothing
// (writing no file) when the water never bounded (every cell wet, or none). Written under a
// temporary name and renamed. Throws std::runtime_error naming the file on failure.
std::optional<InundationSummary> export_inundation_line(const std::filesystem::path& result,
                                                        const std::filesystem::path& file,
                                                        VectorFile format);

// Writes, for a result with tsunami maps and gauges, the CSV table gauge, x_m, y_m,
// arrival_time_s (the first series sample whose surface is the arrival rise above the still
// level; empty where never), max_surface_rise_m and time_of_max_rise_s (empty where the gauge
// was never wet), one row a gauge. Returns false, writing nothing, when the result has no
// gauges or no tsunami maps. Throws std::runtime_error naming the file on failure.
bool export_gauge_arrivals(const std::filesystem::path& result, const std::filesystem::path& csv);

}  // namespace swemps::io
