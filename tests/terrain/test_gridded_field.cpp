#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <stdexcept>
#include <vector>

#include "../support/terrain_fixtures.hpp"
#include "swemps/terrain/gridded_field.hpp"

using swemps::terrain::GriddedField;
using swemps::terrain::GridGeometry;
using swemps::terrain::RasterBed;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Five columns of 10 m and four rows of 20 m, placed at UTM-sized coordinates so that
// rounding in the coordinate arithmetic is as large as in a real scene.
GridGeometry small_geometry() {
  return swemps::testing::grid_geometry(5, 4, 500000.0, 4000000.0, 10.0, 20.0);
}

// z = a + b x + c y, sampled at the cell centres: bilinear interpolation reproduces it.
struct Plane {
  double a = 3.0, b = 0.02, c = -0.05;
  double operator()(double x, double y) const {
    // Relative to the raster's corner so that a stays the size of an elevation.
    return a + b * (x - 500000.0) + c * (y - 4000000.0);
  }
};

GriddedField plane_field(const Plane& plane) {
  const auto g = small_geometry();
  std::vector<double> values;
  for (std::size_t row = 0; row < g.rows; ++row) {
    for (std::size_t col = 0; col < g.columns; ++col) {
      values.push_back(plane(g.cell_centre_x(col), g.cell_centre_y(row)));
    }
  }
  return GriddedField(g, values, "", "plane");
}

GriddedField random_field(std::mt19937& rng, std::vector<std::size_t> nodata_cells = {}) {
  const auto g = small_geometry();
  std::uniform_real_distribution<double> value(-5.0, 5.0);
  std::vector<double> values(g.columns * g.rows);
  for (auto& v : values) v = value(rng);
  for (auto k : nodata_cells) values[k] = kNaN;
  return GriddedField(g, values);
}

// Centre-line index of a coordinate: how far the point is from the nearest line of centres.
double distance_to_centre_line(double position, double first_centre, double spacing) {
  const double index = (position - first_centre) / spacing;
  return std::abs(index - std::round(index)) * spacing;
}

}  // namespace

TEST_CASE("grid geometry: edges, centres and GDAL's geotransform", "[terrain]") {
  const auto g = small_geometry();
  CHECK(g.x_right() == 500050.0);
  CHECK(g.y_bottom() == 3999920.0);
  CHECK(g.cell_centre_x(0) == 500005.0);
  CHECK(g.cell_centre_y(0) == 3999990.0);  // row 0 is the northern row
  CHECK(g.cell_centre_y(3) == 3999930.0);
  CHECK(g.geotransform() == std::array<double, 6>{500000.0, 10.0, 0.0, 4000000.0, 0.0, -20.0});
}

TEST_CASE("gridded field rejects inconsistent input", "[terrain]") {
  auto g = small_geometry();
  CHECK_THROWS_AS(GriddedField(g, std::vector<double>(7)), std::invalid_argument);
  auto empty = g;
  empty.columns = 0;
  CHECK_THROWS_AS(GriddedField(empty, {}), std::invalid_argument);
  auto flat_cells = g;
  flat_cells.cell_height = 0.0;
  CHECK_THROWS_AS(GriddedField(flat_cells, std::vector<double>(20)), std::invalid_argument);
  CHECK_THROWS_AS(RasterBed(nullptr), std::invalid_argument);
}

TEST_CASE("bilinear interpolation reproduces a plane and its gradient", "[terrain]") {
  const Plane plane;
  const auto field = plane_field(plane);
  const auto& g = field.geometry();
  std::mt19937 rng(7);
  // Anywhere between the outermost centres, on centre lines and cell edges alike.
  std::uniform_real_distribution<double> x(g.cell_centre_x(0), g.cell_centre_x(g.columns - 1));
  std::uniform_real_distribution<double> y(g.cell_centre_y(g.rows - 1), g.cell_centre_y(0));
  for (int k = 0; k < 200; ++k) {
    const double px = x(rng), py = y(rng);
    CHECK(field.sample(px, py) == Approx(plane(px, py)).margin(1e-11));
    const auto slope = field.gradient(px, py);
    CHECK(slope[0] == Approx(plane.b).epsilon(1e-9));
    CHECK(slope[1] == Approx(plane.c).epsilon(1e-9));
  }
  // On the last centre lines too, where the interval before them is used.
  const double east = g.cell_centre_x(g.columns - 1), south = g.cell_centre_y(g.rows - 1);
  CHECK(field.gradient(east, south)[0] == Approx(plane.b).epsilon(1e-9));
  CHECK(field.gradient(east, south)[1] == Approx(plane.c).epsilon(1e-9));
}

TEST_CASE("sampling at a cell centre returns the cell's value exactly", "[terrain]") {
  std::mt19937 rng(11);
  // Nodata beside a centre must not leak into it: its weight there is zero.
  const auto field = random_field(rng, {1 * 5 + 2});
  const auto& g = field.geometry();
  for (std::size_t row = 0; row < g.rows; ++row) {
    for (std::size_t col = 0; col < g.columns; ++col) {
      if (std::isnan(field.at(col, row))) continue;
      CHECK(field.sample(g.cell_centre_x(col), g.cell_centre_y(row)) == field.at(col, row));
    }
  }
}

TEST_CASE("the gradient is the derivative of the sampled surface", "[terrain]") {
  std::mt19937 rng(3);
  const auto field = random_field(rng);
  const auto& g = field.geometry();
  // Central differences, kept away from the centre lines where the surface has a kink, and
  // reaching into the clamped margins, where the derivative across the edge is zero.
  const double h = 1e-3;  // m
  std::uniform_real_distribution<double> x(g.x_left - 20.0, g.x_right() + 20.0);
  std::uniform_real_distribution<double> y(g.y_bottom() - 20.0, g.y_top + 20.0);
  int checked = 0;
  while (checked < 300) {
    const double px = x(rng), py = y(rng);
    if (distance_to_centre_line(px, g.cell_centre_x(0), g.cell_width) < 10 * h ||
        distance_to_centre_line(py, g.cell_centre_y(0), g.cell_height) < 10 * h) {
      continue;
    }
    const auto slope = field.gradient(px, py);
    const double ddx = (field.sample(px + h, py) - field.sample(px - h, py)) / (2 * h);
    const double ddy = (field.sample(px, py + h) - field.sample(px, py - h)) / (2 * h);
    // The surface is linear along each axis within a cell: differences are exact up to
    // rounding of values ~5 divided by 2h.
    CHECK(slope[0] == Approx(ddx).margin(1e-8));
    CHECK(slope[1] == Approx(ddy).margin(1e-8));
    ++checked;
  }
}

TEST_CASE("beyond the outermost centres the surface is held constant", "[terrain]") {
  std::mt19937 rng(5);
  const auto field = random_field(rng);
  const auto& g = field.geometry();
  const double west = g.cell_centre_x(0), north = g.cell_centre_y(0);
  const double y_mid = 0.5 * (g.cell_centre_y(1) + g.cell_centre_y(2));
  // West margin and far beyond: the value of the western centre line at that y.
  const double on_line = field.sample(west, y_mid);
  CHECK(field.sample(g.x_left, y_mid) == Approx(on_line));
  CHECK(field.sample(g.x_left - 1000.0, y_mid) == Approx(on_line));
  const auto slope = field.gradient(g.x_left - 3.0, y_mid);
  CHECK(slope[0] == 0.0);
  CHECK(slope[1] == Approx(field.gradient(west + 1e-6, y_mid)[1]));
  // North-west corner and beyond it: the corner cell's value, flat in both directions.
  CHECK(field.sample(west - 50.0, north + 70.0) == field.at(0, 0));
  CHECK(field.gradient(west - 50.0, north + 70.0) == std::array<double, 2>{0.0, 0.0});
  // South-east likewise.
  CHECK(field.sample(g.x_right() + 1.0, g.y_bottom() - 1.0) == field.at(g.columns - 1, g.rows - 1));
}

TEST_CASE("a raster one cell wide is constant across it", "[terrain]") {
  GridGeometry g;
  g.columns = 1;
  g.rows = 3;
  g.cell_width = 2.0;
  g.cell_height = 1.0;
  g.y_top = 3.0;
  const GriddedField field(g, {4.0, 2.0, 0.0});
  CHECK(field.sample(-10.0, 1.5) == Approx(2.0));
  CHECK(field.sample(0.3, 2.0) == Approx(3.0));
  const auto slope = field.gradient(0.3, 2.0);
  CHECK(slope[0] == 0.0);
  CHECK(slope[1] == Approx(2.0));  // z rises northward
}

TEST_CASE("nodata spreads to exactly the cells it is interpolated into", "[terrain]") {
  std::mt19937 rng(13);
  const std::size_t col = 2, row = 1;
  const auto field = random_field(rng, {row * 5 + col});
  const auto& g = field.geometry();
  const double cx = g.cell_centre_x(col), cy = g.cell_centre_y(row);
  // Inside the four intervals around the nodata centre: NaN, gradient too.
  for (double dx : {-0.9, -0.3, 0.0, 0.4, 0.95}) {
    for (double dy : {-0.9, 0.0, 0.5}) {
      const double px = cx + dx * g.cell_width, py = cy + dy * g.cell_height;
      CHECK(std::isnan(field.sample(px, py)));
      CHECK(std::isnan(field.gradient(px, py)[0]));
      CHECK(std::isnan(field.gradient(px, py)[1]));
    }
  }
  // One full cell away the stencil no longer reaches it.
  CHECK(std::isfinite(field.sample(cx + 1.2 * g.cell_width, cy)));
  CHECK(std::isfinite(field.sample(cx, cy - 1.5 * g.cell_height)));
  CHECK(std::isfinite(field.gradient(cx - 1.5 * g.cell_width, cy + 0.5 * g.cell_height)[0]));
  // On the neighbouring centre the value is exact, but the slope toward the hole is not known.
  CHECK(std::isfinite(field.sample(cx - g.cell_width, cy)));
  CHECK(std::isnan(field.gradient(cx - g.cell_width, cy)[0]));
}

TEST_CASE("non-finite input values and coordinates give NaN", "[terrain]") {
  auto g = small_geometry();
  std::vector<double> values(20, 1.0);
  values[0] = std::numeric_limits<double>::infinity();
  const GriddedField field(g, values);
  CHECK(std::isnan(field.at(0, 0)));
  CHECK(std::isnan(field.sample(kNaN, g.cell_centre_y(2))));
  CHECK(std::isnan(field.gradient(g.cell_centre_x(2), kNaN)[1]));
}

TEST_CASE("nodata_in reports the nodata cells a rectangle would use", "[terrain]") {
  std::mt19937 rng(17);
  // Two holes: (col 3, row 0) and (col 4, row 3).
  const auto field = random_field(rng, {0 * 5 + 3, 3 * 5 + 4});
  const auto& g = field.geometry();
  // Interior of the two western columns: clear.
  CHECK(field.nodata_in(g.cell_centre_x(0), g.cell_centre_x(1), g.y_bottom(), g.y_top).count == 0);
  // The western half of the raster reaches column 3 from the interval between 2 and 3.
  const auto west_half = field.nodata_in(g.x_left, g.cell_centre_x(2) + 1.0, g.y_bottom(), g.y_top);
  CHECK(west_half.count == 1);
  CHECK(west_half.col == 3);
  CHECK(west_half.row == 0);
  CHECK(west_half.x_m == g.cell_centre_x(3));
  CHECK(west_half.y_m == g.cell_centre_y(0));
  // The whole raster, and a rectangle larger than it: both holes, the northern one first.
  for (double margin : {0.0, 500.0}) {
    const auto all = field.nodata_in(g.x_left - margin, g.x_right() + margin, g.y_bottom() - margin,
                                     g.y_top + margin);
    CHECK(all.count == 2);
    CHECK(all.col == 3);
    CHECK(all.row == 0);
  }
  // Consistency with sample(): wherever it reports none, sampling finds no NaN.
  std::uniform_real_distribution<double> x(g.x_left - 5.0, g.x_right() + 5.0);
  std::uniform_real_distribution<double> y(g.y_bottom() - 5.0, g.y_top + 5.0);
  for (int k = 0; k < 200; ++k) {
    double x0 = x(rng), x1 = x(rng), y0 = y(rng), y1 = y(rng);
    if (field.nodata_in(x0, x1, y0, y1).count > 0) continue;
    for (double fx : {0.0, 0.25, 0.5, 0.75, 1.0}) {
      for (double fy : {0.0, 0.5, 1.0}) {
        const double px = x0 + fx * (x1 - x0), py = y0 + fy * (y1 - y0);
        CHECK(std::isfinite(field.sample(px, py)));
        CHECK(std::isfinite(field.gradient(px, py)[0]));
      }
    }
  }
}

TEST_CASE("covers is true on the raster, edges included", "[terrain]") {
  std::mt19937 rng(19);
  const auto field = random_field(rng);
  const auto& g = field.geometry();
  CHECK(field.covers(g.x_left, g.y_top));
  CHECK(field.covers(g.x_right(), g.y_bottom()));
  CHECK(field.covers(g.cell_centre_x(2), g.cell_centre_y(1)));
  CHECK_FALSE(field.covers(g.x_left - 0.01, g.cell_centre_y(1)));
  CHECK_FALSE(field.covers(g.cell_centre_x(2), g.y_top + 0.01));
}

TEST_CASE("a raster bed is the field's surface", "[terrain]") {
  const Plane plane;
  const auto field = std::make_shared<const GriddedField>(plane_field(plane));
  const RasterBed bed(field);
  const double x = 500023.0, y = 3999951.0;
  CHECK(bed.elevation(x, y) == field->sample(x, y));
  CHECK(bed.gradient(x, y) == field->gradient(x, y));
  CHECK(bed.elevation(x, y) == Approx(plane(x, y)));
}
