#include "swemps/hydrology/rain_rate.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "swemps/hydrology/rain.hpp"

namespace swemps::hydrology {

namespace {

std::string at_point(const std::array<double, 2>& p) {
  std::ostringstream out;
  out << "(" << p[0] << ", " << p[1] << ")";
  return out.str();
}

bool same_grid(const terrain::GridGeometry& a, const terrain::GridGeometry& b) {
  return a.columns == b.columns && a.rows == b.rows && a.x_left == b.x_left && a.y_top == b.y_top &&
         a.cell_width == b.cell_width && a.cell_height == b.cell_height;
}

}  // namespace

UniformRainRate::UniformRainRate(boundaries::Hydrograph rate_m_s) : rate_(std::move(rate_m_s)) {
  for (const auto& point : rate_.points()) peak_m_s_ = std::max(peak_m_s_, point[1]);
}

void UniformRainRate::bind(std::span<const std::array<double, 2>> /*centres*/) {}

double UniformRainRate::depth_over(double t0_s, double t1_s, std::span<double> depth_m) const {
  const double depth = std::max(0.0, rate_.volume(t0_s, t1_s));
  std::fill(depth_m.begin(), depth_m.end(), depth);
  return depth_m.empty() ? 0.0 : depth;
}

MappedRainRate::MappedRainRate(std::vector<Frame> frames, double end_s, double scale)
    : frames_(std::move(frames)), end_s_(end_s), scale_(scale) {
  if (frames_.empty()) throw std::invalid_argument("rain maps: no map");
  if (!(scale_ > 0.0) || !std::isfinite(scale_)) {
    throw std::invalid_argument("rain maps: the scale must be a positive number");
  }
  for (std::size_t k = 0; k < frames_.size(); ++k) {
    const Frame& f = frames_[k];
    if (!f.rate) throw std::invalid_argument("rain maps: map " + std::to_string(k) + " absent");
    if (!std::isfinite(f.start_s) || (k > 0 && !(f.start_s > frames_[k - 1].start_s))) {
      throw std::invalid_argument("rain maps: the starts must be finite and increasing; map " +
                                  std::to_string(k) + " starts at " + std::to_string(f.start_s) +
                                  " s");
    }
    if (!same_grid(f.rate->geometry(), frames_.front().rate->geometry())) {
      throw std::invalid_argument("rain maps: map " + std::to_string(k) +
                                  " is not on the first map's grid");
    }
  }
  if (!(end_s_ > frames_.back().start_s)) {
    throw std::invalid_argument("rain maps: the last map must end after it starts");
  }
}

void MappedRainRate::bind(std::span<const std::array<double, 2>> centres) {
  const terrain::GriddedField& first = *frames_.front().rate;
  map_cell_.resize(centres.size());
  peak_m_s_ = 0.0;
  for (std::size_t c = 0; c < centres.size(); ++c) {
    const std::size_t cell = first.cell_holding(centres[c][0], centres[c][1]);
    if (cell == terrain::GriddedField::kNoCell) {
      throw std::invalid_argument("the rain map does not cover the rain cell at " +
                                  at_point(centres[c]));
    }
    map_cell_[c] = cell;
  }
  for (const Frame& f : frames_) {
    const auto& values = f.rate->values();
    for (std::size_t c = 0; c < centres.size(); ++c) {
      const double rate = values[map_cell_[c]] * scale_;
      if (!(rate >= 0.0) || !std::isfinite(rate)) {
        std::ostringstream what;
        what << "the rain map of " << f.start_s << " s has "
             << (std::isnan(rate)
                     ? std::string("no value (nodata)")
                     : "a rate of " + std::to_string(rate / kMetresPerSecondPerMmPerHour) + " mm/h")
             << " at the rain cell " << at_point(centres[c]) << "; rates must be >= 0 mm/h";
        throw std::invalid_argument(what.str());
      }
      peak_m_s_ = std::max(peak_m_s_, rate);
    }
  }
}

double MappedRainRate::depth_over(double t0_s, double t1_s, std::span<double> depth_m) const {
  std::fill(depth_m.begin(), depth_m.end(), 0.0);
  double deepest = 0.0;
  if (!(t1_s > t0_s)) return 0.0;
  // The first frame that ends after t0: frame k spans [start_k, start_{k+1}) (the last until
  // end_s).
  auto next_start = std::upper_bound(frames_.begin(), frames_.end(), t0_s,
                                     [](double t, const Frame& f) { return t < f.start_s; });
  std::size_t k = next_start == frames_.begin()
                      ? 0
                      : static_cast<std::size_t>(next_start - frames_.begin()) - 1;
  for (; k < frames_.size(); ++k) {
    const double start = frames_[k].start_s;
    const double end = k + 1 < frames_.size() ? frames_[k + 1].start_s : end_s_;
    if (start >= t1_s) break;
    const double overlap = std::min(end, t1_s) - std::max(start, t0_s);
    if (!(overlap > 0.0)) continue;
    const auto& values = frames_[k].rate->values();
    const double metres = scale_ * overlap;
    for (std::size_t c = 0; c < depth_m.size(); ++c) depth_m[c] += values[map_cell_[c]] * metres;
  }
  for (const double d : depth_m) deepest = std::max(deepest, d);
  return deepest;
}

}  // namespace swemps::hydrology
