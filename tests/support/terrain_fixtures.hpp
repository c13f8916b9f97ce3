#pragma once
// Small pieces the raster, terrain, map and scene tests all need: a CRS as WKT, and a grid
// geometry in one line.

#include <cpl_conv.h>
#include <ogr_spatialref.h>

#include <catch2/catch.hpp>
#include <cstddef>
#include <string>

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

}  // namespace swemps::testing
