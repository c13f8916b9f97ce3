#pragma once
// Whole-run flood statistics per grid cell (the envelopes of a run), accumulated from samples
// of the gridded depth and velocity: how deep and how high the water got, how fast it flowed,
// how hazardous it was, when it arrived and how long it stayed. A shallow-water run samples
// every step, so that a peak between two output times is not missed. Pure arithmetic on spans;
// writing the result is up to io.
//
// Rules, per cell, over the samples t_0 < t_1 < ... given to update():
// - A sample has data where its depth is finite; samples without data are skipped.
// - The cell is wet at sample k when depth_k > wet_depth (strictly); it is above threshold j
//   when depth_k > threshold_j. Threshold 0 is the wet depth itself.
// - max_depth: the largest depth of any sample with data.
// - time_of_max_depth: t_k of the first sample at which max_depth was reached; NaN where the
//   cell was never wet (the largest depth of a film is no event).
// - max_surface_elevation: the largest bed + depth over wet samples; NaN where never wet.
// - max_speed = max |(u, v)|, max_depth_speed = max d |(u, v)|, max_depth_speed2 =
//   max d |(u, v)|^2, max_hazard_rating = max HR(d, |(u, v)|) (hazard.hpp) and
//   max_hazard_class = max H(d, |(u, v)|) (AIDR H1-H6 as 1-6), over wet samples with finite u
//   and v only: velocities gridded from a film thinner than the wet depth are noise, and would
//   make the map of the flood edge meaningless. 0 where the cell had data but was never wet.
//   The hazard of each sample is that of the depth and speed at the same time; its maximum
//   over the run is not the hazard of max_depth and max_speed, which may come at different
//   times (docs/outputs.md).
// - arrival_time(j): t_k of the first sample at which the cell is above threshold j; NaN where
//   never.
// - duration_above(j): a cell above threshold j at sample k counts as above it over
//   (t_{k-1}, t_k], so the duration is the sum of t_k - t_{k-1} over those samples k >= 1;
//   the first sample counts nothing, having no interval before it. 0 where never above.
// Every map is NaN where the cell never had data. A cell is rated (flooded, in the hazard class
// maps) when max_hazard_class is 1 or more: it had a wet sample with a velocity.
//
// With tsunami levels (a still level z_0 and an arrival rise r), two maps more:
// - max_surface_rise: max_surface_elevation - z_0 (NaN where never wet): how high the water
//   stood above the sea at rest, offshore the wave's amplitude, on land the flow's height above
//   the still sea.
// - rise_arrival_time: t_k of the first wet sample with bed + depth_k > z_0 + r; NaN where
//   never. On land above z_0 + r that is the first wet sample.

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "swemps/maps/hazard.hpp"

namespace swemps::maps {

// The whole-run maps of a result by the names its file gives them: the statistics below, the
// hazard classes made from them, and the bed. arrival_time and inundation_duration hold one
// map per depth threshold.
inline const std::vector<std::string>& summary_map_names() {
  static const std::vector<std::string> names{
      "max_depth",           "time_of_max_depth",   "max_surface_elevation", "max_speed",
      "max_depth_speed",     "max_depth_speed2",    "max_hazard_rating",     "arrival_time",
      "inundation_duration", "hazard_class_uk",     "hazard_class_aidr",     "bed_elevation",
      "max_surface_rise",    "tsunami_arrival_time"};
  return names;
}

// The maps only a result with tsunami levels has.
inline bool is_tsunami_map(const std::string& name) {
  return name == "max_surface_rise" || name == "tsunami_arrival_time";
}

// The sea's level at rest, which a tsunami's rise is measured from, and how far above it the
// surface must rise for the wave to have arrived.
struct TsunamiLevels {
  double still_level_m = 0.0;
  double arrival_rise_m = 0.01;  // > 0
};

struct StatisticsSettings {
  double wet_depth_m = 0.01;  // >= 0: the depth a cell must exceed to count as wet
  // Further depths to time arrival and duration at, each above the wet depth; any order.
  std::vector<double> depth_thresholds_m;
  LandUse land_use = LandUse::urban;  // the debris factor of the hazard rating
  std::optional<TsunamiLevels> tsunami;  // absent: no tsunami maps
};

class FloodStatistics {
 public:
  // `cells` grid cells; `bed_m`: the bed elevation of each cell (max_surface_elevation), or
  // empty for a flat bed at z = 0. Throws std::invalid_argument for a negative or non-finite
  // wet depth, a threshold not above it, a bed of another size, or tsunami levels that are not
  // finite or an arrival rise not above 0.
  FloodStatistics(std::size_t cells, StatisticsSettings settings, std::vector<double> bed_m = {});

  // One sample of the gridded fields at `time_s`, each span `cells` long. Times must be
  // strictly increasing; throws std::invalid_argument otherwise or on a size mismatch,
  // leaving the statistics unchanged.
  void update(double time_s, std::span<const double> depth, std::span<const double> u,
              std::span<const double> v);

  std::span<const double> max_depth() const { return max_depth_; }                  // m
  std::span<const double> time_of_max_depth() const { return time_of_max_depth_; }  // s
  std::span<const double> max_surface_elevation() const { return max_surface_; }    // m
  std::span<const double> max_speed() const { return max_speed_; }                  // m/s
  std::span<const double> max_depth_speed() const { return max_depth_speed_; }      // m^2/s
  std::span<const double> max_depth_speed2() const { return max_depth_speed2_; }    // m^3/s^2
  std::span<const double> max_hazard_rating() const { return max_hazard_rating_; }  // HR
  std::span<const double> max_hazard_class() const { return max_hazard_class_; }    // 1-6
  // Threshold j (thresholds()[j]); j = 0 is the wet depth.
  std::span<const double> arrival_time(std::size_t j = 0) const { return arrival_[j]; }     // s
  std::span<const double> duration_above(std::size_t j = 0) const { return duration_[j]; }  // s
  // With tsunami levels only (empty otherwise).
  std::vector<double> max_surface_rise() const;                                // m
  std::span<const double> rise_arrival_time() const { return rise_arrival_; }  // s
  const std::optional<TsunamiLevels>& tsunami() const { return tsunami_; }

  // The wet depth, then the further thresholds in ascending order.
  const std::vector<double>& thresholds() const { return thresholds_m_; }
  LandUse land_use() const { return land_use_; }

  // Every map (those above in their order, then arrival_time(j), duration_above(j) for each
  // j, then rise_arrival_time() with tsunami levels), and restore() of them: a run restarted from a
  // checkpoint goes on with the statistics of the samples before it. restore() takes the maps, the
  // sample count and last_time() as they were; throws std::invalid_argument (leaving the statistics
  // unchanged) unless there are as many maps of cells() values as maps() gives.
  std::vector<std::span<const double>> maps() const;
  void restore(std::size_t samples, double last_time_s, std::vector<std::vector<double>> maps);

  std::size_t cells() const { return max_depth_.size(); }
  double wet_depth() const { return thresholds_m_.front(); }
  std::size_t samples() const { return samples_; }
  double last_time() const { return last_time_s_; }  // NaN before the first sample

 private:
  std::vector<std::vector<double>*> all_maps();

  std::vector<double> thresholds_m_;
  LandUse land_use_;
  std::optional<TsunamiLevels> tsunami_;
  std::vector<double> bed_m_;
  std::size_t samples_ = 0;
  double last_time_s_;
  std::vector<double> max_depth_, time_of_max_depth_, max_surface_, max_speed_, max_depth_speed_,
      max_depth_speed2_, max_hazard_rating_, max_hazard_class_;
  std::vector<std::vector<double>> arrival_, duration_;  // per threshold
  std::vector<double> rise_arrival_;                     // with tsunami levels only
};

}  // namespace swemps::maps
