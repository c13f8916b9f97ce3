// Facts particular to the spiky kernel (eq 8). The contract it shares with every other kernel
// (unit integral, compact support, non-negative, non-increasing, slope consistent with the
// value, radius validation) is tested once for all kernels in test_kernel_properties.cpp.
// The radii, far from 1, catch a missing power of r_e in a normalisation.

#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include "swemps/kernels/spiky.hpp"

TEST_CASE("2D spiky kernel integrates to one on a Cartesian grid", "[kernels]") {
  // The radial quadrature of the all-kernel tests and the kernel could share a wrong idea of
  // the shell measure; a plain grid over the square [-2 r_e, 2 r_e]^2 does not depend on it.
  const double r_e = GENERATE(0.013, 0.1, 1.0, 7.5);
  const swemps::kernels::Spiky<2> kernel(r_e);
  constexpr int cells = 1000;  // per side; even, so the cone tip at 0 sits on a cell corner
  const double extent = kernel.support();
  const double h = 2.0 * extent / cells;
  double sum = 0.0;
  for (int j = 0; j < cells; ++j) {
    const double y = -extent + (j + 0.5) * h;
    for (int i = 0; i < cells; ++i) {
      const double x = -extent + (i + 0.5) * h;
      sum += kernel.w(std::hypot(x, y));
    }
  }
  sum *= h * h;
  // The midpoint rule's h^2 term is h^2 / 24 times the integral of the Laplacian, which is
  // the flux of grad w through the square's edge: zero, since w and its gradient vanish at
  // the support. What remains comes from the cone at the origin, O((h / r_e)^3) = 6e-8
  // times an O(0.1) factor (observed: 5e-9). 1e-6 is a safe bound that still rejects a
  // constant off by a part in a million.
  CHECK(sum == Approx(1.0).epsilon(1e-6));
}

TEMPLATE_TEST_CASE("spiky kernel has a non-zero gradient at the origin", "[kernels]",
                   swemps::kernels::Spiky<1>, swemps::kernels::Spiky<2>,
                   swemps::kernels::Spiky<3>) {
  // The reason for choosing the spiky kernel: coincident particles still repel.
  const double r_e = GENERATE(0.013, 0.1, 1.0, 7.5);
  const TestType kernel(r_e);
  const double slope = kernel.dw_dr(0.0);
  CHECK(slope < 0.0);
  CHECK(std::isfinite(slope));
  // One-sided difference (the kernel is only defined for r >= 0): error h |w''| / 2, i.e.
  // relative h / ((2 - 0) r_e) = 5e-7 with h = 1e-6 r_e; rounding ~ eps r_e / h = 2e-10.
  const double h = 1e-6 * r_e;
  CHECK(slope == Approx((kernel.w(h) - kernel.w(0.0)) / h).epsilon(1e-5));
}

TEST_CASE("2D spiky kernel at the origin is the eq 8 value", "[kernels]") {
  const double r_e = GENERATE(0.013, 0.1, 1.0, 7.5);
  const swemps::kernels::Spiky<2> kernel(r_e);
  // eq 8: w(0) = 5 / (16 pi r_e^2) * (2 - 0)^3.
  const double expected = 5.0 / (16.0 * std::numbers::pi * r_e * r_e) * 8.0;
  CHECK(kernel.w(0.0) == Approx(expected).epsilon(1e-14));
  // And halfway to the support: (2 - 1)^3 = 1.
  CHECK(kernel.w(r_e) == Approx(expected / 8.0).epsilon(1e-14));
}
