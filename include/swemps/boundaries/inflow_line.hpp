#pragma once
// Inflow through a line: water enters the domain at the rate a discharge hydrograph gives.
//
// Picture the water that has crossed the line as a strip moving into the domain at the inflow
// velocity u_in = q / h_in, where q = Q / L is the discharge per metre of line and h_in the
// inflow depth. Each time the strip has advanced one particle spacing l, the water that
// crossed during that advance becomes a row of particles, one per slot, with depth h_in,
// velocity u_in along the entry direction and an equal share of the row's volume. So the
// rows leave the line one spacing apart and each particle carries about h_in l^2 whatever Q
// and dt do: rows of uniform particles, not a column of water dropped at the line.
//
// Each step [t, t + dt]:
//  - the exact hydrograph volume dV of the step joins the pending (crossed, not yet in a row)
//    water; its mean discharge dV / dt sets h_in (when not given: the critical depth of the
//    unit discharge, h_c = (q^2 / g)^(1/3), so that the inflow neither ponds nor shoots) and
//    u_in, and the strip advances by u_in dt;
//  - when the strip has advanced l (or k l: several rows in one step, which only a step long
//    against l / u_in brings, e.g. before inflow particles limit the step by eq 13), the
//    water that crossed after the newest row was complete stays pending and the rest becomes
//    the k rows; the newest row is centred l/2 + (the distance the strip moved since it was
//    complete) inside the line, each older one a spacing further: where they would be had
//    each been emitted the moment it was complete and moved on at u_in;
//  - the created volume is booked in VolumeLedger::added_m3, so that added + pending equals
//    the integral of Q since the first step, to round-off.
//
// The strip starts empty: the first row appears once it has advanced l, so a hydrograph rising
// from zero does not begin with a row of near-empty particles. Q = 0 lets nothing in and
// leaves the strip where it is; when the hydrograph ends at zero, the last partial strip (less
// than a row) stays pending for good: pending_volume() reports it, the ledger never sees it.
// New particles' depth is replaced by eq 7 at the next refresh.
//
// The caller places the line and the direction so that the rows land in the domain (nothing
// here looks for walls). A line lying on a wall is fine: rows start l/2 in front of it.

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "swemps/boundaries/hydrograph.hpp"
#include "swemps/swe/bed.hpp"
#include "swemps/swe/effect.hpp"

namespace swemps::boundaries {

// h_c = (q^2 / g)^(1/3) for a unit discharge q (m^2/s): the depth at which the flow is critical
// (Froude number 1, u = sqrt(g h)).
double critical_depth_m(double unit_discharge_m2_s, double gravity_m_s2);

struct InflowLineSettings {
  std::string name = "inflow";        // for reports
  std::uint32_t label = 0;            // the provenance label of its water (docs/provenance.md)
  std::array<double, 2> from{};       // m: the line the water crosses
  std::array<double, 2> to{};         // m
  std::array<double, 2> direction{};  // the way the water enters: normal to the line, any length
  double spacing_m = 0.0;             // l: particle spacing along and across the line
  std::optional<double> depth_m;      // h_in; unset: the critical depth of the current discharge
  std::shared_ptr<const swe::BedSource> bed;  // z_b of new particles; null: z_b = 0
};

class InflowLine final : public swe::Effect {
 public:
  // Throws std::invalid_argument for a line of zero or non-finite length, a direction that is
  // zero, non-finite or not normal to the line (to 1e-9), a spacing or depth that is not a
  // positive finite number, or an empty name.
  InflowLine(InflowLineSettings settings, Hydrograph hydrograph);

  std::string_view name() const override { return settings_.name; }
  swe::Stage stage() const override { return swe::Stage::topology; }
  void apply(swe::StepContext& context) override;
  std::string report() const override;
  void save_state(swe::StateWriter& out) const override;
  void restore_state(swe::StateReader& in) override;
  // eq 13 for a row at the hydrograph's peak discharge: the step never skips past a rise
  // of the hydrograph, and a domain that starts dry still gets steps of a sensible size.
  double time_step_limit(const swe::Settings& settings, double time_s) const override;

  // n = max(1, round(L / l)) slots at the centres of n equal pieces of the line.
  std::size_t slot_count() const { return slots_.size(); }
  std::array<double, 2> slot(std::size_t k) const { return slots_[k]; }
  std::array<double, 2> direction() const { return direction_; }  // unit
  double line_length_m() const { return length_m_; }
  const Hydrograph& hydrograph() const { return hydrograph_; }

  std::size_t rows_emitted() const { return rows_; }
  std::size_t particles_added() const { return particles_; }
  double volume_added() const { return added_m3_; }      // m^3, as booked in the ledger
  double pending_volume() const { return pending_m3_; }  // m^3, crossed but not yet in a row
  double strip_advance() const { return advance_m_; }    // m, of the partial strip, [0, l)

 private:
  InflowLineSettings settings_;
  Hydrograph hydrograph_;
  std::array<double, 2> direction_{};
  double length_m_ = 0.0;
  std::vector<std::array<double, 2>> slots_;
  double pending_m3_ = 0.0, advance_m_ = 0.0, added_m3_ = 0.0;
  std::size_t rows_ = 0, particles_ = 0;
};

}  // namespace swemps::boundaries
