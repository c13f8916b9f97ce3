// Normalisation of the hyperbolic SPH kernel (seed eqs 18, 20-22) and the dilogarithm it needs.

#include "swemps/kernels/hyperbolic_sph.hpp"

#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace swemps::kernels {

namespace {

// sum_{n >= 1} x^n / n^2 for 0 <= x <= 1/2, where each term is at most half the previous one:
// 60 terms leave less than 2^-60 of the sum, below double rounding.
double dilogarithm_series(double x) {
  double power = x;
  double sum = 0.0;
  for (int n = 1; n <= 60 && power != 0.0; ++n) {
    sum += power / (static_cast<double>(n) * n);
    power *= x;
  }
  return sum;
}

// Below this kappa the closed forms of the normalisation lose more than 1e-11 to cancellation
// (measured by quadrature: 3D, 1e-11 at kappa = 0.05, 2.5e-7 at 0.01).
constexpr double small_kappa = 0.05;

// J = integral_0^2 R^(dim - 1) (sech^2(kappa R) - sech^2(2 kappa)) dR from the Taylor series
// sech^2(x) = sum_n s_n x^(2n): J = 2^dim sum_{n >= 1} s_n (2 kappa)^(2n) (1/(2n + dim) - 1/dim).
// The series converges for 2 kappa < pi / 2; below 2 kappa = 0.1 each term is about 250 times
// smaller than the one before, so six terms leave a relative error near 1e-15.
double bell_integral_series(int dim, double kappa) {
  constexpr std::array<double, 6> sech2_taylor{-1.0,         2.0 / 3.0,         -17.0 / 45.0,
                                               62.0 / 315.0, -1382.0 / 14175.0, 21844.0 / 467775.0};
  const double x2 = 4.0 * kappa * kappa;
  double power = 1.0, sum = 0.0;
  for (std::size_t n = 1; n <= sech2_taylor.size(); ++n) {
    power *= x2;
    sum += sech2_taylor[n - 1] * power * (1.0 / (2.0 * n + dim) - 1.0 / dim);
  }
  return std::ldexp(sum, dim);
}

// ln(cosh(y)) for y >= 0 without overflowing cosh: y + ln((1 + e^(-2y)) / 2).
double log_cosh(double y) { return y + std::log1p(std::exp(-2.0 * y)) - std::numbers::ln2; }

}  // namespace

// The series converges slowly near |x| = 1 and not at all beyond, so every x <= 1 is first
// mapped into [0, 1/2] by one of the classical identities (Landen, reflection, inversion).
double dilogarithm(double x) {
  constexpr double pi_squared = std::numbers::pi * std::numbers::pi;
  if (std::isnan(x) || x > 1.0) return std::numeric_limits<double>::quiet_NaN();
  if (x == 1.0) return pi_squared / 6.0;
  if (x > 0.5) {
    // Reflection: Li2(x) + Li2(1 - x) = pi^2/6 - ln(x) ln(1 - x).
    return pi_squared / 6.0 - std::log(x) * std::log1p(-x) - dilogarithm_series(1.0 - x);
  }
  if (x >= 0.0) return dilogarithm_series(x);
  if (x >= -1.0) {
    // Landen: Li2(x) + Li2(x / (x - 1)) = -ln^2(1 - x) / 2, and x / (x - 1) is in (0, 1/2].
    const double log_one_minus_x = std::log1p(-x);
    return -0.5 * log_one_minus_x * log_one_minus_x - dilogarithm_series(x / (x - 1.0));
  }
  // Inversion: Li2(x) + Li2(1 / x) = -pi^2/6 - ln^2(-x) / 2, and 1 / x is in (-1, 0).
  const double log_minus_x = std::log(-x);
  return -pi_squared / 6.0 - 0.5 * log_minus_x * log_minus_x - dilogarithm(1.0 / x);
}

double hyperbolic_sph_a1(int dim, double influence_radius, double kappa) {
  if (dim < 1 || dim > 3) {
    throw std::invalid_argument("hyperbolic SPH kernel: dimension must be 1, 2 or 3");
  }
  // Each of eqs 18, 20 and 21 reads a1 = 1 / (c r_e^(dim - 1) B) with c = 1, pi, 2 pi and the
  // bracket B = kappa J, where J = integral_0^2 R^(dim - 1) (sech^2(kappa R) - sech^2(2 kappa)) dR
  // is the bell's radial integral. The closed forms of B cancel as kappa -> 0 (B ~ kappa^3
  // from O(1) terms: the 3D one has lost 7 digits at kappa = 0.01), so small kappa uses the
  // power series of J instead.
  const double k = kappa;
  const double bracket = k < small_kappa ? k * bell_integral_series(dim, k) : [&] {
    const double sech2_2k = sech_squared(2.0 * k);
    if (dim == 1) return std::tanh(2.0 * k) - 2.0 * k * sech2_2k;  // eq 18
    if (dim == 2) {
      return (2.0 * k * std::tanh(2.0 * k) - log_cosh(2.0 * k)) / k - 2.0 * k * sech2_2k;  // eq 20
    }
    // eq 22, with tanh(2k) - 1 = -2 e^(-4k) / (1 + e^(-4k)) so that nothing cancels for large
    // k, and ln(e^(-4k) + 1) through log1p; then eq 21.
    const double decay = std::exp(-4.0 * k);
    const double integral_u2_sech2 = -8.0 * k * k * decay / (1.0 + decay) -
                                     4.0 * k * std::log1p(decay) + dilogarithm(-decay) +
                                     std::numbers::pi * std::numbers::pi / 12.0;
    return integral_u2_sech2 / (k * k) - 8.0 * k / 3.0 * sech2_2k;
  }();
  const double shell = dim == 1 ? 1.0 : dim == 2 ? std::numbers::pi : 2.0 * std::numbers::pi;
  return 1.0 / (shell * std::pow(influence_radius, dim - 1) * bracket);
}

}  // namespace swemps::kernels
