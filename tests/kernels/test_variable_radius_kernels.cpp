// The kernels the shallow-water schemes evaluate at a radius per particle (cubic spline,
// Wendland C2, spiky): normalisation, and the derivatives in r and in h that the conservative
// scheme's force and grad-h factor are built from.

#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include "swemps/kernels/cubic_spline.hpp"
#include "swemps/kernels/spiky.hpp"
#include "swemps/kernels/wendland_c2.hpp"

using namespace swemps::kernels;

namespace {

// integral of W over the plane, 2 pi int_0^2h W(r) r dr, by the midpoint rule on 20,000
// intervals: exact to ~1e-9 for these piecewise polynomials.
template <class K>
double integral_2d(double h) {
  constexpr int intervals = 20000;
  const double dr = 2.0 * h / intervals;
  double sum = 0.0;
  for (int k = 0; k < intervals; ++k) {
    const double r = (k + 0.5) * dr;
    sum += K::w(r, h) * r * dr;
  }
  return 2.0 * std::numbers::pi * sum;
}

template <class K>
void check_kernel(double h) {
  CHECK(integral_2d<K>(h) == Approx(1.0).epsilon(1e-8));
  CHECK(K::w(2.0 * h, h) == 0.0);
  CHECK(K::w(2.5 * h, h) == 0.0);
  CHECK(K::dw_dr(2.5 * h, h) == 0.0);
  CHECK(K(h).w(0.7 * h) == Approx(K::w(0.7 * h, h)).epsilon(1e-15));
  // Central differences, step 1e-6 of the scale: truncation ~1e-12, round-off ~1e-10.
  for (const double q : {0.1, 0.5, 0.9, 1.3, 1.7}) {
    const double r = q * h, e = 1e-6 * h;
    const double slope = (K::w(r + e, h) - K::w(r - e, h)) / (2.0 * e);
    CHECK(K::dw_dr(r, h) == Approx(slope).epsilon(1e-6));
    const double in_h = (K::w(r, h + e) - K::w(r, h - e)) / (2.0 * e);
    CHECK(K::dw_dh(r, h) == Approx(in_h).epsilon(1e-6));
  }
}

}  // namespace

TEST_CASE("kernels at a radius per call integrate to one and differentiate right", "[kernels]") {
  for (const double h : {0.013, 1.0, 37.0}) {
    check_kernel<CubicSpline<2>>(h);
    check_kernel<WendlandC2<2>>(h);
    check_kernel<Spiky<2>>(h);
  }
  // The spiky kernel's static form is eq 8, as the fixed-radius one.
  CHECK(Spiky<2>::w(0.3, 0.2) == Approx(Spiky<2>(0.2).w(0.3)).epsilon(1e-14));
  // The cubic spline is smooth where its pieces join (q = 1).
  CHECK(CubicSpline<2>::w(1.0 - 1e-12, 1.0) == Approx(CubicSpline<2>::w(1.0 + 1e-12, 1.0)));
  CHECK(CubicSpline<2>::dw_dr(1.0 - 1e-12, 1.0) ==
        Approx(CubicSpline<2>::dw_dr(1.0 + 1e-12, 1.0)));
}
