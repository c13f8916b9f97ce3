#include "swemps/maps/flood_statistics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace swemps::maps {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

void require_cells(std::span<const double> field, std::size_t cells, const char* name) {
  if (field.size() != cells) {
    throw std::invalid_argument(std::string("FloodStatistics::update: ") + name + " has " +
                                std::to_string(field.size()) + " values, expected " +
                                std::to_string(cells));
  }
}

}  // namespace

FloodStatistics::FloodStatistics(std::size_t cells, double wet_depth_m)
    : wet_depth_m_(wet_depth_m),
      last_time_s_(kNaN),
      max_depth_(cells, kNaN),
      max_speed_(cells, kNaN),
      max_hazard_(cells, kNaN),
      arrival_time_(cells, kNaN),
      inundation_duration_(cells, kNaN) {
  if (!std::isfinite(wet_depth_m) || wet_depth_m < 0.0) {
    throw std::invalid_argument("FloodStatistics: wet depth must be a finite value >= 0 m, got " +
                                std::to_string(wet_depth_m));
  }
}

std::vector<std::span<const double>> FloodStatistics::maps() const {
  return {max_depth_, max_speed_, max_hazard_, arrival_time_, inundation_duration_};
}

void FloodStatistics::restore(std::size_t samples, double last_time_s,
                              std::vector<std::vector<double>> maps) {
  if (maps.size() != 5) {
    throw std::invalid_argument("FloodStatistics::restore: " + std::to_string(maps.size()) +
                                " maps, expected 5");
  }
  for (const auto& m : maps) {
    if (m.size() != cells()) {
      throw std::invalid_argument("FloodStatistics::restore: a map of " + std::to_string(m.size()) +
                                  " values, expected " + std::to_string(cells()));
    }
  }
  samples_ = samples;
  last_time_s_ = last_time_s;
  max_depth_ = std::move(maps[0]);
  max_speed_ = std::move(maps[1]);
  max_hazard_ = std::move(maps[2]);
  arrival_time_ = std::move(maps[3]);
  inundation_duration_ = std::move(maps[4]);
}

void FloodStatistics::update(double time_s, std::span<const double> depth,
                             std::span<const double> u, std::span<const double> v) {
  const std::size_t n = cells();
  require_cells(depth, n, "depth");
  require_cells(u, n, "u");
  require_cells(v, n, "v");
  if (!std::isfinite(time_s) || (samples_ > 0 && !(time_s > last_time_s_))) {
    throw std::invalid_argument("FloodStatistics::update: sample time " + std::to_string(time_s) +
                                " s is not finite or not after the previous one (" +
                                std::to_string(last_time_s_) + " s)");
  }
  // Zero before the first sample: the first sample has no interval to be wet over.
  const double interval_s = samples_ > 0 ? time_s - last_time_s_ : 0.0;

  for (std::size_t i = 0; i < n; ++i) {
    const double h = depth[i];
    if (std::isnan(h)) continue;
    if (std::isnan(max_depth_[i])) {
      // First data for this cell: from here on "never" means 0, not "unknown".
      max_depth_[i] = h;
      max_speed_[i] = 0.0;
      max_hazard_[i] = 0.0;
      inundation_duration_[i] = 0.0;
    } else {
      max_depth_[i] = std::max(max_depth_[i], h);
    }
    if (!(h > wet_depth_m_)) continue;

    if (std::isnan(arrival_time_[i])) arrival_time_[i] = time_s;
    inundation_duration_[i] += interval_s;
    const double speed = std::hypot(u[i], v[i]);
    if (std::isfinite(speed)) {
      max_speed_[i] = std::max(max_speed_[i], speed);
      max_hazard_[i] = std::max(max_hazard_[i], h * speed);
    }
  }
  last_time_s_ = time_s;
  ++samples_;
}

}  // namespace swemps::maps
