// The output grid a scene's maps are written on, and how its maps and gauges read the
// particles' water there (build.hpp).

#include <algorithm>
#include <cmath>

#include "json_reading.hpp"
#include "load_sections.hpp"
#include "swemps/scenario/build.hpp"

namespace swemps::scenario {

using json_reading::fmt;

double finest_spacing(const Scenario& scene) {
  double finest = 0.0;
  const auto consider = [&](double spacing) {
    if (spacing > 0.0 && (finest == 0.0 || spacing < finest)) finest = spacing;
  };
  for (const auto& w : scene.water) consider(w.spacing_m);
  for (const auto& in : scene.inflows) consider(in.spacing_m);
  for (const auto& rain : scene.rain) consider(rain.spacing_m);
  return finest;
}

namespace {

maps::Bounds domain_bounds(const Terrain& terrain) {
  const auto& d = terrain.domain;
  return {d.x_min, d.x_max, d.y_min, d.y_max};
}

}  // namespace

maps::CellAverages map_reader(const Scenario& scene, const Terrain& terrain,
                              const swe::RegularGrid& grid) {
  return maps::CellAverages(grid, terrain.bed, domain_bounds(terrain), finest_spacing(scene));
}

maps::CellAverages gauge_reader(const Scenario& scene, const Terrain& terrain,
                                const swe::RegularGrid& grid, const Point& point) {
  const double finest = finest_spacing(scene);
  const auto side = [&](double cell) {
    if (!(finest > 0.0)) return cell;
    return std::clamp(cell, kGaugeLeastSpacings * finest, kGaugeSpacings * finest);
  };
  const swe::RegularGrid cell{point[0], point[1], side(grid.dx), side(grid.dy), 1, 1};
  return maps::CellAverages(cell, terrain.bed, domain_bounds(terrain),
                            finest / kGaugeSubPointsPerSpacing);
}

swe::RegularGrid output_grid(const Scenario& scene, const Terrain& terrain) {
  const auto& g = scene.output.grid;
  const Rectangle bounds = g.bounds.value_or(terrain.domain);
  if (g.spacing_m || !terrain.bed_raster) {
    const double spacing = g.spacing_m.value_or(bounds.x_max - bounds.x_min);
    const double width = bounds.x_max - bounds.x_min;
    const double height = bounds.y_max - bounds.y_min;
    const auto nx = static_cast<std::size_t>(std::max(1.0, std::round(width / spacing)));
    const auto ny = static_cast<std::size_t>(std::max(1.0, std::round(height / spacing)));
    const double dx = width / static_cast<double>(nx);
    const double dy = height / static_cast<double>(ny);
    return {bounds.x_min + 0.5 * dx, bounds.y_min + 0.5 * dy, dx, dy, nx, ny};
  }
  // The bed raster's own cells, so that the maps line up with the DEM cell for cell. A cell
  // counts when it lies whole inside the bounds; 1e-9 of a cell forgives bounds that were
  // written out with rounding.
  const auto& geo = terrain.bed_cells;
  constexpr double kForgive = 1e-9;
  const auto clamp_index = [](double index, std::size_t count) {
    return static_cast<std::size_t>(std::clamp(index, 0.0, static_cast<double>(count)));
  };
  const std::size_t col_begin =
      clamp_index(std::ceil((bounds.x_min - geo.x_left) / geo.cell_width - kForgive), geo.columns);
  const std::size_t col_end =
      clamp_index(std::floor((bounds.x_max - geo.x_left) / geo.cell_width + kForgive), geo.columns);
  const std::size_t row_begin =
      clamp_index(std::ceil((geo.y_top - bounds.y_max) / geo.cell_height - kForgive), geo.rows);
  const std::size_t row_end =
      clamp_index(std::floor((geo.y_top - bounds.y_min) / geo.cell_height + kForgive), geo.rows);
  if (col_end <= col_begin || row_end <= row_begin) {
    throw ScenarioError(g.bounds ? "/output/grid" : "/domain",
                        "bounds " + describe_box(bounds) + " holding no whole bed raster cell (" +
                            fmt(geo.cell_width) + " m x " + fmt(geo.cell_height) + " m)",
                        "bounds holding at least one bed raster cell, or a grid \"spacing\"");
  }
  // Rows of the output grid run south to north: the first is the raster's southernmost.
  return {geo.cell_centre_x(col_begin),
          geo.cell_centre_y(row_end - 1),
          geo.cell_width,
          geo.cell_height,
          col_end - col_begin,
          row_end - row_begin};
}

}  // namespace swemps::scenario
