#pragma once
// A raster held in memory (bed elevation, Manning's n, ...) and the smooth-enough surface the
// solver sees through it: bilinear interpolation between cell centres. Reading files is the io
// module's job; this is pure arithmetic on a grid of numbers, so the physics can sample a
// raster without knowing that a file ever existed.

#include <array>
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "swemps/swe/bed.hpp"

namespace swemps::terrain {

// A north-up raster in a projected CRS in metres. Cell (col, row) covers
// [x_left + col * cell_width, x_left + (col + 1) * cell_width] in x and has its centre at
//   x = x_left + (col + 0.5) * cell_width,   y = y_top - (row + 0.5) * cell_height;
// row 0 is the northern row, as in GDAL and in most DEM files.
struct GridGeometry {
  std::size_t columns = 0, rows = 0;
  double x_left = 0.0, y_top = 0.0;            // m, outer edges
  double cell_width = 0.0, cell_height = 0.0;  // m, both positive

  // GDAL's affine transform: x_left, cell_width, 0, y_top, 0, -cell_height.
  std::array<double, 6> geotransform() const;
  double x_right() const { return x_left + static_cast<double>(columns) * cell_width; }
  double y_bottom() const { return y_top - static_cast<double>(rows) * cell_height; }
  double cell_centre_x(std::size_t col) const {
    return x_left + (static_cast<double>(col) + 0.5) * cell_width;
  }
  double cell_centre_y(std::size_t row) const {
    return y_top - (static_cast<double>(row) + 0.5) * cell_height;
  }
};

class GriddedField {
 public:
  // `values` is row-major (row * columns + col), nodata as NaN. `crs_wkt` is the CRS as WKT
  // (empty: local metres, no CRS); `name` says what the values are ("bed elevation", ...).
  // Throws std::invalid_argument for an empty grid, non-positive cell sizes or a value count
  // that does not match the geometry.
  GriddedField(GridGeometry geometry, std::vector<double> values, std::string crs_wkt = {},
               std::string name = {});

  const GridGeometry& geometry() const { return geometry_; }
  const std::string& crs_wkt() const { return crs_wkt_; }
  const std::string& name() const { return name_; }
  const std::vector<double>& values() const { return values_; }
  double at(std::size_t col, std::size_t row) const {
    return values_[row * geometry_.columns + col];
  }

  // The same grid with every value multiplied by `factor` (a change of units).
  GriddedField scaled(double factor) const;

  // Bilinear interpolation between cell centres. Between the outermost centres and the outer
  // edges (and beyond) the value is held constant across the boundary (clamped), so any point
  // gets a value. At a cell centre the result is that cell's value exactly. NaN if a cell with
  // non-zero weight is nodata, or if x or y is not finite.
  double sample(double x_m, double y_m) const;

  // The exact derivative (d/dx, d/dy) of the surface sample() describes; zero in a direction
  // in which the point is clamped. On a line of cell centres, where the surface has a kink,
  // this is the derivative of the cell interval to the east (for x) or south (for y) of the
  // line, except on the last line, where it is that of the interval before it. Both
  // components are NaN where sample() is NaN or a cell the derivative depends on is nodata.
  std::array<double, 2> gradient(double x_m, double y_m) const;

  // True if (x, y) lies on the raster: within its outer edges (inclusive).
  bool covers(double x_m, double y_m) const;

  // The cell holding (x, y), as an index into values() (row * columns + col): a point on an
  // edge between cells belongs to the cell east or south of it, one on the raster's own east
  // or south edge to the cell inside. kNoCell off the raster (covers() false) or for a
  // non-finite point.
  static constexpr std::size_t kNoCell = static_cast<std::size_t>(-1);
  std::size_t cell_holding(double x_m, double y_m) const;
  // The value of that cell, read as flat across it: what a map of rates or soil properties
  // means, and what keeps a rain map's volume when finer cells sample it. NaN for kNoCell or
  // a nodata cell.
  double cell_value(double x_m, double y_m) const;

  // Nodata cells that sample() or gradient() would use somewhere in the rectangle
  // [x_min, x_max] x [y_min, y_max], with the first of them (in row-major order), so that an
  // error message can point at one.
  struct NodataReport {
    std::size_t count = 0;
    std::size_t col = 0, row = 0;  // the first nodata cell (valid when count > 0)
    double x_m = 0.0, y_m = 0.0;   // its centre
  };
  NodataReport nodata_in(double x_min, double x_max, double y_min, double y_max) const;

 private:
  // Where a point falls along one axis: the interval between the centres `first` and
  // `second` = first + 1 (second == first when the axis has one cell), the fraction `t` in
  // [0, 1] across it, and whether the point lies beyond the outermost centres (clamped).
  struct AxisStencil {
    std::size_t first = 0, second = 0;
    double t = 0.0;
    bool clamped = false;
  };
  static AxisStencil locate(double index, std::size_t count);
  AxisStencil locate_x(double x_m) const;
  AxisStencil locate_y(double y_m) const;

  GridGeometry geometry_;
  std::vector<double> values_;
  std::string crs_wkt_;
  std::string name_;
};

// The bed elevation z_b read from a raster; its gradient is the bilinear surface's own, so
// the bed-slope force is consistent with the elevation the particles stand on.
class RasterBed final : public swe::BedSource {
 public:
  explicit RasterBed(std::shared_ptr<const GriddedField> field);
  double elevation(double x_m, double y_m) const override { return field_->sample(x_m, y_m); }
  std::array<double, 2> gradient(double x_m, double y_m) const override {
    return field_->gradient(x_m, y_m);
  }
  const GriddedField& field() const { return *field_; }

 private:
  std::shared_ptr<const GriddedField> field_;
};

}  // namespace swemps::terrain
