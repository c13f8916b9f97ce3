// Stoker's wet dam break as the SWASHES benchmark sets it: a 10 m channel, still water 5 mm
// deep upstream of a dam at 5 m and 1 mm downstream, compared at t = 6 s, 0.02 m spacing.
// verification/stoker.hpp has the exact solution (rarefaction, middle state, shock).

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "swemps/scenario/build.hpp"
#include "swemps/scenario/scenario.hpp"
#include "swemps/verification/stoker.hpp"

using namespace swemps;

namespace {

constexpr double kSpacing = 0.02, kWidth = 5 * kSpacing, kTime = 6.0;

struct StokerRun {
  verification::StokerErrors errors{};
  double mean_depth_l1 = 0.0;  // sum |h - h_S| / sum h_S over the whole channel
};

StokerRun run_stoker(const std::string& numerics) {
  char text[2048];
  std::snprintf(text, sizeof text, R"({"name": "stoker", "end_time": %g, "numerics": %s,
    "domain": {"x_min": 0, "x_max": 10, "y_min": 0, "y_max": %g},
    "water": [{"rectangle": {"x_min": 0, "x_max": 5, "y_min": 0, "y_max": %g},
               "depth": 0.005, "spacing": %g},
              {"rectangle": {"x_min": 5, "x_max": 10, "y_min": 0, "y_max": %g},
               "depth": 0.001, "spacing": %g}],
    "walls": [{"polyline": [[0, 0], [10, 0], [10, %g], [0, %g], [0, 0]]}],
    "output": {"path": "stoker.nc"}})",
                kTime, numerics.c_str(), kWidth, kWidth, kSpacing, kWidth, kSpacing, kWidth,
                kWidth);
  auto scene = scenario::parse(text, std::filesystem::temp_directory_path(), "stoker");
  auto sim = scenario::make_simulation(scene);
  sim.advance_to(kTime);
  sim.refresh();
  const verification::StokerProblem problem{5.0, 0.005, 0.001, scene.numerics.gravity_m_s2};
  const auto profile = verification::channel_profile(sim.particles(), sim.kernel(),
                                                     {0.0, 10.0, 0.0, kWidth}, kSpacing / 4.0);
  StokerRun out;
  out.errors = verification::compare_with_stoker(problem, profile, kTime);
  double difference = 0.0, exact_sum = 0.0;
  for (std::size_t k = 0; k < profile.depth_m.size(); ++k) {
    const double x = profile.x0_m + profile.dx_m * static_cast<double>(k);
    const double exact = verification::stoker_depth(problem, x, kTime);
    difference += std::abs(profile.depth_m[k] - exact);
    exact_sum += exact;
  }
  out.mean_depth_l1 = difference / exact_sum;
  return out;
}

}  // namespace

TEST_CASE("Stoker's wet dam break (SWASHES, 5 mm / 1 mm) at 0.02 m", "[verification]") {
  const auto conservative = run_stoker("{}");
  const auto& e = conservative.errors;
  INFO("default scheme: L1 " << e.l1 << " of h_l over the disturbed region, "
                             << conservative.mean_depth_l1 << " of the mean depth; shock at "
                             << e.shock_x_m << " m (exact " << e.exact_shock_x_m << " m)");
  // Issue 17's bars: L1 of the depth under 3 % of the mean depth and the shock within two
  // spacings of Stoker's. Measured 0.35 % and 0.013 m (0.64 spacings); L1 over the disturbed
  // region 0.63 % of h_l (0.73 % without particle shifting), bounded about 12 % above that, as
  // the deterministic Ritter runs are.
  CHECK(conservative.mean_depth_l1 < 0.03);
  CHECK(std::abs(e.shock_x_m - e.exact_shock_x_m) < 2.0 * kSpacing);
  CHECK(e.l1 < 0.0071);

  // The seed scheme with its summation gradient, for the record of docs/verification.md:
  // measured 2.6 % of the mean depth, the shock 0.39 m (20 spacings) behind.
  const auto seed = run_stoker(R"({"scheme": "seed", "gradient": "summation"})");
  INFO("seed scheme: L1 " << seed.errors.l1 << ", " << seed.mean_depth_l1
                          << " of the mean depth; shock at " << seed.errors.shock_x_m << " m");
  CHECK(seed.mean_depth_l1 > conservative.mean_depth_l1);
  CHECK(std::abs(seed.errors.shock_x_m - seed.errors.exact_shock_x_m) > 2.0 * kSpacing);
}
