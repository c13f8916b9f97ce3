#pragma once
// The whole-run maxima of the provenance maps (docs/provenance.md): per source, the deepest its
// water stood in each cell and the largest share of the cell's water it held; and the largest
// mean age of a cell's water. Shares and ages count only where the cell is wet: a film's are
// noise. Taken at the flood statistics' samples, so that they hold every map written.

#include <cstddef>
#include <span>
#include <string>
#include <vector>

namespace swemps::maps {

// The maxima by the names a result's file gives them, which output.rasters and `swe-mps export`
// may ask for besides maps::summary_map_names(): max_source_depth and max_source_share hold one
// map per source.
inline const std::vector<std::string>& provenance_map_names() {
  static const std::vector<std::string> names{"max_source_depth", "max_source_share",
                                              "max_mean_age"};
  return names;
}
// The maps only a result with provenance sources has, one per source.
inline bool is_source_map(const std::string& name) {
  return name == "max_source_depth" || name == "max_source_share";
}

class ProvenanceMaxima {
 public:
  // `cells` map cells, `sources` sources (0: none), ages or not; `wet_depth_m` as the flood
  // statistics' (a cell deeper than this is wet).
  ProvenanceMaxima(std::size_t cells, std::size_t sources, bool ages, double wet_depth_m);

  // One sample: the depth, each source's depth (source k's map at [k * cells, (k + 1) * cells))
  // and the mean entry time of the water (s), at time_s. Spans empty where not kept.
  void update(double time_s, std::span<const double> depth, std::span<const double> source_depth,
              std::span<const double> entry_time);

  // NaN where no sample was wet (shares, age) or none was taken (depths: 0 once sampled).
  std::span<const double> max_source_depth() const { return max_source_depth_; }
  std::span<const double> max_source_share() const { return max_source_share_; }
  std::span<const double> max_mean_age() const { return max_mean_age_; }
  std::size_t sources() const { return sources_; }
  bool ages() const { return ages_; }
  bool kept() const { return sources_ > 0 || ages_; }  // anything at all

  // For a checkpoint: every map, in the order restore() takes them.
  std::vector<std::span<const double>> maps() const;
  // Throws std::invalid_argument unless the maps are as many and as long as maps() gives.
  void restore(std::vector<std::vector<double>> maps);

 private:
  std::size_t cells_, sources_;
  bool ages_;
  double wet_depth_m_;
  std::vector<double> max_source_depth_, max_source_share_, max_mean_age_;
};

}  // namespace swemps::maps
