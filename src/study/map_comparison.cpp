#include "swemps/study/map_comparison.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace swemps::study {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// One target interval's share of the source intervals along an axis: (source index, length
// of the overlap).
struct Overlap {
  std::size_t source = 0;
  double length = 0.0;
};

// For each target interval [start + k step, start + (k + 1) step] (k < count), the source
// intervals [source_start + i source_step, ...] (i < source_count) it overlaps and by how much.
// Overlaps shorter than a billionth of a target interval are round-off of aligned edges.
std::vector<std::vector<Overlap>> overlaps(double start, double step, std::size_t count,
                                           double source_start, double source_step,
                                           std::size_t source_count) {
  std::vector<std::vector<Overlap>> out(count);
  for (std::size_t k = 0; k < count; ++k) {
    const double lo = start + static_cast<double>(k) * step;
    const double hi = lo + step;
    const double first = std::floor((lo - source_start) / source_step);
    const double last = std::ceil((hi - source_start) / source_step);
    for (double i = std::max(first, 0.0); i < std::min(last, static_cast<double>(source_count));
         i += 1.0) {
      const double s_lo = source_start + i * source_step;
      const double length = std::min(hi, s_lo + source_step) - std::max(lo, s_lo);
      if (length > 1e-9 * step) out[k].push_back({static_cast<std::size_t>(i), length});
    }
  }
  return out;
}

}  // namespace

std::vector<double> area_average(const terrain::GriddedField& reference,
                                 const terrain::GridGeometry& cells) {
  const terrain::GridGeometry& source = reference.geometry();
  // Along y both grids count rows from the top edge down.
  const auto columns = overlaps(cells.x_left, cells.cell_width, cells.columns, source.x_left,
                                source.cell_width, source.columns);
  const auto rows = overlaps(-cells.y_top, cells.cell_height, cells.rows, -source.y_top,
                             source.cell_height, source.rows);
  const double cell_area = cells.cell_width * cells.cell_height;
  std::vector<double> out(cells.columns * cells.rows, kNaN);
  for (std::size_t row = 0; row < cells.rows; ++row) {
    for (std::size_t col = 0; col < cells.columns; ++col) {
      double covered = 0.0, sum = 0.0;
      for (const Overlap& r : rows[row]) {
        for (const Overlap& c : columns[col]) {
          const double area = r.length * c.length;
          const double v = reference.at(c.source, r.source);
          covered += area;
          if (v > 0.0) sum += area * v;  // NaN and negative: dry
        }
      }
      if (covered >= 0.5 * cell_area) out[row * cells.columns + col] = sum / covered;
    }
  }
  return out;
}

MaxDepthComparison compare_max_depth(std::span<const double> run, std::span<const double> reference,
                                     double wet_depth_m) {
  if (run.size() != reference.size()) {
    throw std::invalid_argument("compare_max_depth: maps of different sizes");
  }
  double abs_sum = 0.0, sum = 0.0;
  std::size_t either = 0, both = 0, within = 0;
  for (std::size_t i = 0; i < run.size(); ++i) {
    if (std::isnan(reference[i])) continue;
    const double r = std::isnan(run[i]) ? 0.0 : run[i];
    const bool run_wet = r > wet_depth_m, reference_wet = reference[i] > wet_depth_m;
    if (!run_wet && !reference_wet) continue;
    ++either;
    both += run_wet && reference_wet;
    const double d = r - reference[i];
    abs_sum += std::abs(d);
    sum += d;
    within += std::abs(d) <= 0.5;
  }
  MaxDepthComparison c;
  c.compared_cells = either;
  if (either == 0) {
    c.mean_abs_difference_m = c.bias_m = c.within_half_metre = c.critical_success_index = kNaN;
    return c;
  }
  const auto n = static_cast<double>(either);
  c.mean_abs_difference_m = abs_sum / n;
  c.bias_m = sum / n;
  c.within_half_metre = static_cast<double>(within) / n;
  c.critical_success_index = static_cast<double>(both) / n;
  return c;
}

SeriesPeak series_peak(std::span<const double> time_s, std::span<const double> values) {
  SeriesPeak peak{kNaN, kNaN};
  const std::size_t n = std::min(time_s.size(), values.size());
  for (std::size_t i = 0; i < n; ++i) {
    if (std::isnan(values[i])) continue;
    if (std::isnan(peak.value) || values[i] > peak.value) peak = {values[i], time_s[i]};
  }
  return peak;
}

}  // namespace swemps::study
