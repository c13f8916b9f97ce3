// The members of an ensemble (combinations of listed values, sampled draws) and how their
// maximum-depth maps combine.

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include "swemps/ensemble/ensemble.hpp"

using namespace swemps::ensemble;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

Knob listed(const std::string& pointer, std::vector<std::string> values) {
  Knob k;
  k.pointer = k.name = pointer;
  k.values = std::move(values);
  return k;
}

Knob sampled(const std::string& pointer, double low, double high,
             Distribution distribution = Distribution::uniform) {
  Knob k;
  k.pointer = k.name = pointer;
  k.low = low;
  k.high = high;
  k.distribution = distribution;
  return k;
}

}  // namespace

TEST_CASE("listed knobs make every combination, the first knob slowest", "[ensemble]") {
  Ensemble e;
  e.knobs = {listed("/a", {"1", "2", "3"}), listed("/b", {"\"x\"", "[0, 1]"})};
  REQUIRE(member_count(e) == 6);
  const auto m = members(e);
  REQUIRE(m.size() == 6);
  const std::vector<std::vector<std::string>> expected{{"1", "\"x\""}, {"1", "[0, 1]"},
                                                       {"2", "\"x\""}, {"2", "[0, 1]"},
                                                       {"3", "\"x\""}, {"3", "[0, 1]"}};
  for (std::size_t i = 0; i < m.size(); ++i) {
    CHECK(m[i].index == i);
    CHECK(m[i].values == expected[i]);
  }
}

TEST_CASE("the draws are fixed by the seed, on any machine", "[ensemble]") {
  // The generator, the strata's shuffle and the mapping to [0, 1) are integer arithmetic and
  // one exact scaling:
  // these values are what every build must give (a change would silently change every
  // user's sampled ensemble).
  const auto lhs = unit_draws(4, 2, 7, Sampling::latin_hypercube);
  const std::vector<std::vector<double>> expected_lhs{{0.27127983885879242, 0.062862309782845432},
                                                      {0.88016025197627823, 0.6469620376276769},
                                                      {0.071701156680258088, 0.77544064488060482},
                                                      {0.63520386679925744, 0.40821546813126069}};
  CHECK(lhs == expected_lhs);
  const auto random = unit_draws(2, 1, 7, Sampling::random);
  CHECK(random == std::vector<std::vector<double>>{{0.61378156669330797}, {0.34983053033023204}});
  // Another seed, other draws.
  CHECK(unit_draws(4, 2, 8, Sampling::latin_hypercube) != lhs);
  // A knob added after the others leaves their draws as they were.
  const auto three = unit_draws(4, 3, 7, Sampling::latin_hypercube);
  for (std::size_t s = 0; s < 4; ++s) {
    CHECK(three[s][0] == lhs[s][0]);
    CHECK(three[s][1] == lhs[s][1]);
  }
}

TEST_CASE("a Latin hypercube puts one draw in each stratum of every knob", "[ensemble]") {
  for (const std::size_t n : {1U, 2U, 7U, 50U}) {
    const auto draws = unit_draws(n, 3, 12345, Sampling::latin_hypercube);
    for (std::size_t k = 0; k < 3; ++k) {
      std::set<std::size_t> strata;
      for (std::size_t s = 0; s < n; ++s) {
        const double u = draws[s][k];
        REQUIRE(u >= 0.0);
        REQUIRE(u < 1.0);
        strata.insert(static_cast<std::size_t>(u * static_cast<double>(n)));
      }
      CHECK(strata.size() == n);
    }
  }
  // Independent draws need not: with 50 draws some stratum of 50 is all but sure to be empty
  // (the chance that none is, 50!/50^50, is about 3e-21).
  const auto random = unit_draws(50, 1, 12345, Sampling::random);
  std::set<std::size_t> strata;
  for (const auto& d : random) strata.insert(static_cast<std::size_t>(d[0] * 50.0));
  CHECK(strata.size() < 50);
}

TEST_CASE("sampled knobs map the draws into their ranges; every combination shares them",
          "[ensemble]") {
  Ensemble e;
  e.knobs = {listed("/q", {"1000", "2000"}), sampled("/n", 0.01, 0.1, Distribution::log_uniform),
             sampled("/h", 2.0, 3.0)};
  e.samples = 5;
  e.seed = 99;
  REQUIRE(member_count(e) == 10);
  const auto m = members(e);
  const auto draws = unit_draws(5, 2, 99, Sampling::latin_hypercube);
  for (std::size_t i = 0; i < m.size(); ++i) {
    CHECK(m[i].values[0] == (i < 5 ? "1000" : "2000"));
    const double n = std::stod(m[i].values[1]), h = std::stod(m[i].values[2]);
    const auto& d = draws[i % 5];
    // log-uniform: the draw is the fraction of the range in log(n).
    CHECK(std::log(n / 0.01) / std::log(10.0) == Approx(d[0]).margin(1e-12));
    CHECK(h == Approx(2.0 + d[1]).margin(1e-12));
    CHECK(n >= 0.01);
    CHECK(n < 0.1);
    // The paired members of the other peak have the same sampled values, text and all.
    CHECK(m[i].values[1] == m[(i + 5) % 10].values[1]);
    CHECK(m[i].values[2] == m[(i + 5) % 10].values[2]);
  }
}

TEST_CASE("member folders sort in index order", "[ensemble]") {
  CHECK(member_folder_name(0, 1) == "member-0");
  CHECK(member_folder_name(7, 15) == "member-07");
  CHECK(member_folder_name(9, 10) == "member-9");
  CHECK(member_folder_name(10, 101) == "member-010");
}

TEST_CASE("members' maximum depths combine into counts, probabilities, mean and envelope",
          "[ensemble]") {
  // Four cells: wet in all three members; wet in one, dry in one, no data in one; exactly at a
  // threshold in one; no data in any member.
  const std::vector<std::vector<double>> maps{
      {0.5, 0.2, 0.3, kNaN}, {1.5, 0.0, 0.1, kNaN}, {0.05, kNaN, 0.3, kNaN}};
  const Products p = combine(maps, {0.1, 0.3, 1.0});
  REQUIRE(p.members == 3);
  // Cell 0: 0.5, 1.5, 0.05.
  CHECK(p.exceedance_count[0][0] == 2.0);
  CHECK(p.exceedance_count[1][0] == 2.0);
  CHECK(p.exceedance_count[2][0] == 1.0);
  CHECK(p.exceedance_probability[0][0] == Approx(2.0 / 3.0));
  CHECK(p.exceedance_probability[2][0] == Approx(1.0 / 3.0));
  CHECK(p.mean_max_depth[0] == Approx(2.05 / 3.0));
  CHECK(p.max_depth_envelope[0] == 1.5);
  // Cell 1: no data counts as dry.
  CHECK(p.exceedance_count[0][1] == 1.0);
  CHECK(p.exceedance_probability[0][1] == Approx(1.0 / 3.0));
  CHECK(p.mean_max_depth[1] == Approx(0.2 / 3.0));
  CHECK(p.max_depth_envelope[1] == 0.2);
  // Cell 2: depth equal to a threshold does not exceed it.
  CHECK(p.exceedance_count[0][2] == 2.0);
  CHECK(p.exceedance_count[1][2] == 0.0);
  CHECK(p.exceedance_probability[1][2] == 0.0);
  // Cell 3: no data anywhere.
  for (std::size_t j = 0; j < 3; ++j) {
    CHECK(std::isnan(p.exceedance_count[j][3]));
    CHECK(std::isnan(p.exceedance_probability[j][3]));
  }
  CHECK(std::isnan(p.mean_max_depth[3]));
  CHECK(std::isnan(p.max_depth_envelope[3]));
}

TEST_CASE("maps that cannot combine are refused", "[ensemble]") {
  CHECK_THROWS_AS(combine({}, {0.1}), std::invalid_argument);
  const std::vector<std::vector<double>> uneven{{0.1, 0.2}, {0.1}};
  CHECK_THROWS_AS(combine(uneven, {0.1}), std::invalid_argument);
}

TEST_CASE("members added one at a time give what all at once give, bit for bit", "[ensemble]") {
  const std::vector<std::vector<double>> maps{
      {0.31, kNaN, 1.7}, {0.12, 0.4, 0.0}, {2.5, 0.05, kNaN}, {0.7, 0.3, 0.9}};
  const Products all = combine(maps, {0.1, 0.5});
  ProductsAccumulator one_by_one(3, {0.1, 0.5});
  for (const auto& map : maps) one_by_one.add(map);
  CHECK(one_by_one.members() == 4);
  const Products p = one_by_one.finish();
  CHECK(p.exceedance_count == all.exceedance_count);
  CHECK(p.exceedance_probability == all.exceedance_probability);
  CHECK(p.mean_max_depth == all.mean_max_depth);
  CHECK(p.max_depth_envelope == all.max_depth_envelope);
  CHECK(p.mean_max_depth[0] == (((0.31 + 0.12) + 2.5) + 0.7) / 4.0);  // in member order
  CHECK_THROWS_AS(one_by_one.add(std::vector<double>(2, 0.0)), std::invalid_argument);
  CHECK_THROWS_AS(ProductsAccumulator(3, {0.1}).finish(), std::invalid_argument);
}

TEST_CASE("one member alone is the member the whole list has", "[ensemble]") {
  Ensemble e;
  e.knobs = {sampled("/n", 0.01, 0.1), listed("/q", {"1", "2", "3"}), sampled("/h", 1.0, 2.0),
             listed("/z", {"\"a\"", "\"b\""})};
  e.samples = 4;
  e.seed = 3;
  const auto all = members(e);
  REQUIRE(all.size() == 24);
  for (std::size_t i = 0; i < all.size(); ++i) {
    const Member m = member(e, i);
    CHECK(m.index == i);
    CHECK(m.values == all[i].values);
  }
  CHECK(all[5].values[1] == "1");  // combination 1: q slowest, z fastest
  CHECK(all[5].values[3] == "\"b\"");
  CHECK_THROWS_AS(member(e, 24), std::out_of_range);
}
