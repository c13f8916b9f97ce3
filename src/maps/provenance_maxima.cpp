#include "swemps/maps/provenance_maxima.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace swemps::maps {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The larger of a running maximum that may be NaN (no sample yet) and a value.
void raise(double& maximum, double value) {
  if (std::isnan(maximum) || value > maximum) maximum = value;
}
}  // namespace

ProvenanceMaxima::ProvenanceMaxima(std::size_t cells, std::size_t sources, bool ages,
                                   double wet_depth_m)
    : cells_(cells),
      sources_(sources),
      ages_(ages),
      wet_depth_m_(wet_depth_m),
      max_source_depth_(cells * sources, kNaN),
      max_source_share_(cells * sources, kNaN),
      max_mean_age_(ages ? cells : 0, kNaN) {}

void ProvenanceMaxima::update(double time_s, std::span<const double> depth,
                              std::span<const double> source_depth,
                              std::span<const double> entry_time) {
  if (depth.size() != cells_ || source_depth.size() != cells_ * sources_ ||
      entry_time.size() != (ages_ ? cells_ : 0)) {
    throw std::invalid_argument("ProvenanceMaxima::update: maps of other sizes than its own");
  }
  for (std::size_t k = 0; k < sources_; ++k) {
    for (std::size_t c = 0; c < cells_; ++c) {
      const std::size_t at = k * cells_ + c;
      raise(max_source_depth_[at], source_depth[at]);
      if (depth[c] > wet_depth_m_) raise(max_source_share_[at], source_depth[at] / depth[c]);
    }
  }
  for (std::size_t c = 0; c < max_mean_age_.size(); ++c) {
    if (depth[c] > wet_depth_m_) raise(max_mean_age_[c], time_s - entry_time[c]);
  }
}

std::vector<std::span<const double>> ProvenanceMaxima::maps() const {
  return {max_source_depth_, max_source_share_, max_mean_age_};
}

void ProvenanceMaxima::restore(std::vector<std::vector<double>> maps) {
  if (maps.size() != 3 || maps[0].size() != max_source_depth_.size() ||
      maps[1].size() != max_source_share_.size() || maps[2].size() != max_mean_age_.size()) {
    throw std::invalid_argument("ProvenanceMaxima::restore: maps of another scene");
  }
  max_source_depth_ = std::move(maps[0]);
  max_source_share_ = std::move(maps[1]);
  max_mean_age_ = std::move(maps[2]);
}

}  // namespace swemps::maps
