#include "swemps/terrain/gridded_field.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

namespace swemps::terrain {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// A point computed as a cell centre (x_left + (col + 0.5) * width) lands on the centre only up
// to rounding; within this fraction of a cell it is taken to be on it, so that sampling there
// returns the cell's value exactly and never touches a nodata neighbour with weight ~1e-16.
constexpr double kCentreSnap = 1e-8;

double snap_to_centre(double index) {
  const double nearest = std::round(index);
  return std::abs(index - nearest) < kCentreSnap ? nearest : index;
}

// Sum of weight * value over the cells of a 2 x 2 stencil, leaving out cells whose weight is
// exactly zero: such a cell does not shape the surface here, so its being nodata must not
// turn the result into NaN (0 * NaN would).
double weighted_sum(const std::array<double, 4>& values, const std::array<double, 4>& weights) {
  double sum = 0.0;
  for (std::size_t k = 0; k < 4; ++k) {
    if (weights[k] != 0.0) sum += weights[k] * values[k];
  }
  return sum;
}

}  // namespace

std::array<double, 6> GridGeometry::geotransform() const {
  return {x_left, cell_width, 0.0, y_top, 0.0, -cell_height};
}

GriddedField::GriddedField(GridGeometry geometry, std::vector<double> values, std::string crs_wkt,
                           std::string name)
    : geometry_(geometry),
      values_(std::move(values)),
      crs_wkt_(std::move(crs_wkt)),
      name_(std::move(name)) {
  const auto& g = geometry_;
  if (g.columns == 0 || g.rows == 0) throw std::invalid_argument("gridded field: empty grid");
  if (!(g.cell_width > 0.0) || !(g.cell_height > 0.0) || !std::isfinite(g.cell_width) ||
      !std::isfinite(g.cell_height)) {
    throw std::invalid_argument("gridded field: cell sizes must be positive and finite");
  }
  if (!std::isfinite(g.x_left) || !std::isfinite(g.y_top)) {
    throw std::invalid_argument("gridded field: grid origin must be finite");
  }
  if (values_.size() != g.columns * g.rows) {
    throw std::invalid_argument("gridded field: " + std::to_string(values_.size()) +
                                " values for a grid of " + std::to_string(g.columns) + " x " +
                                std::to_string(g.rows) + " cells");
  }
  // Any non-finite value (inf included) is nodata; keeping only NaN lets sample() rely on NaN
  // propagation alone.
  for (double& v : values_) {
    if (!std::isfinite(v)) v = kNaN;
  }
}

GriddedField::AxisStencil GriddedField::locate(double index, std::size_t count) {
  // `index` is the position in units of cells, 0 at the first centre and count - 1 at the
  // last. A single cell spans nothing to interpolate across: constant, as if clamped.
  if (count == 1) return {0, 0, 0.0, true};
  index = snap_to_centre(index);
  const double last = static_cast<double>(count - 1);
  if (index < 0.0) return {0, 1, 0.0, true};
  if (index > last) return {count - 2, count - 1, 1.0, true};
  // The last centre belongs to the interval before it, so `second` stays on the grid.
  const auto first = std::min(static_cast<std::size_t>(std::floor(index)), count - 2);
  return {first, first + 1, index - static_cast<double>(first), false};
}

GriddedField::AxisStencil GriddedField::locate_x(double x_m) const {
  return locate((x_m - geometry_.x_left) / geometry_.cell_width - 0.5, geometry_.columns);
}

GriddedField::AxisStencil GriddedField::locate_y(double y_m) const {
  // Rows count southward, so the row index grows as y falls.
  return locate((geometry_.y_top - y_m) / geometry_.cell_height - 0.5, geometry_.rows);
}

GriddedField GriddedField::scaled(double factor) const {
  std::vector<double> values = values_;
  for (double& v : values) v *= factor;
  return GriddedField(geometry_, std::move(values), crs_wkt_, name_);
}

double GriddedField::sample(double x_m, double y_m) const {
  if (!std::isfinite(x_m) || !std::isfinite(y_m)) return kNaN;
  const auto sx = locate_x(x_m);
  const auto sy = locate_y(y_m);
  // Cells in the order (first col, first row), (second col, first row), (first, second),
  // (second, second).
  const std::array<double, 4> v = {at(sx.first, sy.first), at(sx.second, sy.first),
                                   at(sx.first, sy.second), at(sx.second, sy.second)};
  const double tx = sx.t, ty = sy.t;
  return weighted_sum(v, {(1 - tx) * (1 - ty), tx * (1 - ty), (1 - tx) * ty, tx * ty});
}

std::array<double, 2> GriddedField::gradient(double x_m, double y_m) const {
  if (!std::isfinite(x_m) || !std::isfinite(y_m)) return {kNaN, kNaN};
  const auto sx = locate_x(x_m);
  const auto sy = locate_y(y_m);
  const std::array<double, 4> v = {at(sx.first, sy.first), at(sx.second, sy.first),
                                   at(sx.first, sy.second), at(sx.second, sy.second)};
  const double tx = sx.t, ty = sy.t;
  // The surface is (1-tx)(1-ty) v0 + tx (1-ty) v1 + (1-tx) ty v2 + tx ty v3 with
  // tx = (x - x_first) / cell_width and ty = (y_first - y) / cell_height; these are its
  // partial derivatives in tx and ty.
  const double d_tx = sx.clamped ? 0.0 : weighted_sum(v, {-(1 - ty), (1 - ty), -ty, ty});
  const double d_ty = sy.clamped ? 0.0 : weighted_sum(v, {-(1 - tx), -tx, (1 - tx), tx});
  // Where the value itself is undefined, so is its slope, even along a clamped direction.
  const double value =
      weighted_sum(v, {(1 - tx) * (1 - ty), tx * (1 - ty), (1 - tx) * ty, tx * ty});
  if (std::isnan(value) || std::isnan(d_tx) || std::isnan(d_ty)) return {kNaN, kNaN};
  return {d_tx / geometry_.cell_width, -d_ty / geometry_.cell_height};
}

bool GriddedField::covers(double x_m, double y_m) const {
  const auto& g = geometry_;
  return x_m >= g.x_left && x_m <= g.x_right() && y_m >= g.y_bottom() && y_m <= g.y_top;
}

std::size_t GriddedField::cell_holding(double x_m, double y_m) const {
  if (!covers(x_m, y_m)) return kNoCell;  // also false for NaN
  const auto& g = geometry_;
  const auto index = [](double offset, double size, std::size_t count) {
    const double last = static_cast<double>(count) - 1.0;
    return static_cast<std::size_t>(std::min(last, std::max(0.0, std::floor(offset / size))));
  };
  return index(g.y_top - y_m, g.cell_height, g.rows) * g.columns +
         index(x_m - g.x_left, g.cell_width, g.columns);
}

double GriddedField::cell_value(double x_m, double y_m) const {
  const std::size_t cell = cell_holding(x_m, y_m);
  return cell == kNoCell ? kNaN : values_[cell];
}

GriddedField::NodataReport GriddedField::nodata_in(double x_min, double x_max, double y_min,
                                                   double y_max) const {
  if (!std::isfinite(x_min) || !std::isfinite(x_max) || !std::isfinite(y_min) ||
      !std::isfinite(y_max)) {
    throw std::invalid_argument("gridded field: nodata_in needs a finite rectangle");
  }
  if (x_min > x_max) std::swap(x_min, x_max);
  if (y_min > y_max) std::swap(y_min, y_max);
  const auto& g = geometry_;
  // Cell k shapes the surface for centre indices in [k - 1, k + 1]; beyond the outermost
  // centres the surface is that of the outermost one. Closed intervals count a cell whose
  // weight vanishes on the rectangle's edge, as the one-sided gradient there may use it.
  auto cell_range = [](double index_a, double index_b, std::size_t count) {
    const double last = static_cast<double>(count - 1);
    const double lo = std::clamp(std::min(index_a, index_b), 0.0, last);
    const double hi = std::clamp(std::max(index_a, index_b), 0.0, last);
    const auto first = static_cast<std::size_t>(std::max(0.0, std::ceil(lo) - 1.0));
    const auto end = static_cast<std::size_t>(std::min(last, std::floor(hi) + 1.0)) + 1;
    return std::pair{first, end};
  };
  const auto [col_begin, col_end] = cell_range((x_min - g.x_left) / g.cell_width - 0.5,
                                               (x_max - g.x_left) / g.cell_width - 0.5, g.columns);
  const auto [row_begin, row_end] = cell_range((g.y_top - y_max) / g.cell_height - 0.5,
                                               (g.y_top - y_min) / g.cell_height - 0.5, g.rows);
  NodataReport report;
  for (std::size_t row = row_begin; row < row_end; ++row) {
    for (std::size_t col = col_begin; col < col_end; ++col) {
      if (!std::isnan(at(col, row))) continue;
      if (report.count == 0) {
        report.col = col;
        report.row = row;
        report.x_m = g.cell_centre_x(col);
        report.y_m = g.cell_centre_y(row);
      }
      ++report.count;
    }
  }
  return report;
}

RasterBed::RasterBed(std::shared_ptr<const GriddedField> field) : field_(std::move(field)) {
  if (!field_) throw std::invalid_argument("raster bed: no raster");
}

}  // namespace swemps::terrain
