#include "swemps/boundaries/domain_outflow.hpp"

#include <string>

#include "swemps/boundaries/particle_removal.hpp"
#include "swemps/neighbors/parallel.hpp"

namespace swemps::boundaries {

void DomainOutflow::apply(swe::StepContext& context) {
  auto& p = context.particles;
  const std::size_t n = p.fluid_count();
  outside_.assign(n, 0);
  // Flagged in parallel. Written so that a NaN position counts as inside: a broken particle
  // must reach the finiteness check of the next step, not vanish as outflow.
  parallel_for(n, [&](std::size_t i) {
    outside_[i] = p.x[i] < domain_.x_min || p.x[i] > domain_.x_max || p.y[i] < domain_.y_min ||
                  p.y[i] > domain_.y_max;
  });
  const Removal removal = remove_flagged(p, outside_, context.ledger);
  removed_ += removal.particles;
  removed_m3_ += removal.volume_m3;
}

std::string DomainOutflow::report() const {
  return std::to_string(removed_) + " particles left the domain, " + std::to_string(removed_m3_) +
         " m3";
}

void DomainOutflow::save_state(swe::StateWriter& out) const {
  out.count(removed_);
  out.number(removed_m3_);
}

void DomainOutflow::restore_state(swe::StateReader& in) {
  removed_ = in.count();
  removed_m3_ = in.number();
}

}  // namespace swemps::boundaries
