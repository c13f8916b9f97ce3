#include "swemps/hydrology/rain.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "swemps/particles/seeding.hpp"

namespace swemps::hydrology {

Rain::Rain(RainSettings settings, boundaries::Hydrograph rate_m_s, std::unique_ptr<RainLoss> losses)
    : Rain(std::move(settings), std::make_unique<UniformRainRate>(std::move(rate_m_s)),
           std::move(losses)) {}

Rain::Rain(RainSettings settings, std::unique_ptr<RainRate> rate, std::unique_ptr<RainLoss> losses)
    : settings_(std::move(settings)), rate_(std::move(rate)), losses_(std::move(losses)) {
  if (settings_.name.empty()) throw std::invalid_argument("rain: empty name");
  if (!rate_) throw std::invalid_argument("rain '" + settings_.name + "': no rate");
  const std::string who = "rain '" + settings_.name + "': ";
  const auto& d = settings_.domain;
  const double width = d.x_max - d.x_min, height = d.y_max - d.y_min;
  if (!(width > 0.0) || !(height > 0.0) || !std::isfinite(width) || !std::isfinite(height)) {
    throw std::invalid_argument(who + "the domain has no area");
  }
  const double l = settings_.spacing_m;
  if (!(l > 0.0) || !std::isfinite(l)) {
    throw std::invalid_argument(who + "the spacing must be a positive number of metres");
  }
  if (!(settings_.creation_depth_m > 0.0) || !std::isfinite(settings_.creation_depth_m)) {
    throw std::invalid_argument(who + "the creation depth must be a positive number of metres");
  }
  if (!settings_.polygon.empty() && settings_.polygon.size() < 3) {
    throw std::invalid_argument(who + "a polygon needs at least 3 vertices");
  }
  // Whole numbers of cells across: the cells tile the domain, so that rain over the whole
  // domain is rate x its area exactly.
  nx_ = static_cast<std::size_t>(std::max(1.0, std::round(width / l)));
  ny_ = static_cast<std::size_t>(std::max(1.0, std::round(height / l)));
  cell_dx_ = width / static_cast<double>(nx_);
  cell_dy_ = height / static_cast<double>(ny_);
  if (static_cast<double>(nx_) * static_cast<double>(ny_) >
      static_cast<double>(std::numeric_limits<std::int32_t>::max())) {
    throw std::invalid_argument(who + "the spacing makes more than 2^31 cells over the domain");
  }
  rain_cell_of_.assign(nx_ * ny_, -1);
  for (std::size_t j = 0; j < ny_; ++j) {
    for (std::size_t i = 0; i < nx_; ++i) {
      const std::array<double, 2> centre{d.x_min + (static_cast<double>(i) + 0.5) * cell_dx_,
                                         d.y_min + (static_cast<double>(j) + 0.5) * cell_dy_};
      if (!settings_.polygon.empty() && !particles::point_in_polygon(settings_.polygon, centre)) {
        continue;
      }
      if (settings_.roofs && settings_.roofs->contains(centre[0], centre[1])) continue;
      rain_cell_of_[j * nx_ + i] = static_cast<std::int32_t>(cells_.size());
      cells_.push_back(static_cast<std::uint32_t>(j * nx_ + i));
    }
  }
  if (cells_.empty()) {
    throw std::invalid_argument(who + "the polygon holds no cell centre of a " + std::to_string(l) +
                                " m lattice over the domain outside the buildings");
  }
  pending_m_.assign(cells_.size(), 0.0);
  step_rain_m_.assign(cells_.size(), 0.0);
  std::vector<std::array<double, 2>> centres(cells_.size());
  for (std::size_t k = 0; k < cells_.size(); ++k) centres[k] = cell_centre(k);
  try {
    rate_->bind(centres);
    if (losses_) losses_->bind(centres);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(who + e.what());
  }
}

double Rain::volume_due(double t0_s, double t1_s) const {
  std::vector<double> depth(cells_.size());
  rate_->depth_over(t0_s, t1_s, depth);
  double sum = 0.0;
  for (const double d : depth) sum += d;
  return sum * cell_area_m2();
}

std::array<double, 2> Rain::cell_centre(std::size_t k) const {
  const std::size_t i = cells_[k] % nx_, j = cells_[k] / nx_;
  return {settings_.domain.x_min + (static_cast<double>(i) + 0.5) * cell_dx_,
          settings_.domain.y_min + (static_cast<double>(j) + 0.5) * cell_dy_};
}

std::int64_t Rain::cell_at(double x, double y) const {
  const double fi = std::floor((x - settings_.domain.x_min) / cell_dx_);
  const double fj = std::floor((y - settings_.domain.y_min) / cell_dy_);
  // Written so that a NaN position falls outside.
  if (!(fi >= 0.0 && fi < static_cast<double>(nx_) && fj >= 0.0 && fj < static_cast<double>(ny_)))
    return -1;
  return rain_cell_of_[static_cast<std::size_t>(fj) * nx_ + static_cast<std::size_t>(fi)];
}

void Rain::covered_cells(double x, double y, double area, std::vector<std::uint32_t>& out) const {
  const std::int64_t own = cell_at(x, y);
  // A particle whose area is not a positive number (none should be) covers its own cell.
  const double reach = std::sqrt(area);
  if (!(reach > 0.0) || !std::isfinite(reach)) {
    if (own >= 0) out.push_back(static_cast<std::uint32_t>(own));
    return;
  }
  const auto& d = settings_.domain;
  const auto index_range = [](double lo, double hi, std::size_t count) {
    const double first = std::max(0.0, std::floor(lo));
    const double last = std::min(static_cast<double>(count) - 1.0, std::floor(hi));
    return std::array<double, 2>{first, last};
  };
  const auto is =
      index_range((x - reach - d.x_min) / cell_dx_, (x + reach - d.x_min) / cell_dx_, nx_);
  const auto js =
      index_range((y - reach - d.y_min) / cell_dy_, (y + reach - d.y_min) / cell_dy_, ny_);
  const double reach2 = reach * reach;
  for (double fj = js[0]; fj <= js[1]; fj += 1.0) {
    const double dy = d.y_min + (fj + 0.5) * cell_dy_ - y;
    for (double fi = is[0]; fi <= is[1]; fi += 1.0) {
      const double dx = d.x_min + (fi + 0.5) * cell_dx_ - x;
      const std::size_t lattice = static_cast<std::size_t>(fj) * nx_ + static_cast<std::size_t>(fi);
      const std::int32_t k = rain_cell_of_[lattice];
      if (k >= 0 && (dx * dx + dy * dy <= reach2 || k == own)) {
        out.push_back(static_cast<std::uint32_t>(k));
      }
    }
  }
  // The own cell lies inside the bounding box, so it is listed whenever it is a rain cell.
}

double Rain::time_step_limit(const swe::Settings& /*settings*/, double /*time_s*/) const {
  const double peak = rate_->peak_m_s();
  if (!(peak > 0.0)) return std::numeric_limits<double>::infinity();
  return settings_.creation_depth_m / peak;
}

void Rain::apply(swe::StepContext& context) {
  const double dt = context.dt_s;
  if (!(dt > 0.0)) return;
  // No rain: nothing falls and nothing is lost (the losses take from the rain alone).
  if (!(rate_->depth_over(context.time_s, context.time_s + dt, step_rain_m_) > 0.0)) return;
  double fallen_m = 0.0;
  for (const double d : step_rain_m_) fallen_m += d;
  const double lost_m = losses_ ? losses_->take(dt, step_rain_m_) : 0.0;
  const double cell_area = cell_area_m2();
  auto& p = context.particles;
  const std::size_t n = p.fluid_count();

  // The cells each particle covers, found once: particle i's are covered_[covered_start_[i],
  // covered_start_[i + 1]).
  covered_.clear();
  covered_start_.assign(1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    covered_cells(p.x[i], p.y[i], p.area[i], covered_);
    covered_start_.push_back(covered_.size());
  }
  over_count_.assign(cells_.size(), 0);
  for (const std::uint32_t k : covered_) ++over_count_[k];

  share_m3_.assign(cells_.size(), 0.0);
  std::vector<std::uint32_t> due;  // dry cells that have gathered a particle's water
  for (std::size_t k = 0; k < cells_.size(); ++k) {
    const double excess_m = step_rain_m_[k];
    if (over_count_[k] > 0) {
      share_m3_[k] = (excess_m + pending_m_[k]) * cell_area / static_cast<double>(over_count_[k]);
      pending_m_[k] = 0.0;
    } else {
      pending_m_[k] += excess_m;
      if (pending_m_[k] >= settings_.creation_depth_m) due.push_back(static_cast<std::uint32_t>(k));
    }
  }

  // The rain of the step counts as entered at the step's end.
  const particles::Origin origin{settings_.label, context.time_s + context.dt_s};
  double booked_m3 = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    double gain_m3 = 0.0;
    for (std::size_t j = covered_start_[i]; j < covered_start_[i + 1]; ++j) {
      gain_m3 += share_m3_[covered_[j]];
    }
    if (!(gain_m3 > 0.0)) continue;
    // Rain falls with no horizontal momentum: the particle keeps its momentum V u, so its
    // velocity falls by V / (V + dV), as the depth-averaged momentum equation's rain term says.
    const double keep = p.volume[i] / (p.volume[i] + gain_m3);
    p.u[i] *= keep;
    p.v[i] *= keep;
    p.mix_in(i, p.volume[i], gain_m3, origin);
    p.volume[i] += gain_m3;
    booked_m3 += gain_m3;
  }
  for (const std::uint32_t k : due) {
    const auto [x, y] = cell_centre(k);
    const double depth = pending_m_[k];
    const double volume = depth * cell_area;
    const double bed = settings_.bed ? settings_.bed->elevation(x, y) : 0.0;
    p.add_fluid(x, y, 0.0, 0.0, volume, depth, cell_area, bed, origin);
    booked_m3 += volume;
    pending_m_[k] = 0.0;
  }
  created_ += due.size();
  fallen_m3_ += fallen_m * cell_area;
  lost_m3_ += lost_m * cell_area;
  added_m3_ += booked_m3;
  context.ledger.rain_m3 += booked_m3;
  context.ledger.add_to_label(settings_.label, booked_m3);
}

double Rain::pending_volume() const {
  double sum = 0.0;
  for (const double depth : pending_m_) sum += depth;
  return sum * cell_area_m2();
}

std::string Rain::report() const {
  std::ostringstream out;
  out << cells_.size() << " cells, " << fallen_m3_ << " m3 fallen: " << added_m3_
      << " m3 reached the water, " << lost_m3_ << " m3 lost, " << pending_volume()
      << " m3 pending in dry cells; " << created_ << " particles created";
  return out.str();
}

void Rain::save_state(swe::StateWriter& out) const {
  // What each cell has gathered and has still to lose decides what the next steps make.
  out.numbers(pending_m_);
  // Without losses, the initial loss left is nought in every cell: written so, the record
  // keeps the layout of the initial-and-continuing loss's, which earlier records had always.
  if (losses_) {
    losses_->save_state(out);
  } else {
    out.numbers(std::vector<double>(cells_.size(), 0.0));
  }
  for (const double value : {fallen_m3_, lost_m3_, added_m3_}) out.number(value);
  out.count(created_);
}

void Rain::restore_state(swe::StateReader& in) {
  auto pending = in.numbers();
  if (pending.size() != cells_.size()) {
    throw swe::StateError(in.what() + " holds rain for " + std::to_string(pending.size()) +
                          " cells, not this scene's " + std::to_string(cells_.size()));
  }
  pending_m_ = std::move(pending);
  if (losses_) {
    losses_->restore_state(in);
  } else if (in.numbers().size() != cells_.size()) {
    throw swe::StateError(in.what() + " holds losses for another number of rain cells");
  }
  fallen_m3_ = in.number();
  lost_m3_ = in.number();
  added_m3_ = in.number();
  created_ = in.count();
}

}  // namespace swemps::hydrology
