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

std::vector<double> sorted_thresholds(const StatisticsSettings& s) {
  if (!std::isfinite(s.wet_depth_m) || s.wet_depth_m < 0.0) {
    throw std::invalid_argument("FloodStatistics: wet depth must be a finite value >= 0 m, got " +
                                std::to_string(s.wet_depth_m));
  }
  std::vector<double> further = s.depth_thresholds_m;
  for (const double t : further) {
    if (!std::isfinite(t) || !(t > s.wet_depth_m)) {
      throw std::invalid_argument("FloodStatistics: a depth threshold of " + std::to_string(t) +
                                  " m is not above the wet depth (" +
                                  std::to_string(s.wet_depth_m) + " m)");
    }
  }
  std::sort(further.begin(), further.end());
  further.erase(std::unique(further.begin(), further.end()), further.end());
  further.insert(further.begin(), s.wet_depth_m);
  return further;
}

}  // namespace

FloodStatistics::FloodStatistics(std::size_t cells, StatisticsSettings settings,
                                 std::vector<double> bed_m)
    : thresholds_m_(sorted_thresholds(settings)),
      land_use_(settings.land_use),
      tsunami_(settings.tsunami),
      bed_m_(std::move(bed_m)),
      last_time_s_(kNaN) {
  if (!bed_m_.empty() && bed_m_.size() != cells) {
    throw std::invalid_argument("FloodStatistics: a bed of " + std::to_string(bed_m_.size()) +
                                " cells for " + std::to_string(cells) + " cells");
  }
  if (tsunami_ && (!std::isfinite(tsunami_->still_level_m) ||
                   !std::isfinite(tsunami_->arrival_rise_m) || !(tsunami_->arrival_rise_m > 0.0))) {
    throw std::invalid_argument("FloodStatistics: the still level (" +
                                std::to_string(tsunami_->still_level_m) +
                                " m) must be finite and the arrival rise (" +
                                std::to_string(tsunami_->arrival_rise_m) + " m) above 0");
  }
  arrival_.resize(thresholds_m_.size());
  duration_.resize(thresholds_m_.size());
  for (auto* map : all_maps()) map->assign(cells, kNaN);
}

std::vector<std::vector<double>*> FloodStatistics::all_maps() {
  std::vector<std::vector<double>*> out{
      &max_depth_,       &time_of_max_depth_, &max_surface_,       &max_speed_,
      &max_depth_speed_, &max_depth_speed2_,  &max_hazard_rating_, &max_hazard_class_};
  for (std::size_t j = 0; j < thresholds_m_.size(); ++j) {
    out.push_back(&arrival_[j]);
    out.push_back(&duration_[j]);
  }
  if (tsunami_) out.push_back(&rise_arrival_);
  return out;
}

std::vector<std::span<const double>> FloodStatistics::maps() const {
  std::vector<std::span<const double>> out;
  for (const auto* map : const_cast<FloodStatistics*>(this)->all_maps()) out.emplace_back(*map);
  return out;
}

std::vector<double> FloodStatistics::max_surface_rise() const {
  if (!tsunami_) return {};
  std::vector<double> rise(max_surface_.size());
  for (std::size_t i = 0; i < rise.size(); ++i) rise[i] = max_surface_[i] - tsunami_->still_level_m;
  return rise;
}

void FloodStatistics::restore(std::size_t samples, double last_time_s,
                              std::vector<std::vector<double>> maps) {
  auto targets = all_maps();
  if (maps.size() != targets.size()) {
    throw std::invalid_argument("FloodStatistics::restore: " + std::to_string(maps.size()) +
                                " maps, expected " + std::to_string(targets.size()));
  }
  for (const auto& m : maps) {
    if (m.size() != cells()) {
      throw std::invalid_argument("FloodStatistics::restore: a map of " + std::to_string(m.size()) +
                                  " values, expected " + std::to_string(cells()));
    }
  }
  samples_ = samples;
  last_time_s_ = last_time_s;
  for (std::size_t k = 0; k < targets.size(); ++k) *targets[k] = std::move(maps[k]);
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
  const double wet_depth_m = thresholds_m_.front();
  const std::size_t thresholds = thresholds_m_.size();

  for (std::size_t i = 0; i < n; ++i) {
    const double h = depth[i];
    // No data; an infinite depth (a broken state, which the run refuses) is none either.
    if (!std::isfinite(h)) continue;
    const bool first_data = std::isnan(max_depth_[i]);
    if (first_data) {
      // From here on "never" means 0, not "unknown".
      max_speed_[i] = 0.0;
      max_depth_speed_[i] = 0.0;
      max_depth_speed2_[i] = 0.0;
      max_hazard_rating_[i] = 0.0;
      max_hazard_class_[i] = 0.0;
      for (std::size_t j = 0; j < thresholds; ++j) duration_[j][i] = 0.0;
    }
    const bool deeper = first_data || h > max_depth_[i];
    if (deeper) max_depth_[i] = h;
    if (!(h > wet_depth_m)) continue;

    // The first sample reaching the largest depth, among wet ones (see the header).
    if (deeper) time_of_max_depth_[i] = time_s;
    const double surface_m = h + (bed_m_.empty() ? 0.0 : bed_m_[i]);
    if (!(max_surface_[i] >= surface_m)) max_surface_[i] = surface_m;  // NaN at first
    if (tsunami_ && std::isnan(rise_arrival_[i]) &&
        surface_m > tsunami_->still_level_m + tsunami_->arrival_rise_m) {
      rise_arrival_[i] = time_s;
    }
    for (std::size_t j = 0; j < thresholds && h > thresholds_m_[j]; ++j) {
      if (std::isnan(arrival_[j][i])) arrival_[j][i] = time_s;
      duration_[j][i] += interval_s;
    }
    const double speed = std::hypot(u[i], v[i]);
    if (!std::isfinite(speed)) continue;
    max_speed_[i] = std::max(max_speed_[i], speed);
    max_depth_speed_[i] = std::max(max_depth_speed_[i], h * speed);
    max_depth_speed2_[i] = std::max(max_depth_speed2_[i], h * speed * speed);
    max_hazard_rating_[i] = std::max(max_hazard_rating_[i], uk_hazard_rating(h, speed, land_use_));
    max_hazard_class_[i] =
        std::max(max_hazard_class_[i], static_cast<double>(aidr_hazard(h, speed)));
  }
  last_time_s_ = time_s;
  ++samples_;
}

}  // namespace swemps::maps
