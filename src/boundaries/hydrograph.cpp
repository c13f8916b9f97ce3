#include "swemps/boundaries/hydrograph.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace swemps::boundaries {

namespace {

[[noreturn]] void reject(std::size_t index, const std::array<double, 2>& point,
                         const std::string& problem) {
  std::ostringstream msg;
  msg << "hydrograph point " << index + 1 << " (t = " << point[0] << " s, Q = " << point[1]
      << " m3/s): " << problem;
  throw std::invalid_argument(msg.str());
}

}  // namespace

Hydrograph::Hydrograph(std::vector<std::array<double, 2>> points) : points_(std::move(points)) {
  if (points_.empty()) throw std::invalid_argument("hydrograph: no points");
  for (std::size_t k = 0; k < points_.size(); ++k) {
    const auto& p = points_[k];
    if (!std::isfinite(p[0])) reject(k, p, "time is not a finite number");
    if (!std::isfinite(p[1])) reject(k, p, "discharge is not a finite number");
    if (p[1] < 0.0) reject(k, p, "discharge is negative");
    if (k > 0 && !(p[0] > points_[k - 1][0])) {
      std::ostringstream problem;
      problem << "time is not after the previous point's " << points_[k - 1][0] << " s";
      reject(k, p, problem.str());
    }
  }
}

double Hydrograph::on_piece(std::size_t k, double t) const {
  const auto& a = points_[k];
  const auto& b = points_[k + 1];
  if (t <= a[0]) return a[1];
  if (t >= b[0]) return b[1];
  return a[1] + (b[1] - a[1]) * ((t - a[0]) / (b[0] - a[0]));
}

double Hydrograph::discharge(double t) const {
  if (t <= points_.front()[0]) return points_.front()[1];
  if (t >= points_.back()[0]) return points_.back()[1];
  // The piece whose end is the first point after t.
  const auto after = std::upper_bound(points_.begin(), points_.end(), t,
                                      [](double s, const auto& p) { return s < p[0]; });
  return on_piece(static_cast<std::size_t>(after - points_.begin()) - 1, t);
}

double Hydrograph::volume(double t0, double t1) const {
  if (t1 < t0) return -volume(t1, t0);
  const auto& first = points_.front();
  const auto& last = points_.back();
  double total = 0.0;
  if (t0 < first[0]) total += first[1] * (std::min(t1, first[0]) - t0);  // held before the start
  // Linear pieces overlapping [t0, t1], from the one holding t0 (or the first).
  const auto after = std::upper_bound(points_.begin(), points_.end(), t0,
                                      [](double s, const auto& p) { return s < p[0]; });
  std::size_t k =
      after == points_.begin() ? 0 : static_cast<std::size_t>(after - points_.begin()) - 1;
  for (; k + 1 < points_.size() && points_[k][0] < t1; ++k) {
    const double lo = std::max(t0, points_[k][0]);
    const double hi = std::min(t1, points_[k + 1][0]);
    if (hi > lo) total += 0.5 * (hi - lo) * (on_piece(k, lo) + on_piece(k, hi));
  }
  if (t1 > last[0]) total += last[1] * (t1 - std::max(t0, last[0]));  // held after the end
  return total;
}

}  // namespace swemps::boundaries
