// The solitary wave of NTHMP benchmark problem 1: its profile, its velocity and the lengths
// the benchmark places it by.

#include <catch2/catch.hpp>
#include <cmath>
#include <stdexcept>

#include "swemps/tsunami/solitary_wave.hpp"

using swemps::tsunami::SolitaryWave;
using swemps::tsunami::SolitaryWaveSpec;

TEST_CASE("a solitary wave has the benchmark's profile and velocity", "[tsunami]") {
  // BP1: H/d = 0.019 at d = 1 m, travelling towards -x from X1 = 19.85 + L.
  const SolitaryWaveSpec spec{0.019, 1.0, {38.0968, 0.0}, {-2.0, 0.0}};
  const SolitaryWave wave(spec, 9.81);
  const double gamma = std::sqrt(3.0 * 0.019 / 4.0);
  // L = arccosh(sqrt(20)) / gamma d, where the wave is a twentieth of its height.
  CHECK(wave.half_length_m() == Approx(std::acosh(std::sqrt(20.0)) / gamma).epsilon(1e-14));
  CHECK(wave.half_length_m() == Approx(18.24756).epsilon(1e-6));
  CHECK(wave.elevation(38.0968, 7.0) == Approx(0.019).epsilon(1e-15));  // along the crest line
  CHECK(wave.elevation(38.0968 - wave.half_length_m(), 0.0) == Approx(0.019 / 20).epsilon(1e-12));
  CHECK(wave.elevation(38.0968 + wave.half_length_m(), 0.0) == Approx(0.019 / 20).epsilon(1e-12));
  const double x = 30.0, s = x - 38.0968;
  const double eta = 0.019 / std::pow(std::cosh(gamma * s), 2);
  CHECK(wave.elevation(x, -3.0) == Approx(eta).epsilon(1e-14));
  // u = sqrt(g/d) eta along the direction, here -x (the direction is normalised).
  const auto u = wave.velocity(x, 0.0);
  CHECK(u[0] == Approx(-std::sqrt(9.81) * eta).epsilon(1e-14));
  CHECK(u[1] == 0.0);
  CHECK(wave.crest_speed_m_s() == Approx(std::sqrt(9.81 * 1.019)).epsilon(1e-15));
  // Far from the crest the surface is still, and cosh's overflow gives 0, not NaN.
  CHECK(wave.elevation(1e6, 0.0) == 0.0);
}

TEST_CASE("a solitary wave travelling at an angle is a straight crest across it", "[tsunami]") {
  const SolitaryWave wave({0.1, 2.0, {0.0, 0.0}, {1.0, 1.0}}, 9.81);
  // Points on the line x + y = 0 are on the crest; the velocity is along (1, 1) / sqrt 2.
  CHECK(wave.elevation(5.0, -5.0) == Approx(0.1).epsilon(1e-15));
  const double off = wave.elevation(3.0, 3.0);  // s = 6 / sqrt 2 along the direction
  CHECK(off ==
        Approx(0.1 / std::pow(std::cosh(std::sqrt(0.3 / 8.0) / 2.0 * 6.0 / std::sqrt(2.0)), 2))
            .epsilon(1e-14));
  const auto u = wave.velocity(3.0, 3.0);
  CHECK(u[0] == Approx(u[1]).epsilon(1e-15));
  CHECK(std::hypot(u[0], u[1]) == Approx(std::sqrt(9.81 / 2.0) * off).epsilon(1e-14));
}

TEST_CASE("a solitary wave refuses what has no such wave", "[tsunami]") {
  CHECK_THROWS_AS(SolitaryWave({0.0, 1.0, {0, 0}, {1, 0}}, 9.81), std::invalid_argument);
  CHECK_THROWS_AS(SolitaryWave({1.0, 1.0, {0, 0}, {1, 0}}, 9.81), std::invalid_argument);
  CHECK_THROWS_AS(SolitaryWave({0.1, 1.0, {0, 0}, {0, 0}}, 9.81), std::invalid_argument);
  CHECK_THROWS_AS(SolitaryWave({0.1, 1.0, {NAN, 0}, {1, 0}}, 9.81), std::invalid_argument);
  CHECK_THROWS_AS(SolitaryWave({0.1, 1.0, {0, 0}, {1, 0}}, 0.0), std::invalid_argument);
}
