// Manning friction on a slab of uniform water sliding down a long channel: in the slab's
// middle, far from its ends, the depth stays h and the velocity follows the closed form of
// du/dt = -g n^2 |u| u / h^(4/3):
//   u(t) = u0 / (1 + k u0 t),  k = g n^2 / h^(4/3).
// The friction reads the particle depth, so a depth summed too deep makes the water too fast:
// under the seed scheme (eq 7 sums 15 % deep) the slab keeps 0.582 m/s at 60 s against
// 0.545 m/s (+6.8 %, docs/verification.md).

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <functional>

#include "swemps/scenario/build.hpp"
#include "swemps/scenario/scenario.hpp"

using namespace swemps;

namespace {

// 400 m x 10 m of water 0.5 m deep at 2 m/s, 2 m spacing, slip walls along both sides and open
// ends: the rarefactions from the ends travel sqrt(g h) = 2.2 m/s into the slab, so its middle
// 80 m stay uniform for the 60 s.
constexpr const char* kSlab = R"({
  "name": "manning-slab", "end_time": 60,
  "domain": {"x_min": -100, "x_max": 700, "y_min": 0, "y_max": 10},
  "water": [{"rectangle": {"x_min": 0, "x_max": 400, "y_min": 0, "y_max": 10},
             "depth": 0.5, "spacing": 2, "velocity": [2, 0]}],
  "walls": [{"polyline": [[-100, 0], [700, 0]]}, {"polyline": [[700, 10], [-100, 10]]}],
  "friction": {"manning_n": 0.03},
  "output": {"path": "slab.nc"}
})";

struct SlabMiddle {
  double u_m_s = 0.0, depth_m = 0.0;
  std::size_t particles = 0;
};

SlabMiddle run_slab(const std::function<void(scenario::Scenario&)>& adjust) {
  auto scene = scenario::parse(kSlab, std::filesystem::temp_directory_path(), "slab");
  adjust(scene);
  auto sim = scenario::make_simulation(scene);
  sim.advance_to(scene.end_time_s);
  sim.refresh();
  const auto& p = sim.particles();
  // The slab's middle: its centre has moved with it, about 60 m in the 60 s.
  double centre = 0.0;
  for (std::size_t i = 0; i < p.fluid_count(); ++i) centre += p.x[i];
  centre /= static_cast<double>(p.fluid_count());
  SlabMiddle out;
  for (std::size_t i = 0; i < p.fluid_count(); ++i) {
    if (std::abs(p.x[i] - centre) > 40.0) continue;
    out.u_m_s += p.u[i];
    out.depth_m += p.depth[i];
    ++out.particles;
  }
  out.u_m_s /= static_cast<double>(out.particles);
  out.depth_m /= static_cast<double>(out.particles);
  return out;
}

}  // namespace

TEST_CASE("Manning friction slows a uniform slab as the closed form says", "[verification]") {
  const double k = 9.81 * 0.03 * 0.03 / std::pow(0.5, 4.0 / 3.0);
  const double exact = 2.0 / (1.0 + k * 2.0 * 60.0);  // 0.545 m/s
  const auto conservative = run_slab([](scenario::Scenario&) {});
  INFO("default scheme: u " << conservative.u_m_s << " m/s (exact " << exact << "), depth "
                            << conservative.depth_m << " m over " << conservative.particles
                            << " particles");
  REQUIRE(conservative.particles > 100);
  // The default scheme sums uniform water to its depth (measured 0.5000 m, u within 0.01 %
  // of the closed form); the issue's bar is 1 %, and the friction update is exact for a
  // constant depth (tests/swe/test_effects.cpp), so anything past it is a wrong depth.
  CHECK(conservative.depth_m == Approx(0.5).epsilon(0.005));
  CHECK(conservative.u_m_s == Approx(exact).epsilon(0.01));

  // The seed scheme's deep eq 7 depth is what this guards against: it must fail the bar.
  const auto seed =
      run_slab([](scenario::Scenario& s) { s.numerics.scheme = swe::SchemeKind::seed; });
  INFO("seed scheme: u " << seed.u_m_s << " m/s, depth " << seed.depth_m << " m");
  CHECK(seed.u_m_s > exact * 1.05);
}
