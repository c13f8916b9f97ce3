#pragma once
// A solitary wave as a tsunami benchmark starts it (NTHMP benchmark problem 1, after
// Synolakis 1987 and Titov & Synolakis 1995): over still water of depth d, a wave of height H
// whose crest runs along a straight line, travelling in `direction`,
//   eta(s) = H sech^2(gamma s / d),   gamma = sqrt(3 H / (4 d)),
//   u(s)   = sqrt(g / d) eta(s)       along `direction`,
// with s the signed distance from the crest line along `direction`. The velocity is the
// long-wave relation of a wave moving one way; the shallow-water equations have no solitary
// wave of permanent form, so the wave steepens as it travels (docs/tsunami.md).
// Pure arithmetic: the scene module sets it on the particles where water is seeded.

#include <array>

namespace swemps::tsunami {

struct SolitaryWaveSpec {
  double height_m = 0.0;                      // H > 0
  double still_depth_m = 0.0;                 // d > H
  std::array<double, 2> crest_m{0.0, 0.0};    // a point on the crest line (x, y)
  std::array<double, 2> direction{1.0, 0.0};  // any non-zero vector; normalised here
};

class SolitaryWave {
 public:
  // Throws std::invalid_argument for H <= 0, d <= H, a zero or non-finite direction, or a
  // non-finite crest or gravity <= 0.
  SolitaryWave(const SolitaryWaveSpec& spec, double gravity_m_s2);

  // The surface's rise above the still level at (x, y), m.
  double elevation(double x_m, double y_m) const;
  // The water's velocity (u, v) at (x, y), m/s.
  std::array<double, 2> velocity(double x_m, double y_m) const;

  // L = arccosh(sqrt(20)) d / gamma: where the wave has fallen to 5 % of its height, the
  // half-length benchmark problem 1 places the crest by (X1 = X0 + L).
  double half_length_m() const;
  // sqrt(g (d + H)): the long-wave speed of the crest the benchmarks quote.
  double crest_speed_m_s() const;

 private:
  double height_m_, depth_m_, gamma_over_depth_, gravity_m_s2_;
  std::array<double, 2> crest_m_, direction_;
};

}  // namespace swemps::tsunami
