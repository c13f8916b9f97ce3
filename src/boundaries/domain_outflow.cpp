#include "swemps/boundaries/domain_outflow.hpp"

#include <string>

#include "swemps/neighbors/parallel.hpp"

namespace swemps::boundaries {

void DomainOutflow::apply(swe::StepContext& context) {
  auto& p = context.particles;
  const std::size_t n = p.fluid_count();
  outside_.assign(n, 0);
  // Flagged in parallel, counted and summed in index order (so the booked volume is the same
  // for any number of threads). Written so that a NaN position counts as inside: a broken
  // particle must reach the finiteness check of the next step, not vanish as outflow.
  parallel_for(n, [&](std::size_t i) {
    outside_[i] = p.x[i] < domain_.x_min || p.x[i] > domain_.x_max || p.y[i] < domain_.y_min ||
                  p.y[i] > domain_.y_max;
  });
  std::size_t count = 0;
  double volume = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!outside_[i]) continue;
    volume += p.volume[i];
    ++count;
  }
  if (count == 0) return;
  p.remove(outside_);
  context.ledger.removed_m3 += volume;
  removed_ += count;
  removed_m3_ += volume;
}

std::string DomainOutflow::report() const {
  return std::to_string(removed_) + " particles left the domain, " + std::to_string(removed_m3_) +
         " m3";
}

}  // namespace swemps::boundaries
