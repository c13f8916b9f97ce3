#pragma once
// Where the bed elevation z_b comes from. The solver only asks for z_b and its gradient at
// a point, so an analytic surface and a raster (read by the io module) are interchangeable.

#include <array>
#include <utility>
#include <vector>

namespace swemps::swe {

class BedSource {
 public:
  virtual ~BedSource() = default;
  virtual double elevation(double x_m, double y_m) const = 0;                // z_b, m
  virtual std::array<double, 2> gradient(double x_m, double y_m) const = 0;  // dz_b/dx, dz_b/dy
};

// z_b = elevation + slope . (x - origin): flat when the slope is zero.
class PlaneBed final : public BedSource {
 public:
  PlaneBed(double elevation_m, std::array<double, 2> slope, std::array<double, 2> origin_m)
      : elevation_(elevation_m), slope_(slope), origin_(origin_m) {}
  double elevation(double x, double y) const override {
    return elevation_ + slope_[0] * (x - origin_[0]) + slope_[1] * (y - origin_[1]);
  }
  std::array<double, 2> gradient(double, double) const override { return slope_; }

 private:
  double elevation_;
  std::array<double, 2> slope_, origin_;
};

// z_b(x) linear between given (x, z) points (x strictly increasing), constant beyond the
// first and last: a channel profile such as a flat reach followed by a beach.
class ProfileBed final : public BedSource {
 public:
  explicit ProfileBed(std::vector<std::array<double, 2>> points);
  double elevation(double x, double y) const override;
  std::array<double, 2> gradient(double x, double y) const override;

 private:
  // The segment containing x (clamped to the ends) and its slope.
  std::pair<std::size_t, double> segment(double x) const;
  std::vector<std::array<double, 2>> points_;
};

}  // namespace swemps::swe
