#pragma once
// Outflow through lines: a fluid particle whose path this step touches one of the given
// polylines leaves the domain there. It is removed and its volume booked in
// VolumeLedger::removed_m3, so the volume balance still closes.
//
// The path is the straight segment from the particle's position before this step's move
// (StepContext::previous_x/y) to its position now. Touching is the intersection of closed
// segments: crossing in either direction, ending (or starting) exactly on the line, passing
// through a vertex or sliding along the line all count; moving beside it or stopping short of
// it do not. The test uses only orientation signs, so the exactly degenerate cases (ending on
// the line, passing through a vertex) are decided exactly when the coordinates are exact.
// Particles with a non-finite position are left alone: a broken particle must reach the
// finiteness check of the next step, not vanish as outflow. Particles an earlier topology
// effect added this step (an inflow) have no earlier position and are tested as points.
//
// Order: an effect that removes particles invalidates previous_x/y for the effects after it,
// so this effect must come before every other topology effect that removes particles (domain
// outflow, ...). Effects that only add particles may come before it.

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "swemps/swe/effect.hpp"

namespace swemps::boundaries {

using Polyline = std::vector<std::array<double, 2>>;  // m, at least two points

class OutflowLines final : public swe::Effect {
 public:
  // Throws std::invalid_argument for no polylines, a polyline of fewer than two points, a
  // non-finite point or a segment of zero length, naming the polyline and the point.
  explicit OutflowLines(std::vector<Polyline> polylines);

  std::string_view name() const override { return "outflow lines"; }
  swe::Stage stage() const override { return swe::Stage::topology; }
  // Throws std::logic_error if the previous positions are more than the fluid particles
  // (an effect before this one removed particles).
  void apply(swe::StepContext& context) override;
  std::string report() const override;
  void save_state(swe::StateWriter& out) const override;
  void restore_state(swe::StateReader& in) override;

  std::size_t removed_particles() const { return removed_; }
  double volume_removed() const { return removed_m3_; }  // m^3, as booked in the ledger

  // True if the closed path p0-p1 and the closed segment a-b have a point in common.
  static bool touches(std::array<double, 2> a, std::array<double, 2> b, std::array<double, 2> p0,
                      std::array<double, 2> p1);

 private:
  struct Segment {
    std::array<double, 2> a, b;
    double x_min, x_max, y_min, y_max;  // bounding box, to skip most pairs cheaply
  };
  bool path_touches_any(std::array<double, 2> p0, std::array<double, 2> p1) const;

  std::vector<Segment> segments_;
  std::vector<std::uint8_t> leaving_;
  std::size_t removed_ = 0;
  double removed_m3_ = 0.0;
};

}  // namespace swemps::boundaries
