#pragma once
// Small pieces the raster, terrain, map and scene tests all need: a CRS as WKT, a grid
// geometry in one line, and a field sampled from a formula.

#include <cpl_conv.h>
#include <ogr_spatialref.h>

#include <catch2/catch.hpp>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "swemps/terrain/gridded_field.hpp"

namespace swemps::testing {

// The WKT of any CRS GDAL understands from user input ("EPSG:32616", a PROJ string ...).
inline std::string wkt_of(const std::string& user_input) {
  OGRSpatialReference crs;
  REQUIRE(crs.SetFromUserInput(user_input.c_str()) == OGRERR_NONE);
  char* text = nullptr;
  REQUIRE(crs.exportToWkt(&text) == OGRERR_NONE);
  std::string wkt = text;
  CPLFree(text);
  return wkt;
}

// A north-up grid of columns x rows cells whose top-left corner is (x_left, y_top).
inline terrain::GridGeometry grid_geometry(std::size_t columns, std::size_t rows, double x_left,
                                           double y_top, double cell_width, double cell_height) {
  terrain::GridGeometry g;
  g.columns = columns;
  g.rows = rows;
  g.x_left = x_left;
  g.y_top = y_top;
  g.cell_width = cell_width;
  g.cell_height = cell_height;
  return g;
}

// A field of square cells in local metres over [0, columns * cell] x [0, rows * cell], north
// up, each cell holding elevation(x, y) at its centre (the analytic beds of the verification
// tests, written with io::write_geotiff).
template <class Elevation>
terrain::GriddedField sampled_field(std::size_t columns, std::size_t rows, double cell,
                                    const Elevation& elevation) {
  const double y_top = static_cast<double>(rows) * cell;
  std::vector<double> z(columns * rows);
  for (std::size_t row = 0; row < rows; ++row) {
    const double y = y_top - (static_cast<double>(row) + 0.5) * cell;
    for (std::size_t column = 0; column < columns; ++column)
      z[row * columns + column] = elevation((static_cast<double>(column) + 0.5) * cell, y);
  }
  return terrain::GriddedField(grid_geometry(columns, rows, 0.0, y_top, cell, cell), std::move(z));
}

}  // namespace swemps::testing
