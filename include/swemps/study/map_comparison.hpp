#pragma once
// A run's flood map against a reference map: the figures flood modellers compare models by
// (maximum depth differences over the wet area, the critical success index of the wet area,
// gauge peaks). Pure arithmetic on grids of numbers: reading the maps is the io module's job,
// running the runs the study command's.

#include <cstddef>
#include <span>
#include <vector>

#include "swemps/terrain/gridded_field.hpp"

namespace swemps::study {

// The reference's values averaged over each cell of `cells` (north-up, row-major as
// GriddedField), weighted by the area each reference cell shares with it: the way a finer
// grid model's map is brought onto coarser output cells. A reference cell without data (NaN)
// counts as dry (0 m), as a grid model writes no depth where no water came; negative values
// count as 0 too. A cell less than half covered by the reference's cells is NaN: there is
// nothing to compare it with. The reference must be in the same CRS as `cells`.
std::vector<double> area_average(const terrain::GriddedField& reference,
                                 const terrain::GridGeometry& cells);

// The maximum depths of a run and a reference on the same cells, compared over the cells wet
// (deeper than wet_depth_m) in either map; cells where the reference is NaN are left out, and
// a NaN in the run reads as dry.
struct MaxDepthComparison {
  double mean_abs_difference_m = 0.0;  // mean |run - reference|
  double bias_m = 0.0;                 // mean (run - reference)
  double within_half_metre = 0.0;      // share of the cells with |run - reference| <= 0.5 m
  // Wet in both / wet in either: 1 for the same wet area, 0 for disjoint ones.
  double critical_success_index = 0.0;
  std::size_t compared_cells = 0;  // wet in either; the figures above are NaN when 0
};
MaxDepthComparison compare_max_depth(std::span<const double> run, std::span<const double> reference,
                                     double wet_depth_m);

// The highest value of a series and the first time it is reached; NaN values are skipped.
// Both NaN for a series without a number.
struct SeriesPeak {
  double value = 0.0;
  double time_s = 0.0;
};
SeriesPeak series_peak(std::span<const double> time_s, std::span<const double> values);

}  // namespace swemps::study
