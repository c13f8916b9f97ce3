#include "swemps/hydrology/rain_losses.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace swemps::hydrology {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

void restore_cells(swe::StateReader& in, std::vector<double>& into, const char* what) {
  auto values = in.numbers();
  if (values.size() != into.size()) {
    throw swe::StateError(in.what() + " holds " + what + " for " + std::to_string(values.size()) +
                          " rain cells, not this scene's " + std::to_string(into.size()));
  }
  into = std::move(values);
}

// F2 with F2 - F1 - S ln((F2 + S) / (F1 + S)) = K tau: the depth infiltrated after tau seconds
// of ponding from F1. The left side g(F2) is increasing and convex for F2 > 0, so Newton's
// method from a point above the root falls to it monotonically.
double ponded_infiltration(double k, double s, double f1, double tau) {
  if (!(tau > 0.0)) return f1;
  if (!(s > 0.0)) return f1 + k * tau;  // no suction: the soil takes K
  const auto g = [&](double f2) { return f2 - f1 - s * std::log((f2 + s) / (f1 + s)) - k * tau; };
  double f2 = f1 + k * tau + std::sqrt(2.0 * s * k * tau);
  while (g(f2) < 0.0) f2 = f1 + 2.0 * (f2 - f1);
  for (int iteration = 0; iteration < 100; ++iteration) {
    const double step = g(f2) * (f2 + s) / f2;  // g / g', g' = F2 / (F2 + S)
    f2 -= step;
    if (!(step > 1e-12 * (1.0 + f2))) break;
  }
  return std::max(f2, f1);
}

}  // namespace

std::vector<double> CellParameter::at(std::span<const std::array<double, 2>> centres) const {
  std::vector<double> out(centres.size(), value);
  const auto where = [&](std::size_t c) {
    std::ostringstream text;
    text << "(" << centres[c][0] << ", " << centres[c][1] << ")";
    return text.str();
  };
  for (std::size_t c = 0; c < centres.size(); ++c) {
    if (map) {
      if (!map->covers(centres[c][0], centres[c][1])) {
        throw std::invalid_argument("the " + name + " map does not cover the rain cell at " +
                                    where(c));
      }
      out[c] = map->cell_value(centres[c][0], centres[c][1]) * scale;
    }
    if (!(out[c] >= 0.0) || !(out[c] <= most) || !std::isfinite(out[c])) {
      throw std::invalid_argument(
          "the " + name + " is " +
          (std::isnan(out[c]) ? std::string("nodata") : std::to_string(out[c])) +
          " at the rain cell " + where(c) + "; it must be >= 0" +
          (std::isfinite(most) ? " and <= " + std::to_string(most) : std::string()));
    }
  }
  return out;
}

InitialContinuingLoss::InitialContinuingLoss(CellParameter initial_m, CellParameter continuing_m_s)
    : initial_m_(std::move(initial_m)), continuing_m_s_(std::move(continuing_m_s)) {}

void InitialContinuingLoss::bind(std::span<const std::array<double, 2>> centres) {
  initial_left_m_ = initial_m_.at(centres);
  continuing_m_s_at_ = continuing_m_s_.at(centres);
}

double InitialContinuingLoss::take(double dt_s, std::span<double> depth_m) {
  double lost_m = 0.0;
  for (std::size_t c = 0; c < depth_m.size(); ++c) {
    const double initial = std::min(initial_left_m_[c], depth_m[c]);
    initial_left_m_[c] -= initial;
    const double continuing = std::min(continuing_m_s_at_[c] * dt_s, depth_m[c] - initial);
    depth_m[c] -= initial + continuing;
    lost_m += initial + continuing;
  }
  return lost_m;
}

void InitialContinuingLoss::save_state(swe::StateWriter& out) const {
  out.numbers(initial_left_m_);
}

void InitialContinuingLoss::restore_state(swe::StateReader& in) {
  restore_cells(in, initial_left_m_, "initial losses");
}

double green_ampt_infiltration(double conductivity_m_s, double storage_m, double rain_m,
                               double dt_s, double& infiltrated_m) {
  const double k = conductivity_m_s, s = storage_m;
  if (!(rain_m > 0.0) || !(dt_s > 0.0) || !(k > 0.0)) return 0.0;
  const double rate = rain_m / dt_s;
  const double start = infiltrated_m;
  // The capacity K (1 + S / F) as F rises; at F = 0 it is unbounded unless S = 0.
  const double capacity = start > 0.0 ? k * (1.0 + s / start) : (s > 0.0 ? kInfinity : k);
  double ponding_from_s = 0.0;  // when in the step the surface ponds
  if (capacity > rate) {
    // Not ponded: all the rain soaks in until F reaches K S / (i - K), if it ever does.
    const double ponding_depth = rate > k ? k * s / (rate - k) : kInfinity;
    if (start + rain_m <= ponding_depth) {
      infiltrated_m = start + rain_m;
      return rain_m;
    }
    ponding_from_s = (ponding_depth - start) / rate;
    infiltrated_m = ponding_depth;
  }
  const double ponded =
      ponded_infiltration(k, s, infiltrated_m, dt_s - ponding_from_s) - infiltrated_m;
  // The capacity falls while ponded, so the soil never takes more than the rain brings; the
  // bound only guards round-off.
  const double taken = std::min(rain_m, infiltrated_m - start + ponded);
  infiltrated_m = start + taken;
  return taken;
}

GreenAmptLoss::GreenAmptLoss(GreenAmptSoil soil, CellParameter initial_m)
    : soil_(std::move(soil)), initial_m_(std::move(initial_m)) {}

void GreenAmptLoss::bind(std::span<const std::array<double, 2>> centres) {
  conductivity_ = soil_.conductivity_m_s.at(centres);
  storage_ = soil_.suction_m.at(centres);
  const std::vector<double> deficit = soil_.moisture_deficit.at(centres);
  for (std::size_t c = 0; c < centres.size(); ++c) storage_[c] *= deficit[c];
  initial_left_m_ = initial_m_.at(centres);
  infiltrated_m_.assign(centres.size(), 0.0);
}

double GreenAmptLoss::take(double dt_s, std::span<double> depth_m) {
  double lost_m = 0.0;
  for (std::size_t c = 0; c < depth_m.size(); ++c) {
    const double initial = std::min(initial_left_m_[c], depth_m[c]);
    initial_left_m_[c] -= initial;
    const double soaked = green_ampt_infiltration(conductivity_[c], storage_[c],
                                                  depth_m[c] - initial, dt_s, infiltrated_m_[c]);
    depth_m[c] -= initial + soaked;
    lost_m += initial + soaked;
  }
  return lost_m;
}

void GreenAmptLoss::save_state(swe::StateWriter& out) const {
  out.numbers(initial_left_m_);
  out.numbers(infiltrated_m_);
}

void GreenAmptLoss::restore_state(swe::StateReader& in) {
  restore_cells(in, initial_left_m_, "initial losses");
  restore_cells(in, infiltrated_m_, "infiltrated depths");
}

}  // namespace swemps::hydrology
