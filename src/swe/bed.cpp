#include "swemps/swe/bed.hpp"

#include <algorithm>
#include <stdexcept>

namespace swemps::swe {

ProfileBed::ProfileBed(std::vector<std::array<double, 2>> points) : points_(std::move(points)) {
  if (points_.size() < 2) throw std::invalid_argument("bed profile: fewer than 2 points");
  for (std::size_t k = 1; k < points_.size(); ++k) {
    if (!(points_[k][0] > points_[k - 1][0])) {
      throw std::invalid_argument("bed profile: x must increase strictly");
    }
  }
}

std::pair<std::size_t, double> ProfileBed::segment(double x) const {
  // Index k of the segment [x_k, x_k+1] holding x; beyond the ends the bed is level.
  if (x <= points_.front()[0] || x >= points_.back()[0]) {
    return {x <= points_.front()[0] ? 0 : points_.size() - 2, 0.0};
  }
  const auto it = std::upper_bound(points_.begin(), points_.end(), x,
                                   [](double value, const auto& p) { return value < p[0]; });
  const std::size_t k = static_cast<std::size_t>(it - points_.begin()) - 1;
  const double slope = (points_[k + 1][1] - points_[k][1]) / (points_[k + 1][0] - points_[k][0]);
  return {k, slope};
}

double ProfileBed::elevation(double x, double) const {
  if (x <= points_.front()[0]) return points_.front()[1];
  if (x >= points_.back()[0]) return points_.back()[1];
  const auto [k, slope] = segment(x);
  return points_[k][1] + slope * (x - points_[k][0]);
}

std::array<double, 2> ProfileBed::gradient(double x, double) const {
  return {segment(x).second, 0.0};
}

}  // namespace swemps::swe
