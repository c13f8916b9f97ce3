#pragma once
// Whole-run flood statistics per grid cell, accumulated from samples of the gridded depth
// and velocity: how deep the water got, how fast it flowed, how hazardous it was, when it
// arrived and how long it stayed. Pure arithmetic on spans; writing the result is up to io.
//
// Rules, per cell, over the samples t_0 < t_1 < ... given to update():
// - A sample has data where its depth is not NaN; samples without data are skipped.
// - The cell is wet at sample k when depth_k > wet_depth (strictly).
// - max_depth: the largest depth of any sample with data.
// - max_speed = max |(u, v)| and max_hazard = max depth * |(u, v)|, over wet samples with
//   finite u and v only: velocities gridded from a film thinner than the threshold are
//   noise, and would make the hazard map of the flood edge meaningless. 0 where the cell
//   had data but was never wet.
// - arrival_time: t_k of the first sample at which the cell is wet; NaN where never wet.
// - inundation_duration: a cell wet at sample k counts as wet over (t_{k-1}, t_k], so the
//   duration is the sum of t_k - t_{k-1} over the wet samples k >= 1; the first sample
//   counts nothing, having no interval before it. 0 where never wet.
// Every map is NaN where the cell never had data.

#include <cstddef>
#include <span>
#include <vector>

namespace swemps::maps {

class FloodStatistics {
 public:
  // `cells` grid cells; `wet_depth_m` >= 0 is the depth a cell must exceed to count as wet.
  // Throws std::invalid_argument for a negative or non-finite threshold.
  FloodStatistics(std::size_t cells, double wet_depth_m);

  // One sample of the gridded fields at `time_s`, each span `cells` long. Times must be
  // strictly increasing; throws std::invalid_argument otherwise or on a size mismatch,
  // leaving the statistics unchanged.
  void update(double time_s, std::span<const double> depth, std::span<const double> u,
              std::span<const double> v);

  std::span<const double> max_depth() const { return max_depth_; }                      // m
  std::span<const double> max_speed() const { return max_speed_; }                      // m/s
  std::span<const double> max_hazard() const { return max_hazard_; }                    // m^2/s
  std::span<const double> arrival_time() const { return arrival_time_; }                // s
  std::span<const double> inundation_duration() const { return inundation_duration_; }  // s

  // The five maps in the order above, and restore() of them: a run restarted from a
  // checkpoint goes on with the statistics of the samples before it. restore() takes the maps,
  // the sample count and last_time() as they were; throws std::invalid_argument (leaving the
  // statistics unchanged) unless there are five maps of cells() values.
  std::vector<std::span<const double>> maps() const;
  void restore(std::size_t samples, double last_time_s, std::vector<std::vector<double>> maps);

  std::size_t cells() const { return max_depth_.size(); }
  double wet_depth() const { return wet_depth_m_; }
  std::size_t samples() const { return samples_; }
  double last_time() const { return last_time_s_; }  // NaN before the first sample

 private:
  double wet_depth_m_;
  std::size_t samples_ = 0;
  double last_time_s_;
  std::vector<double> max_depth_, max_speed_, max_hazard_, arrival_time_, inundation_duration_;
};

}  // namespace swemps::maps
