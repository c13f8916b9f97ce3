#pragma once
// Open domain edges: a particle that leaves the domain box (through a side no wall closes)
// is removed and its volume booked as outflow, so the volume balance still closes.

#include <cstdint>
#include <vector>

#include "swemps/swe/effect.hpp"

namespace swemps::boundaries {

struct Box {
  double x_min, x_max, y_min, y_max;  // m
};

class DomainOutflow final : public swe::Effect {
 public:
  explicit DomainOutflow(Box domain) : domain_(domain) {}
  std::string_view name() const override { return "domain outflow"; }
  swe::Stage stage() const override { return swe::Stage::topology; }
  void apply(swe::StepContext& context) override;
  std::string report() const override;
  void save_state(swe::StateWriter& out) const override;
  void restore_state(swe::StateReader& in) override;

  std::size_t removed_particles() const { return removed_; }

 private:
  Box domain_;
  std::vector<std::uint8_t> outside_;
  std::size_t removed_ = 0;
  double removed_m3_ = 0.0;
};

}  // namespace swemps::boundaries
