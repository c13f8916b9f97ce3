#pragma once
// A discharge hydrograph Q(t): the rate at which an inflow boundary lets water in.
//
// Given at points (t, Q) and linear between them. Before the first point Q is held at the
// first value and after the last point at the last value: a run longer than its hydrograph
// keeps the final discharge rather than stopping the inflow abruptly (end a hydrograph with
// a point at Q = 0 to stop it). A single point is a constant discharge.

#include <array>
#include <cstddef>
#include <span>
#include <vector>

namespace swemps::boundaries {

class Hydrograph {
 public:
  // Points (time s, discharge m^3/s): at least one; times finite and strictly increasing;
  // discharges finite and >= 0. Throws std::invalid_argument naming the first wrong point.
  explicit Hydrograph(std::vector<std::array<double, 2>> points);

  double discharge(double t_s) const;  // Q(t), m^3/s
  // The integral of Q from t0 to t1 (m^3), exact for the piecewise-linear Q (one trapezoid per
  // piece); negative when t1 < t0, as integrals are.
  double volume(double t0_s, double t1_s) const;

  std::span<const std::array<double, 2>> points() const { return points_; }

 private:
  // Q on linear piece k (between points k and k + 1) at a time inside it; the points' own
  // values at its ends, so integrals over whole pieces use the given numbers unrounded.
  double on_piece(std::size_t k, double t_s) const;
  std::vector<std::array<double, 2>> points_;
};

}  // namespace swemps::boundaries
