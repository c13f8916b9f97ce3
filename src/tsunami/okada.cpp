#include "swemps/tsunami/okada.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace swemps::tsunami {

namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
// Below this, cos(dip) is taken as 0 (a vertical plane: eq 29's limits of I4 and I5), and a
// coordinate as on a singular line of eq 25-27 (the term's limit there is 0).
constexpr double kTiny = 1e-12;

// eq 25-27's u_z integrand at the corner (xi, eta) of Chinnery's notation.
double corner_vertical(double xi, double eta, double q, double sin_dip, double cos_dip, double u1,
                       double u2, double u3, double alpha) {
  const double r = std::sqrt(xi * xi + eta * eta + q * q);
  const double y_tilde = eta * cos_dip + q * sin_dip;
  const double d_tilde = eta * sin_dip - q * cos_dip;
  const double x = std::sqrt(xi * xi + q * q);
  // ln(R + eta), which vanishes where R + eta does (eta < 0 on the plane's line): Okada
  // sets the terms with 1 / (R + eta) to 0 there.
  const bool eta_singular = r + eta < kTiny;
  const double log_r_eta = eta_singular ? -std::log(r - eta) : std::log(r + eta);
  const double over_r_eta = eta_singular ? 0.0 : 1.0 / (r * (r + eta));
  const double over_r_xi = r + xi < kTiny ? 0.0 : 1.0 / (r * (r + xi));
  const double theta = std::abs(q) < kTiny ? 0.0 : std::atan(xi * eta / (q * r));
  double i4 = 0.0, i5 = 0.0;
  if (std::abs(cos_dip) > kTiny) {
    i4 = alpha / cos_dip * (std::log(r + d_tilde) - sin_dip * log_r_eta);
    i5 = std::abs(xi) < kTiny ? 0.0
                              : alpha * 2.0 / cos_dip *
                                    std::atan((eta * (x + q * cos_dip) + x * (r + x) * sin_dip) /
                                              (xi * (r + x) * cos_dip));
  } else {
    i4 = -alpha * q / (r + d_tilde);
    i5 = -alpha * xi * sin_dip / (r + d_tilde);
  }
  const double strike =
      d_tilde * q * over_r_eta + (eta_singular ? 0.0 : q * sin_dip / (r + eta)) + i4 * sin_dip;
  const double dip = d_tilde * q * over_r_xi + sin_dip * theta - i5 * sin_dip * cos_dip;
  const double tensile =
      y_tilde * q * over_r_xi + cos_dip * (xi * q * over_r_eta - theta) - i5 * sin_dip * sin_dip;
  return (-u1 * strike - u2 * dip + u3 * tensile) / (2.0 * std::numbers::pi);
}

bool finite(double v) { return std::isfinite(v); }

}  // namespace

double okada_vertical(double x, double y, double depth, double dip_rad, double length, double width,
                      double u1, double u2, double u3, double alpha) {
  const double sin_dip = std::sin(dip_rad), cos_dip = std::cos(dip_rad);
  const double p = y * cos_dip + depth * sin_dip;
  const double q = y * sin_dip - depth * cos_dip;
  // Chinnery's notation (eq 24): f(x, p) - f(x, p - W) - f(x - L, p) + f(x - L, p - W).
  const auto f = [&](double xi, double eta) {
    return corner_vertical(xi, eta, q, sin_dip, cos_dip, u1, u2, u3, alpha);
  };
  return f(x, p) - f(x, p - width) - f(x - length, p) + f(x - length, p - width);
}

FaultSource::FaultSource(std::vector<FaultPlane> planes, double poisson_ratio)
    : planes_(std::move(planes)), alpha_(1.0 - 2.0 * poisson_ratio) {
  if (!(poisson_ratio > 0.0 && poisson_ratio < 0.5))
    throw std::invalid_argument("fault source: Poisson's ratio must lie in (0, 0.5)");
  if (planes_.empty()) throw std::invalid_argument("fault source: no fault plane");
  for (const FaultPlane& f : planes_) {
    const bool all_finite = finite(f.top_centre_m[0]) && finite(f.top_centre_m[1]) &&
                            finite(f.top_depth_m) && finite(f.strike_deg) && finite(f.dip_deg) &&
                            finite(f.rake_deg) && finite(f.slip_m) && finite(f.length_m) &&
                            finite(f.width_m);
    if (!all_finite) throw std::invalid_argument("fault source: a non-finite value");
    if (!(f.length_m > 0.0) || !(f.width_m > 0.0))
      throw std::invalid_argument("fault source: a plane's length and width must be > 0");
    if (!(f.dip_deg > 0.0 && f.dip_deg <= 90.0))
      throw std::invalid_argument("fault source: a plane's dip must lie in (0, 90] degrees");
    if (!(f.top_depth_m >= 0.0) || !(f.slip_m >= 0.0))
      throw std::invalid_argument("fault source: a plane's depth and slip must be >= 0");
  }
}

double FaultSource::vertical_displacement(double x_m, double y_m) const {
  double uz = 0.0;
  for (const FaultPlane& f : planes_) {
    const double strike = f.strike_deg * kDegree, dip = f.dip_deg * kDegree;
    const double rake = f.rake_deg * kDegree;
    // Along strike, and normal to it towards the side the plane rises to (its left).
    const std::array<double, 2> along{std::sin(strike), std::cos(strike)};
    const std::array<double, 2> across{-along[1], along[0]};
    // Okada's origin: the lower edge's end behind the strike, on the map.
    const double down_dip = f.width_m * std::cos(dip);
    const double ox = f.top_centre_m[0] - 0.5 * f.length_m * along[0] - down_dip * across[0];
    const double oy = f.top_centre_m[1] - 0.5 * f.length_m * along[1] - down_dip * across[1];
    const double dx = x_m - ox, dy = y_m - oy;
    const double x = dx * along[0] + dy * along[1];
    const double y = dx * across[0] + dy * across[1];
    const double depth = f.top_depth_m + f.width_m * std::sin(dip);
    uz += okada_vertical(x, y, depth, dip, f.length_m, f.width_m, f.slip_m * std::cos(rake),
                         f.slip_m * std::sin(rake), 0.0, alpha_);
  }
  return uz;
}

terrain::GriddedField sample_displacement(const FaultSource& source, double x_min, double x_max,
                                          double y_min, double y_max, double cell_m) {
  if (!(cell_m > 0.0) || !(x_max > x_min) || !(y_max > y_min))
    throw std::invalid_argument("fault source: an empty grid to sample the displacement on");
  // One cell beyond each side, so that bilinear reads inside the bounds never clamp.
  const auto cells = [&](double extent) {
    return static_cast<std::size_t>(std::ceil(extent / cell_m)) + 2;
  };
  terrain::GridGeometry g;
  g.columns = cells(x_max - x_min);
  g.rows = cells(y_max - y_min);
  g.cell_width = (x_max - x_min) / static_cast<double>(g.columns - 2);
  g.cell_height = (y_max - y_min) / static_cast<double>(g.rows - 2);
  g.x_left = x_min - g.cell_width;
  g.y_top = y_max + g.cell_height;
  std::vector<double> uz(g.columns * g.rows);
#pragma omp parallel for schedule(dynamic, 1)
  for (std::size_t row = 0; row < g.rows; ++row) {
    for (std::size_t col = 0; col < g.columns; ++col) {
      uz[row * g.columns + col] =
          source.vertical_displacement(g.cell_centre_x(col), g.cell_centre_y(row));
    }
  }
  return terrain::GriddedField(g, std::move(uz), {}, "sea-floor displacement");
}

}  // namespace swemps::tsunami
