#include "swemps/boundaries/inflow_line.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace swemps::boundaries {

double critical_depth_m(double q, double g) {
  // cbrt(q)^2 rather than cbrt(q^2): q^2 underflows for discharges cbrt(q) still resolves.
  const double r = std::cbrt(q);
  return r * r / std::cbrt(g);
}

InflowLine::InflowLine(InflowLineSettings settings, Hydrograph hydrograph)
    : settings_(std::move(settings)), hydrograph_(std::move(hydrograph)) {
  const std::string who = "inflow line '" + settings_.name + "': ";
  if (settings_.name.empty()) throw std::invalid_argument("inflow line: empty name");
  const std::array<double, 2> along{settings_.to[0] - settings_.from[0],
                                    settings_.to[1] - settings_.from[1]};
  length_m_ = std::hypot(along[0], along[1]);
  if (!(length_m_ > 0.0) || !std::isfinite(length_m_)) {
    throw std::invalid_argument(who + "the line has zero or non-finite length");
  }
  const double l = settings_.spacing_m;
  if (!(l > 0.0) || !std::isfinite(l)) {
    throw std::invalid_argument(who + "the spacing must be a positive number of metres");
  }
  if (settings_.depth_m && (!(*settings_.depth_m > 0.0) || !std::isfinite(*settings_.depth_m))) {
    throw std::invalid_argument(who + "the inflow depth must be a positive number of metres");
  }
  const auto d = settings_.direction;
  const double norm = std::hypot(d[0], d[1]);
  if (!(norm > 0.0) || !std::isfinite(norm)) {
    throw std::invalid_argument(who + "the entry direction is zero or not finite");
  }
  direction_ = {d[0] / norm, d[1] / norm};
  const double cosine = (direction_[0] * along[0] + direction_[1] * along[1]) / length_m_;
  if (std::abs(cosine) > 1e-9) {
    throw std::invalid_argument(who + "the entry direction is not normal to the line");
  }
  const auto n = static_cast<std::size_t>(std::max(1.0, std::round(length_m_ / l)));
  slots_.reserve(n);
  for (std::size_t k = 0; k < n; ++k) {
    const double f = (static_cast<double>(k) + 0.5) / static_cast<double>(n);
    slots_.push_back({settings_.from[0] + f * along[0], settings_.from[1] + f * along[1]});
  }
}

double InflowLine::time_step_limit(const swe::Settings& settings, double /*time_s*/) const {
  double peak_m3_s = 0.0;
  for (const auto& point : hydrograph_.points()) peak_m3_s = std::max(peak_m3_s, point[1]);
  if (!(peak_m3_s > 0.0)) return std::numeric_limits<double>::infinity();
  const double q = peak_m3_s / length_m_;
  const double g = settings.gravity_m_s2;
  const double depth = settings_.depth_m ? *settings_.depth_m : critical_depth_m(q, g);
  const double speed = q / depth;
  return settings.cfl * settings_.spacing_m / (std::sqrt(g * depth) + speed);
}

void InflowLine::apply(swe::StepContext& context) {
  const double dt = context.dt_s;
  if (!(dt > 0.0)) return;
  const double inflow_m3 = hydrograph_.volume(context.time_s, context.time_s + dt);
  // Q = 0 over the whole step: nothing crosses, the strip stands still (and no depth or
  // velocity of a zero discharge is ever needed).
  if (!(inflow_m3 > 0.0)) return;

  const double l = settings_.spacing_m;
  const double q = inflow_m3 / (dt * length_m_);  // mean unit discharge of the step, m^2/s
  const double g = context.settings.gravity_m_s2;
  const double depth = settings_.depth_m ? *settings_.depth_m : critical_depth_m(q, g);
  // u = q / h_c = (g q)^(1/3) at critical depth, written so that it never divides by h_c.
  const double speed = settings_.depth_m ? q / depth : std::cbrt(g * q);
  const double step_advance = speed * dt;
  const double advance = advance_m_ + step_advance;
  const double total_m3 = pending_m3_ + inflow_m3;
  const double complete = std::floor(advance / l);  // rows completed in this step
  if (complete < 1.0) {
    pending_m3_ = total_m3;
    advance_m_ = advance;
    return;
  }
  // The strip has moved `beyond` since the newest row was complete; the water that crossed
  // in that time (the same fraction of this step's water, the step's discharge being taken
  // as its mean) starts the next row.
  const double beyond = std::clamp(advance - complete * l, 0.0, l);
  const double leftover_m3 = inflow_m3 * std::min(1.0, beyond / step_advance);

  auto& p = context.particles;
  const auto rows = static_cast<std::size_t>(complete);
  const std::size_t n = slots_.size();
  const double particle_m3 = (total_m3 - leftover_m3) / static_cast<double>(rows * n);
  const double area_m2 = l * length_m_ / static_cast<double>(n);  // what each particle stands for
  const double u = speed * direction_[0], v = speed * direction_[1];
  // The water enters over the step; it counts as entered at the step's end.
  const particles::Origin origin{settings_.label, context.time_s + dt};
  double booked_m3 = 0.0;
  for (std::size_t r = 0; r < rows; ++r) {
    const double offset = 0.5 * l + beyond + static_cast<double>(r) * l;
    for (const auto& s : slots_) {
      const double x = s[0] + offset * direction_[0];
      const double y = s[1] + offset * direction_[1];
      const double bed = settings_.bed ? settings_.bed->elevation(x, y) : 0.0;
      p.add_fluid(x, y, u, v, particle_m3, depth, area_m2, bed, origin);
      booked_m3 += particle_m3;
    }
  }
  context.ledger.added_m3 += booked_m3;
  context.ledger.add_to_label(settings_.label, booked_m3);
  added_m3_ += booked_m3;
  // The complement of what was booked, so that added + pending is the hydrograph's volume.
  pending_m3_ = std::max(0.0, total_m3 - booked_m3);
  advance_m_ = beyond;
  rows_ += rows;
  particles_ += rows * n;
}

std::string InflowLine::report() const {
  std::ostringstream out;
  out << rows_ << " rows, " << particles_ << " particles, " << added_m3_ << " m3 added, "
      << pending_m3_ << " m3 pending";
  return out.str();
}

void InflowLine::save_state(swe::StateWriter& out) const {
  // The strip's water and advance decide when the next row appears and how much it holds.
  for (const double value : {pending_m3_, advance_m_, added_m3_}) out.number(value);
  out.count(rows_);
  out.count(particles_);
}

void InflowLine::restore_state(swe::StateReader& in) {
  pending_m3_ = in.number();
  advance_m_ = in.number();
  added_m3_ = in.number();
  rows_ = in.count();
  particles_ = in.count();
}

}  // namespace swemps::boundaries
