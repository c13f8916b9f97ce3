#pragma once
// Pathlines out (docs/provenance.md, "Pathlines"): the tracks of the particles a scene follows
// as a vector file QGIS and GDAL open, one line a particle, in the scene's CRS. A GeoPackage
// holds each vertex's time as its M coordinate (LineString M); GeoJSON has no M, so there each
// line carries its vertices' times as the list attribute time_s.

#include <filesystem>
#include <string>
#include <vector>

#include "swemps/io/tsunami_products.hpp"
#include "swemps/maps/pathlines.hpp"

namespace swemps::io {

struct PathlineLayer {
  std::string crs_wkt;                    // the scene's CRS; empty: local metres
  std::vector<std::string> source_names;  // by provenance label, for the lines' source
  // What the times count from: the netCDF time axis's CF units ("seconds since ...").
  std::string time_units = "seconds since the start of the run";
};

// Writes the layer "pathlines" of `file`: per line, the attributes pathline (its index),
// source (its particle's largest share when chosen, where the lines have one), start_time_s,
// end_time_s, fate ("in the domain", "left the domain", "merged"), merged_into (the line a
// merged one joined; unset otherwise), length_m, vertices and time_units. A line of one vertex (its
// particle went in the step it was chosen) is written with that vertex twice, so that every line
// chosen is in the file. Written under a temporary name and renamed. Throws std::runtime_error
// naming the file on failure.
void write_pathlines(const std::vector<maps::Pathline>& lines, const PathlineLayer& layer,
                     const std::filesystem::path& file, VectorFile format);

}  // namespace swemps::io
