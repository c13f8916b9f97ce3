#pragma once
// How hard the rain falls where: the depth each of a rain's cells receives over a step
// (docs/rain.md). One rate for every cell, following a series in time, or maps of the rate:
// one static map, or a sequence of them (a radar product, a forecast's grids).

#include <array>
#include <cstddef>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "swemps/boundaries/hydrograph.hpp"
#include "swemps/terrain/gridded_field.hpp"

namespace swemps::hydrology {

class RainRate {
 public:
  virtual ~RainRate() = default;
  // Fixes the cells the rain falls on (their centres, in the rain's order) before any
  // depth_over(). Throws std::invalid_argument naming the first cell the rate cannot give.
  virtual void bind(std::span<const std::array<double, 2>> centres) = 0;
  // The depth of rain (m) each bound cell receives over [t0, t1], written to depth_m (one per
  // cell); returns the largest of them (0: no rain anywhere in the step).
  virtual double depth_over(double t0_s, double t1_s, std::span<double> depth_m) const = 0;
  // The highest rate any bound cell ever receives (m/s), for the step limit.
  virtual double peak_m_s() const = 0;
};

// One rate over every cell: a series linear between its points (boundaries::Hydrograph, in
// m/s), integrated exactly over each step.
class UniformRainRate final : public RainRate {
 public:
  explicit UniformRainRate(boundaries::Hydrograph rate_m_s);
  void bind(std::span<const std::array<double, 2>> centres) override;
  double depth_over(double t0_s, double t1_s, std::span<double> depth_m) const override;
  double peak_m_s() const override { return peak_m_s_; }
  const boundaries::Hydrograph& series() const { return rate_; }

 private:
  boundaries::Hydrograph rate_;
  double peak_m_s_ = 0.0;
};

// Maps of the rate, each holding from its start until the next map's start, the last
// until `end_s` (+infinity: for ever, as a static map does). This is what a gridded rain
// product means: each grid is the mean rate over its interval. No rain falls before the
// first start or after end_s. A cell takes the value of the map cell holding its centre
// (terrain::GriddedField::cell_value), so rain cells finer than the map's receive the map's
// volume exactly.
class MappedRainRate final : public RainRate {
 public:
  struct Frame {
    double start_s = 0.0;
    std::shared_ptr<const terrain::GriddedField> rate;  // times `scale`: m/s
  };
  // At least one frame; starts finite and strictly increasing; every map on the same grid;
  // end_s after the last start; `scale` (the maps' unit in m/s) positive. Throws
  // std::invalid_argument otherwise.
  MappedRainRate(std::vector<Frame> frames, double end_s, double scale = 1.0);
  // Also throws for a cell off the maps, or one whose map cell is nodata or negative in any
  // frame, naming the cell's centre and the frame's start.
  void bind(std::span<const std::array<double, 2>> centres) override;
  double depth_over(double t0_s, double t1_s, std::span<double> depth_m) const override;
  double peak_m_s() const override { return peak_m_s_; }
  std::size_t frame_count() const { return frames_.size(); }
  double end_s() const { return end_s_; }

 private:
  std::vector<Frame> frames_;
  double end_s_ = 0.0;
  double scale_ = 1.0;
  std::vector<std::size_t> map_cell_;  // per rain cell: its cell in every map
  double peak_m_s_ = 0.0;
};

}  // namespace swemps::hydrology
